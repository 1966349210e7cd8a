// The C++ SDK: parameter access by name, and optional table entries filled only when the class
// has the matching method. Also loads the test plugins through the shared C ABI fixture.
#include <array>
#include <gtest/gtest.h>
#include <stdexcept>

#include "support/plugin_fixture.hpp"
#include "tacta/sdk/device.hpp"
#include "tacta/sdk/model.hpp"

namespace {

constexpr std::array<tacta_param_spec, 4> kSchema{
    tacta::sdk::real_param("youngs", "Pa", 1e5, 0, 1e9, ""),
    tacta::sdk::bool_param("lumped", true, ""),
    tacta::sdk::choice_param("solver", "cg|ldlt", 1, ""),
    tacta::sdk::vector_param("g", "m/s^2", 3, "0 -9.81 0", -100, 100, ""),
};

TEST(Sdk, ParamsReadsEachTypeByName) {
  const double gravity[3] = {0, -9.81, 0};
  const tacta_param_value values[4] = {{2.5e4, nullptr, nullptr, 0},
                                       {0.0, nullptr, nullptr, 0},
                                       {1.0, "ldlt", nullptr, 0},
                                       {0.0, nullptr, gravity, 3}};
  const tacta::sdk::Params params(kSchema, values, 4);
  EXPECT_DOUBLE_EQ(params.real("youngs"), 2.5e4);
  EXPECT_FALSE(params.flag("lumped"));
  EXPECT_EQ(params.choice("solver"), 1);
  EXPECT_EQ(params.choice_name("solver"), "ldlt");
  ASSERT_EQ(params.vector("g").size(), 3u);
  EXPECT_DOUBLE_EQ(params.vector("g")[1], -9.81);
  EXPECT_THROW(params.real("poisson"), std::invalid_argument);
}

struct Minimal {
  static constexpr const char* kName = "minimal";
  static constexpr const char* kDescription = "";
  static constexpr uint32_t kVersion = 1;
  static constexpr std::array<tacta_param_spec, 0> kParams{};
  explicit Minimal(const tacta_model_setup&) {}
  uint32_t step(tacta_body_state&, double) noexcept { return 0; }
};

struct WithExtras : Minimal {
  using Minimal::Minimal;
  double elastic_energy(const double*) noexcept { return 1.5; }
  void set_param(uint32_t, const tacta_param_value&) { throw std::invalid_argument("read-only"); }
};

TEST(Sdk, OptionalEntriesOnlyWhenTheClassHasTheMethod) {
  const auto* minimal =
      static_cast<const tacta_model_api*>(tacta::sdk::model_descriptor<Minimal>()->api);
  EXPECT_NE(minimal->step, nullptr);
  EXPECT_EQ(minimal->begin, nullptr);
  EXPECT_EQ(minimal->elastic_energy, nullptr);
  EXPECT_EQ(minimal->set_param, nullptr);
  EXPECT_EQ(minimal->node_stress, nullptr);

  const auto* extras =
      static_cast<const tacta_model_api*>(tacta::sdk::model_descriptor<WithExtras>()->api);
  ASSERT_NE(extras->elastic_energy, nullptr);
  EXPECT_EQ(extras->internal_forces, nullptr);
  ASSERT_NE(extras->set_param, nullptr);
  WithExtras instance{tacta_model_setup{}};
  EXPECT_DOUBLE_EQ(extras->elastic_energy(&instance, nullptr), 1.5);
  char message[64] = {0};
  const tacta_param_value value{};
  // The exception becomes a status plus message at the boundary.
  EXPECT_EQ(extras->set_param(&instance, 0, &value, message, sizeof message),
            TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_STREQ(message, "read-only");
}

TEST(Sdk, RealPluginsThroughTheCAbiFixture) {
  const tacta::testing::LoadedPlugin model(std::string(TACTA_TEST_GOOD_PLUGIN_DIR) +
                                           "/tacta_test_good_model.so");
  const auto& api = model.api<tacta_model_api>("test_anchor_springs");
  EXPECT_NE(api.step, nullptr);
  EXPECT_EQ(api.begin, nullptr);           // no begin() in the class
  EXPECT_NE(api.elastic_energy, nullptr);  // has elastic_energy()

  const tacta::testing::LoadedPlugin device(std::string(TACTA_TEST_GOOD_PLUGIN_DIR) +
                                            "/tacta_test_good_device.so");
  const auto& d = device.descriptor("test_sine_stylus");
  const auto& dapi = *static_cast<const tacta_device_api*>(d.api);
  EXPECT_EQ(dapi.status, nullptr);  // the class has no status()
  const auto params = tacta::testing::default_params(d);
  tacta_device_setup setup{
      sizeof(tacta_device_setup), params.data(), static_cast<uint32_t>(params.size()), "", 1, 1e-3};
  void* instance = nullptr;
  char message[128] = {0};
  ASSERT_EQ(dapi.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
  ASSERT_EQ(dapi.connect(instance, message, sizeof message), TACTA_OK);
  tacta_device_sample sample{};
  EXPECT_EQ(dapi.read(instance, 0.25, &sample), TACTA_DEVICE_CONNECTED);
  EXPECT_NEAR(sample.position[0], 0.01, 1e-15);  // amplitude sin(pi/2), m
  dapi.destroy(instance);
}

}  // namespace
