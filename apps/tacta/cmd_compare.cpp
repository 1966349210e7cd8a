// `tacta compare SCENE --models a,b,c --out DIR`: runs one scene once per model (every body takes
// that model, lockstep), each into DIR/<model>/, then writes DIR/compare.json, DIR/compare.csv and
// DIR/compare.png and prints a table. Every scene and model is loaded and built before anything
// runs, so bad input stops with exit 2 and no partial results. Exit 0 when every model ran without
// a fault, 1 when any faulted (its row is still written), 2 bad input.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "command.hpp"
#include "compare_last_snapshot.hpp"
#include "compare_table.hpp"
#include "tacta/error.hpp"
#include "tacta/output/plot_script.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta::cli {
namespace {

struct CompareArgs {
  std::string scene;
  std::vector<std::string> models;
  std::string out;
  double duration = -1;  // s; <= 0 keeps the scene's clock.duration_s
  std::vector<std::string> overrides;
  bool quiet = false;
  std::string reference;  // a --models label: the other rows are measured against it
};

// One entry of --models: a plugin name, optionally with parameters, "fd_debunne:symmetric=true".
struct ModelChoice {
  std::string label;     // the entry as written: the row's `model`
  std::string plugin;    // the model plugin
  std::string override;  // the --set that gives every body this model
  std::string dir;       // subfolder of --out: the label with anything but [A-Za-z0-9_.-] as '_'
};

ModelChoice parse_model_choice(const std::string& entry, const PluginRegistry& plugins) {
  const SourceLocation where{"--models", 0, 0, entry};
  if (entry.empty()) throw InputError(where, "expected a model name, found an empty entry");
  ModelChoice choice{entry, entry.substr(0, entry.find(':')), "", entry};
  if (plugins.find(TACTA_KIND_MODEL, choice.plugin) == nullptr)
    throw InputError(where, plugins.unknown_name_message(TACTA_KIND_MODEL, choice.plugin));
  std::string params;
  for (size_t at = entry.find(':'); at != std::string::npos;) {
    const size_t next = entry.find(':', at + 1);
    const std::string pair = entry.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
    const size_t eq = pair.find('=');
    if (eq == 0 || eq == std::string::npos || eq + 1 == pair.size())
      throw InputError(where, "expected MODEL[:param=value]..., found '" + pair + "' after ':'");
    params += ", " + pair.substr(0, eq) + ": " + pair.substr(eq + 1);
    at = next;
  }
  // The loader checks the parameters against the plugin's schema, like any scene value.
  choice.override = "bodies.*.model=" + (params.empty() ? choice.plugin : "{name: " + choice.plugin + params + "}");
  for (char& c : choice.dir)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '-') c = '_';
  return choice;
}

std::vector<ModelChoice> parse_model_choices(const std::vector<std::string>& entries, const PluginRegistry& plugins) {
  if (entries.empty()) throw InputError({"--models", 0, 0, ""}, "expected at least one model name, found none");
  std::vector<ModelChoice> choices;
  std::set<std::string> labels, dirs;
  for (const std::string& entry : entries) {
    ModelChoice choice = parse_model_choice(entry, plugins);
    if (!labels.insert(choice.label).second || !dirs.insert(choice.dir).second)
      throw InputError({"--models", 0, 0, entry}, "model '" + entry + "' is named twice");
    choices.push_back(std::move(choice));
  }
  return choices;
}

// One model's world, built before any run starts.
struct ModelRun {
  ModelChoice model;
  SceneDesc scene;
  std::unique_ptr<Simulation> simulation;
};

std::vector<ModelRun> build_runs(const CompareArgs& args, const std::vector<ModelChoice>& models,
                                 const PluginRegistry& plugins, const SchemaLookup& schemas) {
  std::vector<ModelRun> runs;
  for (const ModelChoice& model : models) {
    // The model override comes last so that it wins over any --set of the user.
    std::vector<std::string> overrides = args.overrides;
    overrides.push_back(model.override);
    ModelRun run{model, load_scene(args.scene, schemas, overrides), nullptr};
    if (!run.scene.swaps.empty()) {
      // A swap would change the model under comparison part way through.
      if (!args.quiet)
        std::fprintf(stderr, "note: %s: the scene's %zu model swap(s) are ignored by compare\n", args.scene.c_str(),
                     run.scene.swaps.size());
      run.scene.swaps.clear();
    }
    run.simulation = std::make_unique<Simulation>(run.scene, plugins);
    runs.push_back(std::move(run));
  }
  return runs;
}

CompareRow run_one(ModelRun& run, const CompareArgs& args) {
  LastSnapshotKeeper final_state;
  RunOptions options;
  options.out_dir = (std::filesystem::path(args.out) / run.model.dir).string();
  options.realtime = false;  // lockstep: the same inputs, one model apart
  if (args.duration > 0) options.duration_s = args.duration;
  options.observers.push_back(&final_state);
  try {
    const RunResult result = run.simulation->run(options);
    CompareRow row = make_compare_row(run.model.label, run.scene, result, final_state);
    row.out_dir = run.model.dir;
    return row;
  } catch (const std::exception& e) {
    CompareRow row = make_failed_row(run.model.label, e.what());
    row.out_dir = run.model.dir;
    return row;
  }
}

int compare_models(const CompareArgs& args) {
  PluginRegistry plugins;
  plugins.load();
  RegistrySchemas schemas(plugins);
  const std::vector<ModelChoice> models = parse_model_choices(args.models, plugins);
  if (!args.reference.empty() && std::none_of(models.begin(), models.end(), [&](const ModelChoice& m) {
        return m.label == args.reference;
      }))
    throw InputError({"--reference", 0, 0, args.reference}, "expected one of the --models entries, found '" + args.reference + "'");
  std::vector<ModelRun> runs = build_runs(args, models, plugins, schemas);

  CompareSummary summary;
  summary.scene = args.scene;
  summary.duration_s = args.duration > 0 ? args.duration : runs.front().scene.clock.duration_s;
  summary.reference = args.reference;
  std::filesystem::create_directories(args.out);
  for (ModelRun& run : runs) {
    if (!args.quiet) std::fprintf(stderr, "running %s ...\n", run.model.label.c_str());
    summary.rows.push_back(run_one(run, args));
    run.simulation.reset();  // free the model's memory before the next one runs
  }

  compare_with_reference(summary);
  const std::filesystem::path out(args.out);
  write_compare_json((out / "compare.json").string(), summary);
  write_compare_csv((out / "compare.csv").string(), summary);
  std::string metrics;
  for (const std::string& m : plotted_metrics(summary)) metrics += (metrics.empty() ? "" : ",") + m;
  const std::string png = (out / "compare.png").string();
  // The chart reads a copy whose faulted models say so: a frozen body is no longer stepped, so
  // its bars (cheap ticks, a diverged energy) must not pass for a fast, sound model.
  const std::string chart_csv = (out / ".compare_chart.csv").string();
  write_compare_csv(chart_csv, summary, true);
  const int plot_status = run_plot_script("compare_bars.py", {chart_csv, png, "--metrics", metrics});
  std::filesystem::remove(chart_csv);
  if (!args.quiet) {
    print_compare_table(stdout, summary);
    std::printf("  wrote %s, %s\n", (out / "compare.json").string().c_str(), (out / "compare.csv").string().c_str());
    if (plot_status == 0) std::printf("  wrote %s\n", png.c_str());
  }
  if (plot_status != 0) std::fprintf(stderr, "warning: compare_bars.py exited with %d; no %s\n", plot_status, png.c_str());

  for (const CompareRow& r : summary.rows)
    if (r.faults > 0) return kExitFault;
  return kExitOk;
}

void add_compare_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "Run one scene once per model and compare timings, displacement, energy");
  cmd->add_option("scene", args->scene, "Scene file (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--models,-m", args->models, "Models, comma-separated; each NAME or NAME:param=value:... (tensor_mass,fd_debunne:symmetric=true)")
      ->required()
      ->delimiter(',');
  cmd->add_option("--out,-o", args->out, "Output folder: one subfolder a model, compare.json/csv/png")->required();
  cmd->add_option("--duration", args->duration, "Simulated duration, s (overrides clock.duration_s)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--set", args->overrides, "Override a scene key for every run: key.path=value");
  cmd->add_option("--reference", args->reference,
                  "A --models entry to measure the others against: max displacement ratio and RMS node distance at the end");
  cmd->add_flag("--quiet,-q", args->quiet, "Print nothing but errors");
  cmd->callback([args, &exit_code] { exit_code = run_guarded([&] { return compare_models(*args); }); });
}

const bool registered = register_command(&add_compare_command);

}  // namespace
}  // namespace tacta::cli
