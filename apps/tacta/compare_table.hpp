// The results of `tacta compare`: one row per model, computed from a run's RunResult and its final
// snapshot, written as compare.json and compare.csv and printed as a table.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "compare_last_snapshot.hpp"
#include "tacta/scene.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta::cli {

// Below this total energy at t = 0, J, a relative drift means nothing (a scene that starts at
// rest): energy_drift is left empty and energy_start_J / energy_end_J say what happened.
inline constexpr double kNegligibleEnergyJ = 1e-12;

struct CompareRow {
  std::string model;
  double tick_p50_ms = 0, tick_p99_ms = 0;  // ms, measured duration of every tick
  double max_displacement_m = 0;            // m, largest node displacement of any body over the run
  double energy_start_J = 0, energy_end_J = 0;  // J, kinetic + elastic of every body
  std::optional<double> energy_drift;           // (E_end - E_0) / |E_0|, empty when E_0 ~ 0
  std::optional<double> probe_displacement_m;   // m, |x - x_rest| of the probe node at the end
  std::string probe;                            // "body:node" of the probe, empty when none
  size_t faults = 0;
  std::string state_hash;
  std::string fault_reason;  // first frozen body's reason, or a run error; empty when none
  std::string out_dir;       // the run's subfolder of --out
  std::vector<double> final_positions;  // m, every body's nodes at the end, in body order
  // Against the --reference model (empty without one, or when either run has no final state):
  std::optional<double> displacement_ratio;           // max_displacement_m / the reference's
  std::optional<double> difference_from_reference_m;  // m, RMS over nodes of |x - x_reference| at the end
};

// Fills a row from a finished run. `scene` is the loaded scene (probe_node), `final_state` the
// observer that saw the run's frames.
CompareRow make_compare_row(const std::string& model, const SceneDesc& scene, const RunResult& result,
                            const LastSnapshotKeeper& final_state);

// A row for a model whose run stopped with an error before it produced a result.
CompareRow make_failed_row(const std::string& model, const std::string& reason);

struct CompareSummary {
  std::string scene;
  double duration_s = 0;  // s of simulated time each model ran
  std::string reference;  // the --reference model's label; empty when none
  std::vector<CompareRow> rows;
};

// Fills displacement_ratio and difference_from_reference_m of every row against the row whose
// model is summary.reference (nothing when it is empty). The runs share the mesh, so node i of
// one is node i of the other.
void compare_with_reference(CompareSummary& summary);

// Throw std::runtime_error naming the file when it cannot be written.
void write_compare_json(const std::string& path, const CompareSummary& summary);
// `label_faults` appends " (fault)" to the model of a faulted row: for the chart's input only.
void write_compare_csv(const std::string& path, const CompareSummary& summary, bool label_faults = false);
void print_compare_table(std::FILE* out, const CompareSummary& summary);

// Metric columns worth a bar chart: energy_end_J stands in for an all-empty energy_drift, and the
// probe column is drawn only when some row has it.
std::vector<std::string> plotted_metrics(const CompareSummary& summary);

}  // namespace tacta::cli
