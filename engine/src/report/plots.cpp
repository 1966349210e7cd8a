// Plots: the scene's output.plots, drawn by the scripts in scripts/plots with Debian's python3
// and matplotlib. Run as child processes (no shell) after the run; a plot that fails is a warning.
#include <filesystem>

#include "run_outputs.hpp"
#include "tacta/output/plot_script.hpp"

namespace tacta {

namespace {

// The paper's corner names for the nodes of a 4-node planar square, else "node N".
std::string node_label(const SoftBody& body, uint32_t node) {
  static const char* const corners[] = {"SW", "SE", "NW", "NE"};
  if (body.shape.topology->mesh.dimension == 2 && body.node_count() == 4)
    return std::string(corners[node]) + " (node " + std::to_string(node) + ")";
  return "node " + std::to_string(node);
}

}  // namespace

void write_plots(const std::string& dir, const World& world, RunResult& result,
                 std::vector<std::string>& warnings) {
  const OutputDesc& out = world.scene().output;
  const std::string scripts = plot_scripts_dir();
  for (const std::string& plot : out.plots) {
    std::vector<std::string> args{plot_python()};
    std::string png = dir + "/" + plot + ".png";
    if (plot == "phase_portrait") {
      if (!std::filesystem::exists(dir + "/trajectory.csv")) {
        warnings.push_back(
            "phase_portrait: no trajectory was recorded (set output.plot_nodes or probe_node)");
        continue;
      }
      args.insert(args.end(), {scripts + "/phase_portrait.py", dir + "/trajectory.csv", png,
                               "--title", world.scene().name});
      size_t first = 0;
      while (first + 1 < world.body_count() && world.body(first).recording.recorded_nodes.empty())
        ++first;
      const SoftBody body = world.body(first);
      std::string nodes, labels;
      for (uint32_t n : body.recording.recorded_nodes) {
        nodes += (nodes.empty() ? "" : ",") + std::to_string(n);
        labels += (labels.empty() ? "" : ",") + node_label(body, n);
      }
      args.insert(args.end(), {"--nodes", nodes, "--labels", labels});
    } else if (plot == "force") {
      if (!std::filesystem::exists(dir + "/trace.csv")) {
        warnings.push_back("force: no trace.csv (the scene has no device, or output.trace is off)");
        continue;
      }
      png = dir + "/force_vs_time.png";
      args.insert(args.end(), {scripts + "/force_vs_time.py", dir + "/trace.csv", png});
      if (world.device_count() > 0)
        args.insert(args.end(),
                    {"--peak-force",
                     std::to_string(world.device(0).link.device->capabilities().peak_force)});
    } else if (plot == "energy" || plot == "displacement") {
      args.insert(args.end(), {scripts + "/energy.py", dir + "/energy.csv", png, "--quantity", plot,
                               "--title", world.scene().name});
    } else {
      warnings.push_back("unknown plot '" + plot + "'");
      continue;
    }
    const int status = run_plot_process(args);
    if (status == 0 && std::filesystem::exists(png))
      result.outputs.push_back(png);
    else
      warnings.push_back("plot " + plot + " failed (" + args[1] + " exited with " +
                         std::to_string(status) + ")");
  }
}

}  // namespace tacta
