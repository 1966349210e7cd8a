// Parameter panel values: schema defaults, scene overrides, and the ParamSet in schema order.
#include <array>
#include <gtest/gtest.h>

#include "param_values.hpp"
#include "tacta/sdk/common.hpp"

namespace tacta::view {
namespace {

constexpr std::array<tacta_param_spec, 5> kSchema{{
    sdk::choice_param("solver", "pcg|cholesky|lu", 1, "linear solver"),
    sdk::real_param("damping", "N s/m", 0.5, 0.0, 1e6, "damping"),
    sdk::int_param("iterations", 25, 1, 10000, "iterations"),
    sdk::vector_param("origin", "m", 3, "0 0.1 -2.5e-3", -1.0, 1.0, "origin"),
    sdk::text_param("file", "a.csv", "log"),
}};

TEST(ParamValues, DefaultsComeFromTheSchema) {
  const std::vector<ParamValue> v = param_values(kSchema);
  ASSERT_EQ(v.size(), 5u);
  EXPECT_EQ(v[0].number, 1);
  EXPECT_EQ(v[1].number, 0.5);
  EXPECT_EQ(v[2].number, 25);
  EXPECT_EQ(v[3].values, (std::vector<double>{0, 0.1, -2.5e-3}));
  EXPECT_EQ(v[4].text, "a.csv");
}

TEST(ParamValues, SceneValuesOverrideDefaults) {
  ParamSet scene;
  scene.add_number("iterations", 40);
  scene.add_vector("origin", {1, 2, 3});
  const std::vector<ParamValue> v = param_values(kSchema, &scene);
  EXPECT_EQ(v[2].number, 40);
  EXPECT_EQ(v[3].values, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(v[1].number, 0.5);  // not given: default
}

TEST(ParamValues, ParamSetIsInSchemaOrderWithChoiceNames) {
  std::vector<ParamValue> v = param_values(kSchema);
  v[0].number = 2;
  v[1].number = 7.5;
  const ParamSet set = to_param_set(v);
  ASSERT_EQ(set.size(), 5u);
  EXPECT_EQ(set.names(),
            (std::vector<std::string>{"solver", "damping", "iterations", "origin", "file"}));
  EXPECT_STREQ(set.data()[0].text, "lu");
  EXPECT_EQ(set.data()[0].number, 2);
  EXPECT_EQ(set.data()[1].number, 7.5);
  ASSERT_EQ(set.data()[3].count, 3u);
  EXPECT_EQ(set.data()[3].values[2], -2.5e-3);
  EXPECT_STREQ(set.data()[4].text, "a.csv");
}

TEST(ParamValues, ChoiceNamesSplitOnBars) {
  EXPECT_EQ(choice_names(kSchema[0]), (std::vector<std::string>{"pcg", "cholesky", "lu"}));
  EXPECT_TRUE(choice_names(kSchema[1]).empty());
}

}  // namespace
}  // namespace tacta::view
