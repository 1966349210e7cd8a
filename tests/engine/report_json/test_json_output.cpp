// The JSON the engine writes (nlohmann::ordered_json): keys in the order written, doubles that
// read back bit for bit, null for NaN and infinities (JSON cannot hold them) and for absent
// figures, UTF-8 passed through and stray bytes replaced rather than failing the run.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unistd.h>

#include "tacta/compare/compare.hpp"

namespace {

std::string written_compare_json(const tacta::CompareSummary& summary) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("tacta_compare_" + std::to_string(::getpid()) + ".json");
  tacta::write_compare_json(path.string(), summary);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  return text.str();
}

tacta::CompareSummary one_row() {
  tacta::CompareSummary s;
  s.scene = "módulo µ \"beam\"\n";
  s.duration_s = 1.0 / 3.0;
  tacta::CompareRow r;
  r.model = "fem";
  r.tick_p50_ms = 6.02214076e23;
  r.tick_p99_ms = -2.5e-300;
  r.max_displacement_m = std::numeric_limits<double>::quiet_NaN();
  r.energy_start_J = std::numeric_limits<double>::infinity();
  r.energy_end_J = 0.1;
  r.energy_drift = 1e-3;
  r.fault_reason = std::string("bad \xff byte");
  s.rows.push_back(r);
  return s;
}

TEST(JsonOutput, DoublesRoundTripAndNonFiniteIsNull) {
  const auto json = nlohmann::json::parse(written_compare_json(one_row()));
  const auto& row = json["models"][0];
  EXPECT_EQ(json["duration_s"].get<double>(), 1.0 / 3.0);
  EXPECT_EQ(row["tick_p50_ms"].get<double>(), 6.02214076e23);
  EXPECT_EQ(row["tick_p99_ms"].get<double>(), -2.5e-300);
  EXPECT_EQ(row["energy_drift"].get<double>(), 1e-3);
  EXPECT_TRUE(row["max_displacement_m"].is_null());    // NaN
  EXPECT_TRUE(row["energy_start_J"].is_null());        // infinity
  EXPECT_TRUE(row["probe_displacement_m"].is_null());  // absent
  EXPECT_TRUE(json["reference"].is_null());            // none named
}

TEST(JsonOutput, StringsEscapedUtf8KeptStrayBytesReplaced) {
  const std::string text = written_compare_json(one_row());
  EXPECT_NE(text.find(R"("scene": "módulo µ \"beam\"\n")"), std::string::npos) << text;
  const auto json = nlohmann::json::parse(text);
  EXPECT_EQ(json["models"][0]["fault_reason"].get<std::string>(), "bad \xef\xbf\xbd byte");
}

TEST(JsonOutput, KeysInTheOrderWritten) {
  const std::string text = written_compare_json(one_row());
  const size_t scene = text.find("\"scene\""), duration = text.find("\"duration_s\""),
               reference = text.find("\"reference\""), models = text.find("\"models\"");
  EXPECT_LT(scene, duration);
  EXPECT_LT(duration, reference);
  EXPECT_LT(reference, models);
  EXPECT_EQ(text.back(), '\n');
}

}  // namespace
