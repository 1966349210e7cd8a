// `tacta snapshot SCENE --at T --out FILE.png`: runs the scene in lockstep up to simulated time T
// and draws the final state with the headless (EGL) renderer into one PNG. Exit 0 ok, 1 the run
// faulted (the picture is still written) or no picture could be made, 2 bad input.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <utility>

#include "command.hpp"
#include "tacta/error.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/render/headless.hpp"
#include "tacta/render/image.hpp"
#include "tacta/render/snapshot_frame.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta::cli {
namespace {

struct SnapshotArgs {
  std::string scene;
  double at = -1;  // s of simulated time
  std::string out;
  std::optional<int> width, height;  // pixels; absent: the scene's output.frame_size
  std::vector<std::string> overrides;
  bool quiet = false;
};

void check_args(const SnapshotArgs& args) {
  if (!std::isfinite(args.at) || args.at < 0)
    throw InputError({"--at", 0, 0, ""},
                     "expected a simulated time >= 0 s, found " + std::to_string(args.at));
  for (const auto& [name, side] :
       {std::pair{"--width", args.width}, std::pair{"--height", args.height}})
    if (side && (*side < 1 || *side > kMaxFrameSide))  // the scene's output.frame_size bounds
      throw InputError({name, 0, 0, ""}, "expected pixels in [1, " + std::to_string(kMaxFrameSide) +
                                             "] (the off-screen renderer's limit), found " +
                                             std::to_string(*side));
  if (args.out.empty())
    throw InputError({"--out", 0, 0, ""}, "expected a PNG file name, found nothing");
}

int take_snapshot(const SnapshotArgs& args) {
  apply_quiet(args.quiet);
  check_args(args);
  PluginRegistry plugins;
  plugins.load();
  RegistrySchemas schemas(plugins);
  const SceneDesc scene = load_scene(args.scene, schemas, args.overrides);
  Simulation simulation(scene, plugins);

  render::HeadlessOptions view;
  view.width = args.width.value_or(scene.output.frame_width);
  view.height = args.height.value_or(scene.output.frame_height);
  // Made before the run, so a machine without EGL fails at once rather than after the run.
  render::HeadlessRenderer renderer(view);

  RunOptions options;
  options.realtime = false;
  options.duration_s = args.at;
  const RunResult result = simulation.run(options);
  const render::Image image = render::write_snapshot_png(renderer, simulation.scene_static(),
                                                         simulation.snapshot(), args.out);

  if (!args.quiet) {
    std::printf("%s at t = %.6g s (%llu ticks): wrote %s (%dx%d)\n", result.scene.c_str(),
                simulation.time(), static_cast<unsigned long long>(result.schedule.ticks),
                args.out.c_str(), image.width, image.height);
    for (const BodyResult& b : result.bodies)
      if (b.frozen)
        std::printf("  body %s (%s) FROZEN: %s\n", b.name.c_str(), b.model.c_str(),
                    b.fault.c_str());
  }
  return result.exit_code;
}

void add_snapshot_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SnapshotArgs>();
  CLI::App* cmd = app.add_subcommand(
      "snapshot", "Run a scene in lockstep to time T and write one picture (PNG)");
  cmd->add_option("scene", args->scene, "Scene file (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--at,-t", args->at, "Simulated time of the picture, s (>= 0)")->required();
  cmd->add_option("--out,-o", args->out, "PNG file to write")->required();
  cmd->add_option("--width", args->width,
                  "Picture width, pixels (default: the scene's output.frame_size)");
  cmd->add_option("--height", args->height,
                  "Picture height, pixels (default: the scene's output.frame_size)");
  cmd->add_option("--set", args->overrides,
                  "Override a scene key: key.path=value (bodies.*.model=tensor_mass)");
  cmd->add_flag("--quiet,-q", args->quiet, kQuietHelp);
  cmd->callback(
      [args, &exit_code] { exit_code = run_guarded([&] { return take_snapshot(*args); }); });
}

const bool registered = register_command(&add_snapshot_command);

}  // namespace
}  // namespace tacta::cli
