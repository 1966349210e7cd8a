// `tacta compare SCENE --models a,b,c --out DIR`: runs one scene once per model (every body takes
// that model, lockstep), each into DIR/<model>/, then writes DIR/compare.json, DIR/compare.csv and
// DIR/compare.png and prints a table (tacta/compare/compare.hpp, shared with Python's
// tacta.compare). Bad input stops with exit 2 and no partial results. Exit 0 when every model ran
// without a fault, 1 when any faulted (its row is still written), 2 bad input.
#include <cstdio>
#include <memory>

#include "command.hpp"
#include "tacta/compare/compare.hpp"
#include "tacta/plugin_registry.hpp"

namespace tacta::cli {
namespace {

struct CompareArgs {
  CompareOptions options;
  bool quiet = false;
};

int compare_models(const CompareArgs& args) {
  apply_quiet(args.quiet);
  PluginRegistry plugins;
  plugins.load();
  CompareOptions options = args.options;
  options.note = [](const std::string& text) { log_info(text); };
  const CompareSummary summary = run_comparison(options, plugins);
  std::string warning;
  const std::vector<std::string> written = write_compare_outputs(options.out_dir, summary, warning);
  if (!args.quiet) {
    print_compare_table(stdout, summary);
    std::printf("  wrote %s, %s\n", written[0].c_str(), written[1].c_str());
    if (written.size() > 2) std::printf("  wrote %s\n", written[2].c_str());
  }
  if (!warning.empty()) log_warning(warning);

  for (const CompareRow& r : summary.rows)
    if (r.faults > 0) return kExitFault;
  return kExitOk;
}

void add_compare_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Run one scene once per model and compare timings, displacement, energy");
  cmd->add_option("scene", args->options.scene, "Scene file (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--models,-m", args->options.models,
                  "Models, comma-separated; each NAME or NAME:param=value:... "
                  "(tensor_mass,fd_debunne:symmetric=true)")
      ->required()
      ->delimiter(',');
  cmd->add_option("--out,-o", args->options.out_dir,
                  "Output folder: one subfolder a model, compare.json/csv/png")
      ->required();
  cmd->add_option("--duration", args->options.duration_s,
                  "Simulated duration, s (overrides clock.duration_s)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--set", args->options.overrides,
                  "Override a scene key for every run: key.path=value");
  cmd->add_option("--reference", args->options.reference,
                  "A --models entry to measure the others against: max displacement ratio and RMS "
                  "node distance at the end");
  cmd->add_flag("--quiet,-q", args->quiet, kQuietHelp);
  cmd->callback(
      [args, &exit_code] { exit_code = run_guarded([&] { return compare_models(*args); }); });
}

const bool registered = register_command(&add_compare_command);

}  // namespace
}  // namespace tacta::cli
