// compare.json, compare.csv, the chart and the printed table of a comparison (docs/COMPARE.md).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "tacta/compare/compare.hpp"
#include "tacta/output/plot_script.hpp"

namespace tacta {
namespace {

std::string csv_number(double value) {
  if (!std::isfinite(value)) return "";
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

std::string csv_number(const std::optional<double>& value) {
  return value ? csv_number(*value) : "";
}

// Model names come from the plugin registry; quote them anyway if they ever hold a comma.
std::string csv_text(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// Fixed decimals for times (ms), significant digits for everything else.
enum class Style { Fixed4, Significant6 };

std::string table_number(const std::optional<double>& value, Style style) {
  if (!value || !std::isfinite(*value)) return "-";
  char text[40];
  if (style == Style::Fixed4)
    std::snprintf(text, sizeof text, "%.4f", *value);
  else
    std::snprintf(text, sizeof text, "%.6g", *value);
  return text;
}

}  // namespace

CompareRow make_failed_row(const std::string& model, const std::string& reason) {
  CompareRow row;
  row.model = model;
  row.tick_p50_ms = row.tick_p99_ms = row.max_displacement_m = std::nan("");
  row.energy_start_J = row.energy_end_J = std::nan("");
  row.faults = 1;
  row.fault_reason = reason;
  return row;
}

void compare_with_reference(CompareSummary& summary) {
  const auto reference =
      std::find_if(summary.rows.begin(), summary.rows.end(),
                   [&](const CompareRow& r) { return r.model == summary.reference; });
  if (summary.reference.empty() || reference == summary.rows.end()) return;
  const CompareRow ref = *reference;
  for (CompareRow& r : summary.rows) {
    if (std::isfinite(r.max_displacement_m) && ref.max_displacement_m > 0)
      r.displacement_ratio = r.max_displacement_m / ref.max_displacement_m;
    const std::vector<double>& a = r.final_positions;
    const std::vector<double>& b = ref.final_positions;
    if (a.empty() || a.size() != b.size()) continue;
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
    r.difference_from_reference_m = std::sqrt(sum / static_cast<double>(a.size() / 3));
  }
}

namespace {

using Json = nlohmann::ordered_json;

// An absent figure or name is null in compare.json.
Json or_null(const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); }
Json or_null(const std::string& text) { return text.empty() ? Json(nullptr) : Json(text); }

}  // namespace

void write_compare_json(const std::string& path, const CompareSummary& summary) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  Json models = Json::array();
  for (const CompareRow& r : summary.rows)
    models.push_back({{"model", r.model},
                      {"tick_p50_ms", r.tick_p50_ms},
                      {"tick_p99_ms", r.tick_p99_ms},
                      {"max_displacement_m", r.max_displacement_m},
                      {"energy_drift", or_null(r.energy_drift)},
                      {"energy_start_J", r.energy_start_J},
                      {"energy_end_J", r.energy_end_J},
                      {"probe_displacement_m", or_null(r.probe_displacement_m)},
                      {"probe", or_null(r.probe)},
                      {"faults", static_cast<uint64_t>(r.faults)},
                      {"state_hash", r.state_hash},
                      {"fault_reason", or_null(r.fault_reason)},
                      {"out_dir", r.out_dir},
                      {"displacement_ratio", or_null(r.displacement_ratio)},
                      {"difference_from_reference_m", or_null(r.difference_from_reference_m)}});
  const Json json = {{"scene", summary.scene},
                     {"duration_s", summary.duration_s},
                     {"reference", or_null(summary.reference)},
                     {"models", models}};
  // Non-finite numbers are written as null; bytes that are not UTF-8 become U+FFFD.
  file << json.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
  if (!file) throw std::runtime_error("cannot write " + path);
}

void write_compare_csv(const std::string& path, const CompareSummary& summary, bool label_faults) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write " + path);
  file << "model,tick_p50_ms,tick_p99_ms,max_displacement_m,energy_drift,probe_displacement_m,"
          "faults,state_hash,"
          "energy_start_J,energy_end_J,displacement_ratio,difference_from_reference_m\n";
  for (const CompareRow& r : summary.rows)
    file << csv_text(label_faults && r.faults > 0 ? r.model + " (fault)" : r.model) << ','
         << csv_number(r.tick_p50_ms) << ',' << csv_number(r.tick_p99_ms) << ','
         << csv_number(r.max_displacement_m) << ',' << csv_number(r.energy_drift) << ','
         << csv_number(r.probe_displacement_m) << ',' << r.faults << ',' << r.state_hash << ','
         << csv_number(r.energy_start_J) << ',' << csv_number(r.energy_end_J) << ','
         << csv_number(r.displacement_ratio) << ',' << csv_number(r.difference_from_reference_m)
         << '\n';
  if (!file) throw std::runtime_error("cannot write " + path);
}

std::vector<std::string> write_compare_outputs(const std::string& dir,
                                               const CompareSummary& summary,
                                               std::string& warning) {
  const std::filesystem::path out(dir);
  std::filesystem::create_directories(out);
  std::vector<std::string> written{(out / "compare.json").string(), (out / "compare.csv").string()};
  write_compare_json(written[0], summary);
  write_compare_csv(written[1], summary);
  std::string metrics;
  for (const std::string& m : plotted_metrics(summary)) metrics += (metrics.empty() ? "" : ",") + m;
  const std::string png = (out / "compare.png").string();
  // The chart reads a copy whose faulted models say so: a frozen body is no longer stepped, so
  // its bars (cheap ticks, a diverged energy) must not pass for a fast, sound model.
  const std::string chart_csv = (out / ".compare_chart.csv").string();
  write_compare_csv(chart_csv, summary, true);
  const int plot_status =
      run_plot_script("compare_bars.py", {chart_csv, png, "--metrics", metrics});
  std::filesystem::remove(chart_csv);
  if (plot_status == 0)
    written.push_back(png);
  else
    warning = "compare_bars.py exited with " + std::to_string(plot_status) + "; no " + png;
  return written;
}

void print_compare_table(std::FILE* out, const CompareSummary& summary) {
  std::fprintf(out, "%s, %.6g s simulated per model (lockstep)\n", summary.scene.c_str(),
               summary.duration_s);
  int width = 18;  // characters of the model column: the longest label
  for (const CompareRow& r : summary.rows)
    width = std::max(width, static_cast<int>(r.model.size()));
  const bool against = !summary.reference.empty();
  if (against)
    std::fprintf(out,
                 "reference model: %s (disp ratio: max displacement / its; diff: RMS node distance "
                 "at the end)\n",
                 summary.reference.c_str());
  std::fprintf(out, "%-*s %10s %10s %14s %13s %14s %6s  %s%s\n", width, "model", "p50 ms", "p99 ms",
               "max disp m", "energy drift", "probe disp m", "faults", "state hash        ",
               against ? "  disp ratio   diff m" : "");
  for (const CompareRow& r : summary.rows) {
    std::fprintf(out, "%-*s %10s %10s %14s %13s %14s %6zu  %-18s", width, r.model.c_str(),
                 table_number(r.tick_p50_ms, Style::Fixed4).c_str(),
                 table_number(r.tick_p99_ms, Style::Fixed4).c_str(),
                 table_number(r.max_displacement_m, Style::Significant6).c_str(),
                 table_number(r.energy_drift, Style::Significant6).c_str(),
                 table_number(r.probe_displacement_m, Style::Significant6).c_str(), r.faults,
                 r.state_hash.empty() ? "-" : r.state_hash.c_str());
    if (against) {
      std::fprintf(out, "  %10s %8s",
                   table_number(r.displacement_ratio, Style::Significant6).c_str(),
                   table_number(r.difference_from_reference_m, Style::Significant6).c_str());
    }
    std::fprintf(out, "\n");
    if (!r.fault_reason.empty())
      std::fprintf(out, "  %s: %s\n", r.model.c_str(), r.fault_reason.c_str());
  }
}

std::vector<std::string> plotted_metrics(const CompareSummary& summary) {
  std::vector<std::string> metrics{"tick_p50_ms", "tick_p99_ms", "max_displacement_m"};
  const bool any_drift =
      std::any_of(summary.rows.begin(), summary.rows.end(),
                  [](const CompareRow& r) { return r.energy_drift.has_value(); });
  metrics.push_back(any_drift ? "energy_drift" : "energy_end_J");
  if (std::any_of(summary.rows.begin(), summary.rows.end(),
                  [](const CompareRow& r) { return r.probe_displacement_m.has_value(); }))
    metrics.push_back("probe_displacement_m");
  return metrics;
}

}  // namespace tacta
