// Descriptor validation in-process: each malformed field is refused with a reason naming it.
#include <gtest/gtest.h>
#include <string>

#include "plugin/descriptor_check.hpp"
#include "tacta/device_api.h"
#include "tacta/model_api.h"
#include "tacta/sdk/common.hpp"

namespace {

using tacta::plugin::check_descriptor;
using tacta::plugin::check_param;

tacta_status fake_create(const tacta_model_setup*, void**, char*, size_t) { return TACTA_OK; }
void fake_destroy(void*) {}
uint32_t fake_step(void*, tacta_body_state*, double) { return 0; }

// Value-initialised, then the required entries: entries appended to the API need no edit here.
const tacta_model_api kFullApi = [] {
  tacta_model_api api{};
  api.create = &fake_create;
  api.destroy = &fake_destroy;
  api.step = &fake_step;
  return api;
}();

tacta_descriptor make_model(const tacta_param_spec* params = nullptr, uint32_t count = 0) {
  return {sizeof(tacta_descriptor),
          TACTA_ABI_ID,
          TACTA_KIND_MODEL,
          "ok",
          1,
          "fine",
          params,
          count,
          &kFullApi,
          sizeof(tacta_model_api)};
}

std::string refusal(const tacta_descriptor& d) {
  const auto reason = check_descriptor(&d, TACTA_ABI_ID);
  return reason ? *reason : std::string("<accepted>");
}

TEST(DescriptorCheck, AcceptsAWellFormedDescriptor) {
  const tacta_descriptor d = make_model();
  EXPECT_FALSE(check_descriptor(&d, TACTA_ABI_ID).has_value()) << refusal(d);
}

TEST(DescriptorCheck, RefusesBadHeaderFields) {
  tacta_descriptor d = make_model();
  d.struct_size = 8;
  EXPECT_NE(refusal(d).find("struct_size 8"), std::string::npos);
  d = make_model();
  d.abi = tacta_abi_make(TACTA_ABI_MAJOR + 1, 0, tacta_abi_build_bits());
  EXPECT_NE(refusal(d).find("ABI major version differs"), std::string::npos) << refusal(d);
  d = make_model();
  d.kind = 42;
  EXPECT_NE(refusal(d).find("unknown kind 42"), std::string::npos);
  d = make_model();
  d.name = "";
  EXPECT_NE(refusal(d).find("empty name"), std::string::npos);
  d = make_model();
  d.api = nullptr;
  EXPECT_NE(refusal(d).find("api) is NULL"), std::string::npos);
  d = make_model();
  d.api_size = 8;
  EXPECT_NE(refusal(d).find("function table is 8 bytes"), std::string::npos) << refusal(d);
}

TEST(DescriptorCheck, NamesTheMissingRequiredFunction) {
  tacta_model_api api = kFullApi;
  api.destroy = nullptr;
  tacta_descriptor d = make_model();
  d.api = &api;
  EXPECT_NE(refusal(d).find("required function 'destroy'"), std::string::npos) << refusal(d);
  api = kFullApi;
  api.begin = nullptr;  // optional: fine
  EXPECT_EQ(refusal(d), "<accepted>");
}

TEST(DescriptorCheck, DeviceTableRequiresItsEntries) {
  const tacta_device_api empty{};
  tacta_descriptor d = make_model();
  d.kind = TACTA_KIND_DEVICE;
  d.api = &empty;
  d.api_size = sizeof empty;
  EXPECT_NE(refusal(d).find("required function 'create'"), std::string::npos) << refusal(d);
}

TEST(DescriptorCheck, RefusesInsaneParameters) {
  using namespace tacta::sdk;
  EXPECT_FALSE(check_param(real_param("E", "Pa", 1e5, 0, 1e9, "")).has_value());
  EXPECT_NE(check_param(real_param("E", "Pa", 1e5, 1e9, 0, ""))->find("min must be <= max"),
            std::string::npos);
  EXPECT_NE(check_param(real_param("E", "Pa", -1, 0, 1e9, ""))->find("default -1 is outside"),
            std::string::npos);
  EXPECT_NE(check_param(choice_param("c", nullptr, 0, ""))->find("no choices"), std::string::npos);
  EXPECT_NE(check_param(choice_param("c", "a|b", 2, ""))->find("not one of the 2 choices"),
            std::string::npos);
  EXPECT_FALSE(check_param(choice_param("c", "a|b", 1, "")).has_value());
  EXPECT_NE(check_param(vector_param("g", "m/s^2", 0, "", -1, 1, ""))->find("stride is 0"),
            std::string::npos);
  EXPECT_NE(check_param(vector_param("g", "m", 3, "0 0", -1, 1, ""))->find("not a multiple"),
            std::string::npos);
  EXPECT_FALSE(check_param(vector_param("g", "m", 3, "0 -0.5 1 0 0 0", -1, 1, "")).has_value());
  EXPECT_FALSE(check_param(bool_param("b", true, "")).has_value());

  // Inside a descriptor the reason names the parameter; duplicate names are refused.
  const tacta_param_spec bad[] = {int_param("n", 5, 0, 3, "")};
  EXPECT_NE(refusal(make_model(bad, 1)).find("parameter 'n': default 5 is outside"),
            std::string::npos);
  const tacta_param_spec twice[] = {int_param("n", 1, 0, 3, ""), int_param("n", 1, 0, 3, "")};
  EXPECT_NE(refusal(make_model(twice, 2)).find("declared twice"), std::string::npos);
  EXPECT_NE(refusal(make_model(nullptr, 3)).find("params is NULL"), std::string::npos);
}

TEST(DescriptorCheck, LiveParametersMustBeNumbersOfTheSchemaWithASetParamEntry) {
  using namespace tacta::sdk;
  const tacta_param_spec params[] = {real_param("damping", "1/s", 1, 0, 10, ""),
                                     choice_param("solver", "cg|ldlt", 0, "")};
  tacta_model_api api = kFullApi;
  const auto with = [&](const char* live) {
    api.live_params = live;
    tacta_descriptor d = make_model(params, 2);
    d.api = &api;
    return refusal(d);
  };
  EXPECT_NE(with("damping").find("set_param is NULL"), std::string::npos) << with("damping");
  api.set_param = [](void*, uint32_t, const tacta_param_value*, char*, size_t) { return TACTA_OK; };
  EXPECT_EQ(with("damping"), "<accepted>");
  EXPECT_EQ(with(nullptr), "<accepted>");
  EXPECT_NE(with("damping|stiffness").find("'stiffness', which is not a parameter"),
            std::string::npos);
  EXPECT_NE(with("solver").find("'solver' is not a number"), std::string::npos) << with("solver");
}

}  // namespace
