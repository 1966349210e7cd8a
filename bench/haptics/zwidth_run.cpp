#include "zwidth_run.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "tacta/plugin_registry.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta::bench {

ZwidthRunner::ZwidthRunner(std::string scene, std::string work_dir, const std::string& plugin_dir)
    : scene_(std::move(scene)),
      work_dir_(std::move(work_dir)),
      plugins_(std::make_unique<PluginRegistry>()) {
  if (!plugin_dir.empty() && std::filesystem::is_directory(plugin_dir))
    plugins_->add_path(plugin_dir);
  plugins_->load();
  std::filesystem::create_directories(work_dir_);
}

ZwidthRunner::~ZwidthRunner() = default;

StabilityVerdict ZwidthRunner::run(const ZwidthCase& c, double stiffness) {
  std::ostringstream k, b;
  k << std::setprecision(17) << stiffness;
  b << std::setprecision(17) << c.coupling_damping;
  std::vector<std::string> overrides = {
      "bodies.*.model=" + c.model,
      "devices.*.coupling.stiffness=" + k.str(),
      "devices.*.coupling.damping=" + b.str(),
      std::string("devices.*.coupling.passivity=") + (c.passivity ? "true" : "false"),
      "output.trace=true",
  };
  overrides.insert(overrides.end(), c.overrides.begin(), c.overrides.end());
  RegistrySchemas schemas(*plugins_);
  const SceneDesc scene = load_scene(scene_, schemas, overrides);
  Simulation simulation(scene, *plugins_);
  RunOptions options;
  options.out_dir = work_dir_;
  options.realtime = false;
  const RunResult result = simulation.run(options);
  bool fault = result.faults > 0;
  for (const BodyResult& body : result.bodies) fault = fault || body.frozen;
  const std::vector<TraceSample> trace = read_trace_csv(work_dir_ + "/trace.csv");
  return judge_stability(trace, criterion, fault);
}

ZwidthResult ZwidthRunner::largest_stable(const ZwidthCase& c, const ZwidthSearch& search) {
  ZwidthResult out;
  StabilityVerdict high = run(c, search.k_max);
  ++out.runs;
  if (high.stable) {
    out.largest_stable = search.k_max;
    out.at_largest_stable = high;
    return out;
  }
  StabilityVerdict low = run(c, search.k_min);
  ++out.runs;
  if (!low.stable) {
    out.smallest_unstable = search.k_min;
    out.unstable_reason = low.reason;
    return out;
  }
  double k_stable = search.k_min, k_unstable = search.k_max;
  std::string unstable_reason = high.reason;
  while (k_unstable / k_stable > search.resolution) {
    const double k = std::sqrt(k_stable * k_unstable);  // midpoint in log(k)
    StabilityVerdict v = run(c, k);
    ++out.runs;
    if (v.stable) {
      k_stable = k;
      low = v;
    } else {
      k_unstable = k;
      unstable_reason = v.reason;
    }
  }
  out.largest_stable = k_stable;
  out.smallest_unstable = k_unstable;
  out.at_largest_stable = low;
  out.unstable_reason = unstable_reason;
  return out;
}

}  // namespace tacta::bench
