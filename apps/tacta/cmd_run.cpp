// `tacta run SCENE`: loads a scene, runs it (lockstep by default, or realtime), writes the report,
// records and plots to --out. Exit 0 ok, 1 a runtime fault (a body diverged, a device failed),
// 2 bad input (scene, mesh, plugin).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <unistd.h>

#include "command.hpp"
#include "tacta/error.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/render/snapshot_frame.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta::cli {
namespace {

struct RunArgs {
  std::string scene;
  std::string out;
  double duration = -1;
  bool realtime = false;
  bool lockstep = false;
  std::vector<std::string> overrides;
  std::string record;
  std::string replay;
  bool frames = false;
  bool quiet = false;
  int haptic_cpu = -2;        // -2: as the scene says
  double checkpoint_at = -1;  // s: write a checkpoint at this simulated time
  std::string checkpoint;     // the checkpoint file --checkpoint-at writes
  std::string resume;         // a checkpoint to continue from
};

// CLI11's PositiveNumber prints the whole double range as its bound; say what a duration is.
const CLI::Validator kDurationSeconds(
    [](const std::string& text) -> std::string {
      double value = 0;
      if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || !(value > 0))
        return "expected a duration in s > 0 (at most " + std::to_string(kMaxRunTicks) +
               " haptic ticks, 1 h at 1 kHz), found '" + text + "'";
      return {};
    },
    "SECONDS > 0");

int run_scene(const RunArgs& args) {
  apply_quiet(args.quiet);
  PluginRegistry plugins;
  plugins.load();
  RegistrySchemas schemas(plugins);
  std::vector<std::string> overrides = args.overrides;
  // --duration replaces clock.duration_s before the scene is checked, so a scene's own (perhaps
  // too long) duration does not matter and the bound is checked on the one that runs.
  if (args.duration > 0) {
    char text[64];
    std::snprintf(text, sizeof text, "clock.duration_s=%.17g", args.duration);
    overrides.push_back(text);
  }
  if (args.haptic_cpu >= -1)
    overrides.push_back("clock.haptic_cpu=" + std::to_string(args.haptic_cpu));
  // --resume FILE is clock.resume (a path typed here is relative to the working folder).
  if (!args.resume.empty()) overrides.push_back("clock.resume=\"" + args.resume + "\"");
  if (!args.replay.empty()) {
    // The scene's device is replaced by a replay of the log, keeping its tool and coupling.
    overrides.push_back("devices.*.plugin=replay");
    overrides.push_back("devices.*.params={log: \"" + args.replay + "\"}");
  }
  SceneDesc scene = load_scene(args.scene, schemas, overrides);
  Simulation simulation(scene, plugins);
  for (const std::string& warning : simulation.load_warnings()) log_warning(warning);
  RunOptions options;
  options.out_dir = args.out;
  if (args.realtime) options.realtime = true;
  if (args.lockstep) options.realtime = false;
  options.record_log = args.record;
  options.frames = args.frames;
  options.progress = !args.quiet && isatty(STDERR_FILENO);
  std::unique_ptr<FrameObserver> frames;
  if ((args.frames || scene.output.frames) && !args.out.empty()) {
    frames = render::make_png_frame_writer(args.out + "/frames", scene.output.frame_times,
                                           scene.output.frame_width, scene.output.frame_height);
    options.observers.push_back(frames.get());
  }
  if (!scene.clock.resume.empty())
    for (const std::string& note : simulation.checkpoint_notes()) log_warning(note);
  // The rest of the scene's duration from where it stands (0 on a fresh run, the checkpoint's
  // time on a resumed one); the outputs cover the whole run.
  const double rest = std::max(0.0, scene.clock.duration_s - simulation.time());
  if (args.checkpoint_at >= 0 && args.checkpoint_at > simulation.time()) {
    RunOptions first = options;
    first.out_dir.clear();
    first.progress = false;
    first.record_log.clear();
    first.duration_s = std::min(rest, args.checkpoint_at - simulation.time());
    simulation.run(first);
    simulation.save_state(args.checkpoint);
    for (const std::string& note : simulation.checkpoint_notes()) log_warning(note);
    if (!args.quiet)
      std::printf("checkpoint at t = %.6g s written to %s\n", simulation.time(),
                  args.checkpoint.c_str());
  }
  options.duration_s = std::max(0.0, scene.clock.duration_s - simulation.time());
  const RunResult result = simulation.run(options);
  // A fault is an error: printed even with --quiet, on stderr, with the exit code 1.
  for (const std::string& fault : result.fault_messages) log_error("runtime fault: " + fault);
  // One line per status bit kind seen (who x bit), warnings included, with its remedy; each line
  // starts with its severity ("warning: " or "error: "), which the sink writes back.
  for (const std::string& line : result.status.lines) {
    const bool error = line.rfind("error: ", 0) == 0;
    const size_t text = line.find(": ");
    log(error ? LogLevel::error : LogLevel::warning,
        text == std::string::npos ? line : line.substr(text + 2));
  }

  if (!args.quiet) {
    std::printf(
        "%s: %s, %llu ticks, %.3f s simulated in %.3f s, tick p50 %.3f ms p99 %.3f ms max %.3f ms",
        result.scene.c_str(), result.mode.c_str(),
        static_cast<unsigned long long>(result.schedule.ticks), result.sim_time_s,
        result.schedule.wall_time_s, result.schedule.tick.p50_ms, result.schedule.tick.p99_ms,
        result.schedule.tick.max_ms);
    if (result.mode == "realtime")
      std::printf(", %llu deadline misses",
                  static_cast<unsigned long long>(result.schedule.deadline_misses));
    std::printf("\n");
    const RealtimeGrant& grant = result.schedule.realtime;
    if (grant.demoted_at_tick >= 0)
      std::printf(
          "  warning: the haptic thread missed %u deadlines in a row at tick %lld and was dropped "
          "from "
          "SCHED_FIFO to SCHED_OTHER (nice %d) so it would not starve the machine; the scene's "
          "tick is "
          "too slow for clock.haptic_rate_hz here\n",
          kStarvingTicks, static_cast<long long>(grant.demoted_at_tick), grant.nice);
    for (const BodyResult& b : result.bodies)
      std::printf(
          "  body %s (%s): %zu nodes (%zu fixed), %zu elements, max displacement %.6g m%s%s\n",
          b.name.c_str(), b.model.c_str(), b.nodes, b.fixed_nodes, b.elements, b.max_displacement_m,
          b.frozen ? ", FROZEN: " : "", b.fault.c_str());
    for (const BodyResult& b : result.bodies) {
      std::printf("  body %s mesh: %s\n", b.name.c_str(), b.mesh.c_str());
      for (const std::string& w : b.mesh_warnings)
        std::printf("  body %s mesh warning: %s\n", b.name.c_str(), w.c_str());
    }
    for (const std::string& f : result.outputs) std::printf("  wrote %s\n", f.c_str());
    std::printf("  state hash %s\n", result.state_hash.c_str());
  }
  return result.exit_code;
}

void add_run_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd =
      app.add_subcommand("run", "Run a scene headless and write its report, records and plots");
  cmd->add_option("scene", args->scene, "Scene file (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out,-o", args->out,
                  "Output folder for report.json, trace.csv, plots and frames");
  cmd->add_option("--duration", args->duration,
                  "Simulated duration, s (overrides clock.duration_s)")
      ->check(kDurationSeconds);
  cmd->add_flag("--realtime", args->realtime,
                "Run on the wall clock: haptic thread at 1 kHz, render thread at 60 Hz");
  cmd->add_flag("--lockstep", args->lockstep,
                "Run on simulated time, as fast as possible (deterministic)");
  cmd->add_option("--set", args->overrides,
                  "Override a scene key: key.path=value (bodies.*.model=tensor_mass)");
  cmd->add_option("--record", args->record, "Write the first device's session log (CSV) here");
  cmd->add_option("--replay", args->replay, "Replace the scene's device by a replay of this log")
      ->check(CLI::ExistingFile);
  cmd->add_option("--haptic-cpu", args->haptic_cpu,
                  "Realtime: pin the haptic thread to this CPU and move other threads off it "
                  "(clock.haptic_cpu)")
      ->check(CLI::Range(-1, 1023));
  CLI::Option* at = cmd->add_option(
      "--checkpoint-at", args->checkpoint_at,
      "Write a checkpoint (--checkpoint FILE) at this simulated time, s, and run on");
  at->check(CLI::NonNegativeNumber);
  CLI::Option* file = cmd->add_option("--checkpoint", args->checkpoint,
                                      "The checkpoint file --checkpoint-at writes");
  at->needs(file);
  file->needs(at);
  cmd->add_option("--resume", args->resume,
                  "Continue from this checkpoint (of the same scene and --set) to the scene's "
                  "duration")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--frames", args->frames, "Write PNG frames from the render task");
  cmd->add_flag("--quiet,-q", args->quiet, kQuietHelp);
  cmd->callback([args, &exit_code] { exit_code = run_guarded([&] { return run_scene(*args); }); });
}

const bool registered = register_command(&add_run_command);

}  // namespace
}  // namespace tacta::cli
