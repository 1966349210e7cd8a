// bullet_softbody plugin: descriptor, parameter schema and the SDK glue around BulletSoftBody.
#include <array>
#include <memory>
#include <span>
#include <string>

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
  // A reference peer (Bullet's position-based links): no claim about its forces. No history:
  // step() writes every node's x, q (the predicted start) and v into Bullet and clears its
  // forces before it steps; what Bullet derives from them (links' constants, bounds, normals) it
  // recomputes each step, and its world steps with a fixed substep, accumulating no time.
  static constexpr uint32_t kClaims = TACTA_MODEL_CLAIM_NO_HISTORY;
  static constexpr std::array<tacta_param_spec, 4> kParams = {
      sdk::int_param("position_iterations", 10, 1, 200,
                     "Bullet position-solver iterations per step (m_cfg.piterations)"),
      sdk::real_param("stiffness_override", "", 0.0, 0.0, 1.0,
                      "Bullet kLST in (0, 1]; 0 derives it from E (docs/VALIDATION.md)"),
      sdk::bool_param("bending", false, "add Bullet's distance-2 bending links"),
      sdk::choice_param("stiffness_rule", "van_gelder|fem_projection", 0,
                        "spring constant per edge behind each link's kLST (as mass_spring's)"),
  };

  explicit BulletSoftBodyPlugin(const tacta_model_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    Options options;
    options.position_iterations = params.integer("position_iterations");
    options.stiffness_override = params.real("stiffness_override");
    options.bending = params.flag("bending");
    options.stiffness_rule = static_cast<StiffnessRule>(params.choice("stiffness_rule"));
    rule_ = options.stiffness_rule;
    stiffness_override_ = options.stiffness_override;
    const uint32_t n = setup.mesh->node_count;
    body_ = std::make_unique<BulletSoftBody>(
        *setup.mesh, *setup.material, std::span<const double>(setup.masses, n),
        setup.fixed ? std::span<const uint8_t>(setup.fixed, n) : std::span<const uint8_t>(),
        setup.dt, options);
  }
  uint32_t step(tacta_body_state& state, double dt) noexcept { return body_->step(state, dt); }
  std::string describe() const {
    return std::string("link kLST ") + median_and_range(body_->link_stiffness()) +
           (stiffness_override_ > 0
                ? " (stiffness_override)"
                : std::string(" from ") + stiffness_rule_name(rule_) + " springs at the setup dt") +
           ", " + std::to_string(body_->substeps()) + " Bullet steps per step";
  }

 private:
  std::unique_ptr<BulletSoftBody> body_;
  StiffnessRule rule_ = StiffnessRule::kVanGelder;
  double stiffness_override_ = 0.0;
};

}  // namespace
}  // namespace tacta::models::bullet

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<tacta::models::bullet::BulletSoftBodyPlugin>())
