// `tacta compare` on the paper's unit square (case B, a few seconds): one row per model, files
// per model, the rows agree with `tacta run` of the same model, bad model names stop everything.
// Only fd_debunne accepts the 4-node quad (the others need tets), so the two "models" are two
// of its integrators with its default (zero) damping.
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <sstream>

#include "cli_process.hpp"
#include "tacta/render/image.hpp"

namespace tacta::test {
namespace {

const char* const kScene = "scenes/seed/unit_square_case_b.yaml";
// 100 ticks of the scene's 0.04 s step; no per-model plots, so no python but the bar chart.
const std::vector<std::string> kShortRun{"--duration", "4", "--set", "output.plots=[]"};

using CsvRow = std::map<std::string, std::string>;

std::vector<CsvRow> read_csv(const std::filesystem::path& file) {
  std::istringstream text(read_text(file));
  std::vector<std::string> header;
  std::vector<CsvRow> rows;
  for (std::string line; std::getline(text, line);) {
    std::vector<std::string> cells;
    std::istringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    if (header.empty()) {
      header = cells;
      continue;
    }
    CsvRow row;
    for (size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    EXPECT_EQ(cells.size(), header.size()) << line;
    rows.push_back(row);
  }
  return rows;
}

std::string json_string_field(const std::string& json, const std::string& key) {
  const std::string marker = "\"" + key + "\": \"";
  const size_t at = json.find(marker);
  if (at == std::string::npos) return "";
  const size_t begin = at + marker.size();
  return json.substr(begin, json.find('"', begin) - begin);
}

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(CompareCommand, TwoModelsWriteOneRowEachAndTheChart) {
  const auto dir = fresh_dir("two_models");
  const CliResult r = run_tacta(
      with({"compare", kScene, "--models", "fd_debunne,fd_debunne:integrator=explicit_euler",
            "--out", (dir / "cmp").string()},
           kShortRun),
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;

  const std::vector<CsvRow> rows = read_csv(dir / "cmp" / "compare.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("model"), "fd_debunne");
  EXPECT_EQ(rows[1].at("model"), "fd_debunne:integrator=explicit_euler");
  for (const CsvRow& row : rows) {
    SCOPED_TRACE(row.at("model"));
    EXPECT_EQ(row.at("faults"), "0");
    EXPECT_EQ(row.at("state_hash").size(), 16u);
    EXPECT_GE(std::stod(row.at("tick_p99_ms")), std::stod(row.at("tick_p50_ms")));
    // The NE corner starts 0.05 m off in x and y (|d| = 0.0707 m at t = 0) and springs back.
    EXPECT_GT(std::stod(row.at("max_displacement_m")), 0.05);
    EXPECT_LT(std::stod(row.at("max_displacement_m")), 1.0);
    EXPECT_GT(std::stod(row.at("energy_start_J")), 0.0);
    // The scene names no probe node.
    EXPECT_EQ(row.at("probe_displacement_m"), "");
    const double drift = std::stod(row.at("energy_drift"));
    const double start = std::stod(row.at("energy_start_J")),
                 end = std::stod(row.at("energy_end_J"));
    EXPECT_NEAR(drift, (end - start) / start, 1e-6 * std::abs(drift) + 1e-12);
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "cmp" / "fd_debunne" / "report.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "cmp" / "fd_debunne_integrator_explicit_euler" /
                                      "report.json"));
  EXPECT_NE(rows[0].at("state_hash"), rows[1].at("state_hash"));
  // Undamped: symplectic Euler keeps the energy within a few percent over 100 steps; forward
  // Euler amplifies every mode by sqrt(1 + (omega dt)^2) a step, so it gains energy.
  EXPECT_LT(std::abs(std::stod(rows[0].at("energy_drift"))), 0.1);
  EXPECT_GT(std::stod(rows[1].at("energy_drift")), std::abs(std::stod(rows[0].at("energy_drift"))));

  const std::string json = read_text(dir / "cmp" / "compare.json");
  EXPECT_NE(json.find("\"model\": \"fd_debunne\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"model\": \"fd_debunne:integrator=explicit_euler\""), std::string::npos)
      << json;
  const render::Image chart = render::read_png(dir / "cmp" / "compare.png");
  EXPECT_GT(chart.width, 100);
  EXPECT_GT(chart.height, 100);
  EXPECT_NE(r.out.find("fd_debunne:integrator=explicit_euler"), std::string::npos) << r.out;

  // The same model through `tacta run` ends in the same state: the override is the whole change.
  const CliResult single =
      run_tacta(with({"run", kScene, "--quiet", "--set",
                      "bodies.*.model={name: fd_debunne, integrator: explicit_euler}", "--out",
                      (dir / "run").string()},
                     kShortRun),
                dir);
  ASSERT_EQ(single.exit_code, 0) << single.err;
  EXPECT_EQ(json_string_field(read_text(dir / "run" / "report.json"), "state_hash"),
            rows[1].at("state_hash"));
}

TEST(CompareCommand, ProbeDisplacementIsTheProbeNodesFinalOffsetFromRest) {
  // The beam names probe_node 35, its far top corner, at rest at (0.4, 0.05, 0.05) m; the run's
  // own trajectory.csv follows that node, so its last row gives the final position.
  const auto dir = fresh_dir("probe");
  const CliResult r = run_tacta(
      {"compare", "scenes/examples/beam_under_gravity.yaml", "--models", "corotational_fem",
       "--out", (dir / "cmp").string(), "--duration", "0.2", "--set", "output.plots=[]"},
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::vector<CsvRow> rows = read_csv(dir / "cmp" / "compare.csv");
  ASSERT_EQ(rows.size(), 1u);
  const std::vector<CsvRow> trajectory =
      read_csv(dir / "cmp" / "corotational_fem" / "trajectory.csv");
  ASSERT_FALSE(trajectory.empty());
  const CsvRow& last = trajectory.back();
  ASSERT_EQ(last.at("node"), "35");
  EXPECT_NEAR(std::stod(last.at("time_s")), 0.2, 1e-9);
  const double dx = std::stod(last.at("x")) - 0.4, dy = std::stod(last.at("y")) - 0.05,
               dz = std::stod(last.at("z")) - 0.05;
  const double probe = std::stod(rows[0].at("probe_displacement_m"));
  EXPECT_NEAR(probe, std::sqrt(dx * dx + dy * dy + dz * dz), 1e-8);
  EXPECT_GT(probe, 0.01) << "the free end sags under gravity";
  EXPECT_LE(probe, std::stod(rows[0].at("max_displacement_m")) + 1e-12);
  // Starts at rest with no gravitational term in E: E_0 ~ 0, so no relative drift is given.
  EXPECT_EQ(rows[0].at("energy_drift"), "");
  EXPECT_GT(std::stod(rows[0].at("energy_end_J")), 0.0);
  EXPECT_NE(read_text(dir / "cmp" / "compare.json").find("\"probe\": \"beam:35\""),
            std::string::npos);
}

// --reference: each row's max displacement over the reference's, and the RMS node distance of
// the final states; the reference row itself is 1 and 0. Two fd_debunne integrators differ.
TEST(CompareCommand, ReferenceColumnsMeasureEveryModelAgainstOne) {
  const auto dir = fresh_dir("reference");
  const CliResult r = run_tacta(
      with({"compare", kScene, "--models", "fd_debunne,fd_debunne:integrator=explicit_euler",
            "--reference", "fd_debunne", "--out", (dir / "cmp").string()},
           kShortRun),
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::vector<CsvRow> rows = read_csv(dir / "cmp" / "compare.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(std::stod(rows[0].at("displacement_ratio")), 1.0);
  EXPECT_EQ(std::stod(rows[0].at("difference_from_reference_m")), 0.0);
  const double ratio = std::stod(rows[1].at("displacement_ratio"));
  EXPECT_NEAR(
      ratio,
      std::stod(rows[1].at("max_displacement_m")) / std::stod(rows[0].at("max_displacement_m")),
      1e-6);
  EXPECT_GT(std::stod(rows[1].at("difference_from_reference_m")), 0.0);
  EXPECT_LT(std::stod(rows[1].at("difference_from_reference_m")), 1.0);
  EXPECT_NE(read_text(dir / "cmp" / "compare.json").find("\"reference\": \"fd_debunne\""),
            std::string::npos);
  EXPECT_NE(r.out.find("reference model: fd_debunne"), std::string::npos) << r.out;

  // Without --reference the columns are empty; a reference that is not compared is bad input.
  const CliResult plain = run_tacta(
      with({"compare", kScene, "--models", "fd_debunne", "--out", (dir / "plain").string()},
           kShortRun),
      dir);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(read_csv(dir / "plain" / "compare.csv")[0].at("displacement_ratio"), "");
  const CliResult bad = run_tacta(with({"compare", kScene, "--models", "fd_debunne", "--reference",
                                        "tensor_mass", "--out", (dir / "bad").string()},
                                       kShortRun),
                                  dir);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--reference"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
}

TEST(CompareCommand, UnknownModelStopsBeforeAnythingRuns) {
  const auto dir = fresh_dir("unknown_model");
  const CliResult r = run_tacta(with({"compare", kScene, "--models", "fd_debunne,no_such_model",
                                      "--out", (dir / "cmp").string()},
                                     kShortRun),
                                dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("no_such_model"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "cmp")) << "compare wrote output before failing";
}

TEST(CompareCommand, BadModelParametersAreBadInput) {
  const auto dir = fresh_dir("bad_parameters");
  // No '=', an unknown parameter, a value outside the schema's choices.
  for (const std::string entry :
       {"fd_debunne:integrator", "fd_debunne:no_such_param=1", "fd_debunne:integrator=rk4"}) {
    SCOPED_TRACE(entry);
    const CliResult r = run_tacta(
        with({"compare", kScene, "--models", entry, "--out", (dir / "cmp").string()}, kShortRun),
        dir);
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "cmp"));
  }
}

TEST(CompareCommand, DuplicateModelIsBadInput) {
  const auto dir = fresh_dir("duplicate_model");
  const CliResult r = run_tacta(with({"compare", kScene, "--models", "fd_debunne,fd_debunne",
                                      "--out", (dir / "cmp").string()},
                                     kShortRun),
                                dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("twice"), std::string::npos) << r.err;
}

TEST(CompareCommand, AModelThatDivergesKeepsItsRowAndExitsOne) {
  // lambda = 1e5 Pa on a 1 kg/m^2 unit square: omega ~ sqrt(lambda / rho) ~ 316 rad/s, so the
  // 0.04 s explicit step (omega dt ~ 13 >> 2) diverges and the body is frozen.
  const auto dir = fresh_dir("diverging_model");
  const CliResult r = run_tacta(
      with({"compare", kScene, "--models", "fd_debunne", "--out", (dir / "cmp").string(), "--set",
            "bodies.*.material={lame_lambda: 1.0e5, lame_mu: 1.0e3, density: 1.0}"},
           kShortRun),
      dir);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const std::vector<CsvRow> rows = read_csv(dir / "cmp" / "compare.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NE(rows[0].at("faults"), "0");
}

}  // namespace
}  // namespace tacta::test
