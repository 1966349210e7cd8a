// Golden images: the synthetic frames rendered on llvmpipe against tests/golden/*.png.
// TACTA_REGEN_GOLDENS=1 (scripts/regen-goldens) rewrites the goldens instead of comparing.
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>

#include "headless_fixture.hpp"

namespace tacta::render::testing {
namespace {

const std::filesystem::path kGoldenDir =
    std::filesystem::path(TACTA_SOURCE_DIR) / "tests" / "golden";
const std::filesystem::path kOutDir =
    std::filesystem::path(TACTA_BINARY_DIR) / "test-output" / "golden";

bool regenerating() {
  const char* flag = std::getenv("TACTA_REGEN_GOLDENS");
  return flag != nullptr && std::string(flag) == "1";
}

class GoldenImage : public HeadlessTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(GoldenImage, MatchesTheCommittedPicture) {
  for (const NamedFrame& named : golden_frames()) {
    if (named.name != GetParam()) continue;
    const Image actual = renderer().render(named.frame);
    const auto golden = kGoldenDir / (named.name + ".png");
    if (regenerating()) {
      write_png(golden, actual);
      GTEST_SKIP() << "regenerated " << golden;
    }
    const GoldenResult result = compare_with_golden(actual, golden, kOutDir);
    EXPECT_TRUE(result.comparison.matches) << result.message;
    return;
  }
  FAIL() << "no synthetic frame named " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Frames, GoldenImage,
                         ::testing::Values("bent_cantilever", "coloured_sphere", "tool_on_plate",
                                           "top_view_sphere_tool"));

TEST(GoldenSet, EveryFrameHasAGoldenFile) {
  for (const NamedFrame& named : golden_frames())
    EXPECT_TRUE(std::filesystem::exists(kGoldenDir / (named.name + ".png"))) << named.name;
}

}  // namespace
}  // namespace tacta::render::testing
