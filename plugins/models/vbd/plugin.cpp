// vbd plugin: descriptor, parameter schema and the SDK glue around VbdModel.
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "tacta/sdk/model.hpp"
#include "vbd_model.hpp"

namespace tacta::models::vbd {
namespace {

using tacta::models::load_state_blob;
using tacta::models::save_state_blob;
using tacta::models::StateHeader;

class VbdPlugin {
 public:
  static constexpr const char* kName = "vbd";
  static constexpr const char* kDescription =
      "Vertex Block Descent: implicit Euler by per-vertex 3x3 Newton steps over a graph "
      "colouring, matrix-free, parallel per colour (corotational or Neo-Hookean tets)";
  static constexpr uint32_t kVersion = 10000;
  // Forces depend on the deformation alone and sum to zero over each element. Colouring, rest
  // data and warm starts all come from create() and begin(), so a rebuild on a cut mesh is exact.
  static constexpr uint32_t kClaims = TACTA_MODEL_CLAIM_ROTATION_INVARIANT |
                                      TACTA_MODEL_CLAIM_MOMENTUM | TACTA_MODEL_CLAIM_TOPOLOGY_EDITS;
  // How far each step converges; the energy and the guess decide buffers and history.
  static constexpr const char* kLiveParams = "iterations|chebyshev_rho";
  static constexpr std::array<tacta_param_spec, 4> kParams = {
      sdk::choice_param("energy", "corotational|neo_hookean", 0,
                        "tet energy: corotational (corotational_fem's, rotations taken at the "
                        "step's start) or compressible Neo-Hookean (hyperelastic's)"),
      sdk::int_param("iterations", 10, 1, 1000,
                     "VBD iterations per step (each one Newton step per vertex, colour by "
                     "colour); more: closer to the exact implicit Euler step"),
      sdk::real_param("chebyshev_rho", "", 0.85, 0.0, 0.999,
                      "spectral radius estimate of the Chebyshev acceleration over the "
                      "iterations; 0: none (0.9 and above can gain energy)"),
      sdk::choice_param("initial_guess", "adaptive|inertia|previous", 0,
                        "first iterate: adaptive (x + h v + h^2 times the part of the last "
                        "acceleration along the external one), inertia (x + h v + h^2 f_ext / m) "
                        "or previous (x + h v)"),
  };

  explicit VbdPlugin(const tacta_model_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    Options options;
    // An engine older than the host services passes a shorter setup: no workers then.
    if (setup.struct_size >= offsetof(tacta_model_setup, host) + sizeof setup.host)
      options.host = setup.host;
    options.energy = static_cast<Energy>(params.choice("energy"));
    options.iterations = params.integer("iterations");
    options.chebyshev_rho = params.real("chebyshev_rho");
    options.initial_guess = static_cast<InitialGuess>(params.choice("initial_guess"));
    const uint32_t n = setup.mesh->node_count;
    model_ = std::make_unique<VbdModel>(
        *setup.mesh, *setup.material, std::span<const double>(setup.masses, n),
        setup.fixed ? std::span<const uint8_t>(setup.fixed, n) : std::span<const uint8_t>(),
        options);
  }
  uint32_t step(tacta_body_state& state, double dt) noexcept { return model_->step(state, dt); }
  void begin(const tacta_body_state& state, double dt) noexcept { model_->begin(state, dt); }
  double elastic_energy(const double* x) noexcept { return model_->elastic_energy(x); }
  void internal_forces(const double* x, double* f) noexcept { model_->internal_forces(x, f); }
  size_t save_state(void* bytes, size_t capacity) noexcept {
    return save_state_blob(state_header(), bytes, capacity,
                           [&](StateIo& io) { model_->state_fields(io); });
  }
  void load_state(const void* bytes, size_t size) {
    load_state_blob(state_header(), bytes, size, [&](StateIo& io) { model_->state_fields(io); });
  }
  uint32_t counters(tacta_model_counter* out, uint32_t capacity) noexcept {
    const std::array<tacta_model_counter, 2> own{{
        {"colours", static_cast<double>(model_->colour_count())},
        {"skipped_vertex_updates", static_cast<double>(model_->skipped_updates())},
    }};
    return sdk::copy_counters(own.data(), static_cast<uint32_t>(own.size()), out, capacity);
  }
  std::string describe() const {
    uint32_t free = 0;
    for (uint32_t c = 0; c < model_->colour_count(); ++c)
      free += static_cast<uint32_t>(model_->colour(c).size());
    return std::to_string(model_->colour_count()) + " colours over " + std::to_string(free) +
           " free vertices";
  }
  // iterations and chebyshev_rho only: the energy and the initial guess decide what step()
  // keeps between steps.
  void set_param(uint32_t index, const tacta_param_value& value) {
    if (index >= kParams.size())
      throw std::invalid_argument("vbd: no parameter with index " + std::to_string(index));
    const tacta_param_spec& spec = kParams[index];
    const std::string_view name = spec.name;
    if (name != "iterations" && name != "chebyshev_rho")
      throw std::invalid_argument("vbd: '" + std::string(name) +
                                  "' cannot change while running (only iterations and "
                                  "chebyshev_rho can)");
    const double v = value.number;
    if (!(v >= spec.min_value && v <= spec.max_value) ||
        (spec.type == TACTA_PARAM_INT && v != std::floor(v)))
      throw std::invalid_argument("vbd: " + std::string(name) + " = " + std::to_string(v) +
                                  " is outside [" + std::to_string(spec.min_value) + ", " +
                                  std::to_string(spec.max_value) + "]" +
                                  (spec.type == TACTA_PARAM_INT ? " or not an integer" : ""));
    if (name == "iterations") model_->set_iterations(static_cast<int>(v));
    if (name == "chebyshev_rho") model_->set_chebyshev_rho(v);
  }

 private:
  static constexpr uint32_t kStateVersion = 1;  // VbdModel::state_fields' layout
  StateHeader state_header() const {
    return {kName, kStateVersion, model_->node_count(), model_->element_count()};
  }
  std::unique_ptr<VbdModel> model_;
};

}  // namespace
}  // namespace tacta::models::vbd

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<tacta::models::vbd::VbdPlugin>())
