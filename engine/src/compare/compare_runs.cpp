// Running a comparison: the model choices checked, one world built per model before any run,
// then each run in lockstep and its row filled from the result and the final state.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>

#include "tacta/compare/compare.hpp"
#include "tacta/error.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta {
namespace {

// One entry of the model list: a plugin name, optionally with parameters, "fd_debunne:symmetric=true".
struct ModelChoice {
  std::string label;     // the entry as written: the row's `model`
  std::string plugin;    // the model plugin
  std::string override;  // the override that gives every body this model
  std::string dir;  // subfolder of the output: the label with anything but [A-Za-z0-9_.-] as '_'
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
    const std::string pair =
        entry.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
    const size_t eq = pair.find('=');
    if (eq == 0 || eq == std::string::npos || eq + 1 == pair.size())
      throw InputError(where, "expected MODEL[:param=value]..., found '" + pair + "' after ':'");
    params += ", " + pair.substr(0, eq) + ": " + pair.substr(eq + 1);
    at = next;
  }
  // The loader checks the parameters against the plugin's schema, like any scene value.
  choice.override = "bodies.*.model=" +
                    (params.empty() ? choice.plugin : "{name: " + choice.plugin + params + "}");
  for (char& c : choice.dir)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '-') c = '_';
  return choice;
}

std::vector<ModelChoice> parse_model_choices(const std::vector<std::string>& entries,
                                             const PluginRegistry& plugins) {
  if (entries.empty())
    throw InputError({"--models", 0, 0, ""}, "expected at least one model name, found none");
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

std::vector<ModelRun> build_runs(const CompareOptions& options,
                                 const std::vector<ModelChoice>& models,
                                 const PluginRegistry& plugins, const SchemaLookup& schemas) {
  std::vector<ModelRun> runs;
  for (const ModelChoice& model : models) {
    // The model override comes last so that it wins over any override of the user.
    std::vector<std::string> overrides = options.overrides;
    overrides.push_back(model.override);
    ModelRun run{model, load_scene(options.scene, schemas, overrides), nullptr};
    if (!run.scene.swaps.empty()) {
      // A swap would change the model under comparison part way through.
      if (options.note)
        options.note("note: " + options.scene + ": the scene's " +
                     std::to_string(run.scene.swaps.size()) +
                     " model swap(s) are ignored by compare");
      run.scene.swaps.clear();
    }
    run.simulation = std::make_unique<Simulation>(run.scene, plugins);
    runs.push_back(std::move(run));
  }
  return runs;
}

// |x - x_rest| of one node, m; nullopt when the state does not hold the node.
std::optional<double> node_displacement(const SceneStatic& scene, const Snapshot& state,
                                        size_t body, uint32_t node) {
  if (body >= scene.bodies.size() || body >= state.bodies.size()) return std::nullopt;
  const std::vector<double>& rest = scene.bodies[body].rest_positions;
  const std::vector<double>& now = state.bodies[body].positions;
  const size_t i = 3 * static_cast<size_t>(node);
  if (i + 2 >= rest.size() || i + 2 >= now.size()) return std::nullopt;
  const double dx = now[i] - rest[i], dy = now[i + 1] - rest[i + 1], dz = now[i + 2] - rest[i + 2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// A row from a finished run: its result and the simulation's final state.
CompareRow make_compare_row(const std::string& model, const SceneDesc& scene,
                            const RunResult& result, Simulation& simulation) {
  CompareRow row;
  row.model = model;
  row.tick_p50_ms = result.schedule.tick.p50_ms;
  row.tick_p99_ms = result.schedule.tick.p99_ms;
  for (const BodyResult& b : result.bodies) {
    row.max_displacement_m = std::max(row.max_displacement_m, b.max_displacement_m);
    row.energy_start_J += b.initial_energy_J;
    row.energy_end_J += b.kinetic_energy_J + b.elastic_energy_J;
    if (b.frozen && row.fault_reason.empty()) row.fault_reason = b.name + ": " + b.fault;
  }
  if (std::abs(row.energy_start_J) >= kNegligibleEnergyJ)
    row.energy_drift = (row.energy_end_J - row.energy_start_J) / std::abs(row.energy_start_J);
  const Snapshot final_state = simulation.snapshot();
  // The first body that names a probe node; the scene format allows one per body.
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    if (!scene.bodies[i].probe_node) continue;
    row.probe = scene.bodies[i].name + ":" + std::to_string(*scene.bodies[i].probe_node);
    row.probe_displacement_m =
        node_displacement(simulation.scene_static(), final_state, i, *scene.bodies[i].probe_node);
    break;
  }
  for (const BodySnapshot& body : final_state.bodies)
    row.final_positions.insert(row.final_positions.end(), body.positions.begin(),
                               body.positions.end());
  row.faults = result.faults;
  row.state_hash = result.state_hash;
  if (row.faults > 0 && row.fault_reason.empty())
    row.fault_reason = "fault reported (see report.json)";
  return row;
}

CompareRow run_one(ModelRun& run, const CompareOptions& options) {
  RunOptions run_options;
  if (!options.out_dir.empty())
    run_options.out_dir = (std::filesystem::path(options.out_dir) / run.model.dir).string();
  run_options.realtime = false;  // lockstep: the same inputs, one model apart
  if (options.duration_s > 0) run_options.duration_s = options.duration_s;
  CompareRow row;
  try {
    const RunResult result = run.simulation->run(run_options);
    row = make_compare_row(run.model.label, run.scene, result, *run.simulation);
  } catch (const std::exception& e) {
    row = make_failed_row(run.model.label, e.what());
  }
  row.out_dir = run.model.dir;
  return row;
}

}  // namespace

CompareSummary run_comparison(const CompareOptions& options, const PluginRegistry& plugins) {
  RegistrySchemas schemas(plugins);
  const std::vector<ModelChoice> models = parse_model_choices(options.models, plugins);
  if (!options.reference.empty() &&
      std::none_of(models.begin(), models.end(),
                   [&](const ModelChoice& m) { return m.label == options.reference; }))
    throw InputError({"--reference", 0, 0, options.reference},
                     "expected one of the --models entries, found '" + options.reference + "'");
  std::vector<ModelRun> runs = build_runs(options, models, plugins, schemas);

  CompareSummary summary;
  summary.scene = options.scene;
  summary.duration_s =
      options.duration_s > 0 ? options.duration_s : runs.front().scene.clock.duration_s;
  summary.reference = options.reference;
  for (ModelRun& run : runs) {
    if (options.note) options.note("running " + run.model.label + " ...");
    summary.rows.push_back(run_one(run, options));
    run.simulation.reset();  // free the model's memory before the next one runs
  }
  compare_with_reference(summary);
  return summary;
}

}  // namespace tacta
