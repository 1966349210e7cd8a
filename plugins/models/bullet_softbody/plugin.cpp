// bullet_softbody plugin: descriptor, parameter schema and the SDK glue around BulletSoftBody.
#include <array>
#include <memory>
#include <span>

#include "bullet_softbody.hpp"
#include "tacta/sdk/model.hpp"

namespace tacta::models::bullet {
namespace {

class BulletSoftBodyPlugin {
 public:
  static constexpr const char* kName = "bullet_softbody";
  static constexpr const char* kDescription =
      "Bullet's btSoftBody (links and tetras, position-based) as a reference peer; not for haptics";
  static constexpr uint32_t kVersion = 10000;
  // A reference peer (Bullet's position-based links): no claim about its forces.
  static constexpr uint32_t kClaims = 0;
  static constexpr std::array<tacta_param_spec, 3> kParams = {
      sdk::int_param("position_iterations", 10, 1, 200,
                     "Bullet position-solver iterations per step (m_cfg.piterations)"),
      sdk::real_param("stiffness_override", "", 0.0, 0.0, 1.0,
                      "Bullet kLST in (0, 1]; 0 derives it from E (docs/VALIDATION.md)"),
      sdk::bool_param("bending", false, "add Bullet's distance-2 bending links"),
  };

  explicit BulletSoftBodyPlugin(const tacta_model_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    Options options;
    options.position_iterations = params.integer("position_iterations");
    options.stiffness_override = params.real("stiffness_override");
    options.bending = params.flag("bending");
    const uint32_t n = setup.mesh->node_count;
    body_ = std::make_unique<BulletSoftBody>(
        *setup.mesh, *setup.material, std::span<const double>(setup.masses, n),
        setup.fixed ? std::span<const uint8_t>(setup.fixed, n) : std::span<const uint8_t>(),
        setup.dt, options);
  }
  uint32_t step(tacta_body_state& state, double dt) noexcept { return body_->step(state, dt); }

 private:
  std::unique_ptr<BulletSoftBody> body_;
};

}  // namespace
}  // namespace tacta::models::bullet

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<tacta::models::bullet::BulletSoftBodyPlugin>())
