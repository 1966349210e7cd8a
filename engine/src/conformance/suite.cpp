// The conformance suite: every check in order, a plugin's refusal or exception turned into a
// failed check so one bad entry does not hide the others.
#include <exception>
#include <functional>

#include "conformance/checks.hpp"
#include "tacta/model_api.h"

namespace tacta::conformance {

namespace {

CheckResult guarded(const char* name, const std::function<CheckResult()>& check) {
  try {
    return check();
  } catch (const std::exception& e) {
    return {name, e.what(), Verdict::Fail};
  }
}

}  // namespace

const char* verdict_name(Verdict verdict) {
  switch (verdict) {
    case Verdict::Pass: return "PASS";
    case Verdict::Fail: return "FAIL";
    case Verdict::Skip: return "SKIP";
  }
  return "?";
}

std::vector<CheckResult> check_model(const tacta_descriptor& model, const AllocationProbe& probe) {
  std::vector<CheckResult> results;
  if (model.kind != TACTA_KIND_MODEL) {
    results.push_back(
        {"model kind",
         std::string("'") + model.name + "' is a " + tacta_kind_name(model.kind) + " plugin",
         Verdict::Fail});
    return results;
  }
  results.push_back(check_schema(model));
  const std::pair<const char*, std::function<CheckResult()>> checks[] = {
      {"force at rest", [&] { return check_force_at_rest(model); }},
      {"stretch response", [&] { return check_stretch_response(model); }},
      {"rigid translation", [&] { return check_rigid_translation(model); }},
      {"rigid rotation", [&] { return check_rigid_rotation(model); }},
      {"net internal force", [&] { return check_net_force(model); }},
      {"no allocation in step", [&] { return check_step_allocations(model, probe); }},
      {"NaN input reported", [&] { return check_nan_reported(model); }},
      {"step on a worker thread", [&] { return check_worker_thread(model); }},
      {"live parameters", [&] { return check_live_params(model); }},
      {"checkpoint", [&] { return check_checkpoint(model); }},
      {"topology edits", [&] { return check_topology_edits(model); }},
  };
  for (const auto& [name, check] : checks) results.push_back(guarded(name, check));
  return results;
}

}  // namespace tacta::conformance
