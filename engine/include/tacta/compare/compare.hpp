// One scene run once per model, side by side: the table of `tacta compare` and Python's
// tacta.compare (docs/COMPARE.md). Every scene and model is loaded and built before anything
// runs, so bad input throws InputError and nothing runs; a model whose run fails keeps a row.
#pragma once

#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tacta/plugin_registry.hpp"

namespace tacta {

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
  std::string out_dir;       // the run's subfolder of the output folder
  std::vector<double> final_positions;  // m, every body's nodes at the end, in body order
  // Against the reference model (empty without one, or when either run has no final state):
  std::optional<double> displacement_ratio;  // max_displacement_m / the reference's
  std::optional<double>
      difference_from_reference_m;  // m, RMS over nodes of |x - x_reference| at the end
};

struct CompareSummary {
  std::string scene;
  double duration_s = 0;  // s of simulated time each model ran
  std::string reference;  // the reference model's label; empty when none
  std::vector<CompareRow> rows;
};

struct CompareOptions {
  std::string scene;                // scene file
  std::vector<std::string> models;  // each NAME or NAME:param=value:... (fd_debunne:symmetric=true)
  std::vector<std::string> overrides;  // key.path=value, for every run (the model's comes last)
  double duration_s = -1;              // s; <= 0 keeps the scene's clock.duration_s
  std::string reference;               // one of `models`: the others are measured against it
  std::string out_dir;                 // each run's outputs in <out_dir>/<model>/; empty: none
  std::function<void(const std::string&)>
      note;  // progress and notes ("running x ..."); null: silent
};

// Runs the scene once per model (every body takes it, lockstep, the scene's swaps ignored) and
// fills the table, reference columns included. Throws InputError for bad input before any run.
CompareSummary run_comparison(const CompareOptions& options, const PluginRegistry& plugins);

// A row for a model whose run stopped with an error before it produced a result.
CompareRow make_failed_row(const std::string& model, const std::string& reason);

// Fills displacement_ratio and difference_from_reference_m of every row against the row whose
// model is summary.reference (nothing when it is empty). The runs share the mesh, so node i of
// one is node i of the other.
void compare_with_reference(CompareSummary& summary);

// Throw std::runtime_error naming the file when it cannot be written.
void write_compare_json(const std::string& path, const CompareSummary& summary);
// `label_faults` appends " (fault)" to the model of a faulted row: for the chart's input only.
void write_compare_csv(const std::string& path, const CompareSummary& summary,
                       bool label_faults = false);
// compare.json, compare.csv and the bar chart compare.png in `dir`; returns the files written
// (the chart is left out, with a warning in `warning`, when its script fails).
std::vector<std::string> write_compare_outputs(const std::string& dir,
                                               const CompareSummary& summary, std::string& warning);
void print_compare_table(std::FILE* out, const CompareSummary& summary);

// Metric columns worth a bar chart: energy_end_J stands in for an all-empty energy_drift, and the
// probe column is drawn only when some row has it.
std::vector<std::string> plotted_metrics(const CompareSummary& summary);

}  // namespace tacta
