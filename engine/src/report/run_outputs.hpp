// Writing a finished run to its output folder: the CSV records, report.json, and the plots.
// Runs after the haptic task has stopped, never from the 1 kHz path.
#pragma once

#include <string>

#include "../systems/haptic_loop.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta {

// trace.csv, trajectory.csv, energy.csv (those with rows); appends the paths to result.outputs.
void write_csv_records(const std::string& dir, const HapticLoop& loop, const World& world,
                       RunResult& result);

// report.json (see docs/REPORT.md); appends the path to result.outputs.
void write_report_json(const std::string& dir, const HapticLoop& loop, const World& world,
                       RunResult& result);

// The plots the scene asks for (output.plots), made by scripts/plots/*.py with /usr/bin/python3.
// A plot that cannot be made is a warning in the result, not a failed run.
void write_plots(const std::string& dir, const World& world, RunResult& result,
                 std::vector<std::string>& warnings);

}  // namespace tacta
