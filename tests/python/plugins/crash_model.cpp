// Test plugin for the sweep tests (tests/python/test_sweep.py): a model that holds its nodes
// still and, from step `after_steps` on, either dies of SIGSEGV (a plugin that segfaults) or
// never returns (a run that hangs). Built into a test-only folder, never installed.
#include <array>
#include <chrono>
#include <csignal>
#include <thread>

#include "tacta/sdk/model.hpp"

namespace {

class CrashModel {
 public:
  static constexpr const char* kName = "test_crash";
  static constexpr const char* kDescription = "segfaults or hangs after some steps (test only)";
  static constexpr uint32_t kVersion = 1;
  static constexpr std::array<tacta_param_spec, 2> kParams{
      tacta::sdk::choice_param("fault", "segfault|hang|none", 0, "what happens at after_steps"),
      tacta::sdk::int_param("after_steps", 10, 0, 1000000, "steps run normally first"),
  };

  explicit CrashModel(const tacta_model_setup& setup) {
    const tacta::sdk::Params params(kParams, setup.params, setup.param_count);
    fault_ = params.choice("fault");
    after_ = params.integer("after_steps");
  }

  uint32_t step(tacta_body_state&, double) noexcept {
    if (steps_++ >= after_) {
      if (fault_ == 0) std::raise(SIGSEGV);
      while (fault_ == 1) std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    return TACTA_STEP_OK;
  }

  double elastic_energy(const double*) noexcept { return 0.0; }

 private:
  int fault_ = 0;
  int after_ = 0;
  int steps_ = 0;
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<CrashModel>())
