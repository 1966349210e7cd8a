// Step checks: the 1 kHz contract of model_api.h. step() allocates nothing once warm, reports a
// NaN it is handed, and gives the same state whichever thread calls it.
#include <algorithm>
#include <cmath>
#include <thread>

#include "conformance/checks.hpp"
#include "conformance/test_body.hpp"
#include "tacta/live_params.hpp"

namespace tacta::conformance {

namespace {

constexpr int kWarmUpSteps = 5;  // first-touch paths (lazy factorisations, solver workspaces)
constexpr int kCountedSteps = 20;

// A clamped cube sagging under gravity: every step does real work.
struct Sagging {
  std::unique_ptr<TestBody> body;
  std::unique_ptr<ModelInstance> model;
  NodeState state;
  double time = 0;

  explicit Sagging(const tacta_descriptor& descriptor)
      : body(make_test_body(descriptor, true)),
        model(create_model(descriptor, *body)),
        state(body->mesh.positions) {
    for (size_t i = 2; i < state.f.size(); i += 3) state.f[i] = -9.81 * body->masses[i / 3];
    const tacta_body_state view = state.view();
    model->begin(view, body->dt);
  }
  uint32_t steps(int count) noexcept {
    uint32_t bits = 0;
    for (int k = 0; k < count; ++k, time += body->dt) {
      tacta_body_state view = state.view(time);
      bits |= model->step(view, body->dt);
    }
    return bits;
  }
};

bool all_finite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

CheckResult check_step_allocations(const tacta_descriptor& model, const AllocationProbe& probe) {
  const char* name = "no allocation in step";
  if (probe.start == nullptr) return {name, "not counted: " + probe.unavailable, Verdict::Skip};
  Sagging run(model);
  run.steps(kWarmUpSteps);
  probe.start();
  const uint32_t bits = run.steps(kCountedSteps);
  const long allocations = probe.stop();
  std::string text = std::to_string(allocations) + " heap allocations in " +
                     std::to_string(kCountedSteps) + " steps after " +
                     std::to_string(kWarmUpSteps) + " warm-up steps, limit 0";
  if (bits & TACTA_STEP_FAULT_MASK)
    text += " (the steps faulted: bits " + std::to_string(bits) + ")";
  return {name, text,
          allocations == 0 && !(bits & TACTA_STEP_FAULT_MASK) ? Verdict::Pass : Verdict::Fail};
}

CheckResult check_nan_reported(const tacta_descriptor& model) {
  const char* name = "NaN input reported";
  const auto body = make_test_body(model, false);
  const auto instance = create_model(model, *body);
  NodeState s(body->mesh.positions);
  s.x[3 * body->centre_node] = std::nan("");
  tacta_body_state view = s.view();
  instance->begin(view, body->dt);
  const uint32_t bits = instance->step(view, body->dt);
  if (bits & TACTA_STEP_FAULT_MASK)
    return {name, "step returned fault bits " + std::to_string(bits), Verdict::Pass};
  // The engine checks the state after every step (body_step.cpp), so a NaN passed on is caught.
  if (!all_finite(s.x) || !all_finite(s.v))
    return {name,
            "step returned " + std::to_string(bits) +
                "; the NaN reached the new state, where the engine's finite check faults it",
            Verdict::Pass};
  return {name,
          "step returned " + std::to_string(bits) +
              " with a finite state: the NaN node was silently replaced, no one can tell",
          Verdict::Fail};
}

CheckResult check_worker_thread(const tacta_descriptor& model) {
  // Reference: created and stepped on this thread. Probe: created here, stepped half here and
  // half on another thread, as the engine's body workers do.
  Sagging here(model), moved(model);
  here.steps(2 * kCountedSteps);
  moved.steps(kCountedSteps);
  std::thread worker([&] { moved.steps(kCountedSteps); });
  worker.join();
  double worst = 0;
  for (size_t i = 0; i < here.state.x.size(); ++i)
    worst = std::max(worst, std::abs(here.state.x[i] - moved.state.x[i]));
  if (!all_finite(here.state.x)) worst = std::nan("");
  const double limit = 1e-12 * here.body->cell;
  return {"step on a worker thread",
          "max |x(this thread) - x(worker)| " + figure(worst) + " m after " +
              std::to_string(2 * kCountedSteps) + " steps, limit " + figure(limit) + " m",
          worst <= limit ? Verdict::Pass : Verdict::Fail};
}

}  // namespace tacta::conformance

namespace tacta::conformance {

CheckResult check_live_params(const tacta_descriptor& model) {
  const char* name = "live parameters";
  const std::vector<std::string> live = live_param_names(model);
  if (live.empty()) return {name, "the model lists no live parameter", Verdict::Skip};
  // Setting each live parameter to the value it already has, mid-run, must be accepted and must
  // leave the motion exactly as it was: set_param changes a limit, it does not restart the model.
  Sagging plain(model), touched(model);
  plain.steps(2 * kCountedSteps);
  touched.steps(kCountedSteps);
  for (const std::string& param : live) {
    const uint32_t index = param_index(model, param);
    std::string why;
    const tacta_param_value value{model.params[index].default_value, nullptr, nullptr, 0};
    if (!touched.model->set_param(index, value, why))
      return {name, "set_param('" + param + "') refused its own default: " + why, Verdict::Fail};
  }
  touched.steps(kCountedSteps);
  double worst = 0;
  for (size_t i = 0; i < plain.state.x.size(); ++i)
    worst = std::max(worst, std::abs(plain.state.x[i] - touched.state.x[i]));
  if (!all_finite(touched.state.x)) worst = std::nan("");
  return {name,
          std::to_string(live.size()) + " live, each set to its value mid-run: max |dx| " +
              figure(worst) + " m against the untouched run, limit 0",
          worst == 0 ? Verdict::Pass : Verdict::Fail};
}

}  // namespace tacta::conformance
