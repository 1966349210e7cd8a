// tacta::defaults_of (tacta/param_defaults.hpp), the one schema-default filler the engine, apps,
// plugins and tests share: every parameter kind of plugin.h, in schema order, with the C views
// a plugin reads (CHOICE name and index, TEXT text, VECTOR values and count) valid after copies
// and moves of the ParamSet.
#include <array>
#include <gtest/gtest.h>
#include <string>
#include <utility>
#include <vector>

#include "plugin/complete_params.hpp"
#include "tacta/param_defaults.hpp"
#include "tacta/sdk/common.hpp"

namespace tacta {
namespace {

constexpr std::array<tacta_param_spec, 8> kSchema{{
    sdk::real_param("stiffness", "N/m", 250.5, 0.0, 1e6, "a REAL"),
    sdk::int_param("iterations", 12, 1, 100, "an INT"),
    sdk::bool_param("enabled", true, "a BOOL"),
    sdk::choice_param("method", "first|second|third", 2, "a CHOICE whose default is not the first"),
    sdk::text_param("label", "left_hand", "a TEXT with a default"),
    {"path", TACTA_PARAM_TEXT, "", 0.0, 0.0, 0.0, nullptr, nullptr, 0, "a TEXT without one"},
    {"points", TACTA_PARAM_VECTOR, "m", 0.0, -1.0, 1.0, nullptr, "0 0.5 -0.25  1e-3 0 1", 3,
     "a VECTOR of two xyz points"},
    {"empty_points", TACTA_PARAM_VECTOR, "m", 0.0, -1.0, 1.0, nullptr, nullptr, 3,
     "a VECTOR without a default"},
}};

const tacta_descriptor& descriptor() {
  static const tacta_descriptor d{sizeof(tacta_descriptor),
                                  TACTA_ABI_ID,
                                  TACTA_KIND_MODEL,
                                  "defaults_probe",
                                  1,
                                  "",
                                  kSchema.data(),
                                  static_cast<uint32_t>(kSchema.size()),
                                  nullptr,
                                  0};
  return d;
}

void expect_schema_defaults(const ParamSet& set) {
  ASSERT_EQ(set.size(), kSchema.size());
  EXPECT_EQ(set.names(), (std::vector<std::string>{"stiffness", "iterations", "enabled", "method",
                                                   "label", "path", "points", "empty_points"}));
  const tacta_param_value* v = set.data();
  EXPECT_EQ(v[0].number, 250.5);
  EXPECT_EQ(v[0].text, nullptr);
  EXPECT_EQ(v[1].number, 12.0);
  EXPECT_EQ(v[2].number, 1.0);
  EXPECT_EQ(v[3].number, 2.0);  // CHOICE: the index ...
  ASSERT_NE(v[3].text, nullptr);
  EXPECT_STREQ(v[3].text, "third");  // ... and the name (sdk::Params::choice_name reads it)
  EXPECT_STREQ(v[4].text, "left_hand");
  ASSERT_NE(v[5].text, nullptr);  // TEXT without a default: "" rather than null
  EXPECT_STREQ(v[5].text, "");
  ASSERT_EQ(v[6].count, 6u);
  ASSERT_NE(v[6].values, nullptr);
  EXPECT_EQ(std::vector<double>(v[6].values, v[6].values + 6),
            (std::vector<double>{0, 0.5, -0.25, 1e-3, 0, 1}));
  EXPECT_EQ(v[7].count, 0u);
}

TEST(ParamDefaults, EveryKindFromTheSchema) { expect_schema_defaults(defaults_of(descriptor())); }

TEST(ParamDefaults, ViewsSurviveCopiesAndMoves) {
  ParamSet original = defaults_of(descriptor());
  const ParamSet copy = original;
  expect_schema_defaults(copy);
  ParamSet moved = std::move(original);
  expect_schema_defaults(moved);
  ParamSet assigned;
  assigned = std::move(moved);
  expect_schema_defaults(assigned);
  std::vector<ParamSet> grown;
  for (int i = 0; i < 5; ++i) grown.push_back(defaults_of(descriptor()));  // reallocations move
  for (const ParamSet& set : grown) expect_schema_defaults(set);
}

TEST(ParamDefaults, ChoiceNamesAndOutOfRangeIndex) {
  EXPECT_EQ(choice_names(kSchema[3]), (std::vector<std::string>{"first", "second", "third"}));
  EXPECT_EQ(choice_name(kSchema[3], 1), "second");
  EXPECT_EQ(choice_name(kSchema[3], 3), "");
  EXPECT_TRUE(choice_names(kSchema[0]).empty());
}

// The engine fills a swap request's missing values with the same defaults.
TEST(ParamDefaults, EngineCompletesAnEmptySetWithTheDefaults) {
  expect_schema_defaults(complete_params(descriptor(), ParamSet{}));
  ParamSet full = defaults_of(descriptor());
  ASSERT_TRUE(full.set_number("stiffness", 7.0));
  EXPECT_EQ(complete_params(descriptor(), full).find("stiffness")->number, 7.0);
}

}  // namespace
}  // namespace tacta
