// The scene's `events` as the loader reads them: cuts ({time, cut: {body, mode, triangles | quad}})
// and removals, and the InputError each bad one gives (file, line, key, what was expected).
#include <gtest/gtest.h>
#include <string>

#include "fake_schemas.hpp"

namespace tacta::testing {
namespace {

// kMinimalScene (5 lines, one body 'cube') with `events` on line 6.
std::string with_events(const std::string& events) {
  return yaml(kMinimalScene) + "events:\n" + events;
}

// The error's key path and line, and each fragment in its message.
void expect_error(const std::string& events, int line, const std::string& key_path,
                  std::initializer_list<std::string> fragments) {
  expect_at(load_error(with_events(events)), line, key_path, fragments);
}

TEST(SceneEvents, CutTrianglesAreReadAsNineNumbersEach) {
  const SceneDesc scene = load(with_events(R"(  - time: 0.25
    cut:
      body: cube
      triangles: [[0.05, -1, -1], [0.05, 1, -1], [0.05, 1, 1],
                  [0.05, -1, -1], [0.05, 1, 1], [0.05, -1, 1]]
)"));
  ASSERT_EQ(scene.events.size(), 1u);
  const BodyEventDesc& event = scene.events[0];
  EXPECT_DOUBLE_EQ(event.time, 0.25);
  EXPECT_FALSE(event.add);
  EXPECT_TRUE(event.remove.empty());
  EXPECT_FALSE(event.change_tool);
  ASSERT_TRUE(event.cut);
  EXPECT_EQ(event.cut->body, "cube");
  EXPECT_EQ(event.cut->mode, CutMode::kSeparate) << "separate is the default";
  EXPECT_EQ(event.cut->where.line, 9);  // the map under `cut:` starts at `body`
  const std::vector<double> expected = {0.05, -1, -1, 0.05, 1, -1, 0.05, 1,  1,
                                        0.05, -1, -1, 0.05, 1, 1,  0.05, -1, 1};
  EXPECT_EQ(event.cut->triangles, expected);
}

TEST(SceneEvents, CutQuadIsTwoTrianglesAndModeIsRead) {
  const SceneDesc scene = load(with_events(
      "  - {time: 0.1, cut: {body: cube, mode: remove, quad: [[0, 0, 0], [1, 0, 0], [1, 1, 0], "
      "[0, 1, 0]]}}\n"
      "  - {time: 0.2, cut: {body: cube, mode: separate, quad: [[0, 0, 1], [1, 0, 1], [1, 1, 1], "
      "[0, 1, 1]]}}\n"));
  ASSERT_EQ(scene.events.size(), 2u);
  ASSERT_TRUE(scene.events[0].cut && scene.events[1].cut);
  EXPECT_EQ(scene.events[0].cut->mode, CutMode::kRemove);
  EXPECT_EQ(scene.events[1].cut->mode, CutMode::kSeparate);
  // (p0, p1, p2), (p0, p2, p3)
  const std::vector<double> expected = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};
  EXPECT_EQ(scene.events[0].cut->triangles, expected);
}

TEST(SceneEvents, CutMayNameABodyAnEarlierEventAdds) {
  const SceneDesc scene = load(with_events(R"(  - time: 0.1
    add:
      name: late
      mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [1, 1, 1]}}
      material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
      model: tensor_mass
  - {time: 0.2, cut: {body: late, quad: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}}
)"));
  ASSERT_EQ(scene.events.size(), 2u);
  ASSERT_TRUE(scene.events[1].cut);
  EXPECT_EQ(scene.events[1].cut->body, "late");
}

TEST(SceneEvents, CutOfAnUnknownBodyNamesTheClosest) {
  expect_error(
      "  - {time: 0.1, cut: {body: cub, quad: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, "
      "0]]}}\n",
      7, "events[0].cut.body", {"no body named 'cub'", "did you mean 'cube'?"});
  expect_error("  - {time: 0.1, remove: cubs}\n", 7, "events[0].remove",
               {"no body named 'cubs'", "did you mean 'cube'?"});
}

TEST(SceneEvents, CutModeMustBeRemoveOrSeparate) {
  expect_error(
      "  - {time: 0.1, cut: {body: cube, mode: carve, quad: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, "
      "1, 0]]}}\n",
      7, "events[0].cut.mode", {"'carve'", "remove", "separate"});
}

TEST(SceneEvents, CutNeedsThreePointsATriangleOrFourForAQuad) {
  expect_error(R"(  - time: 0.1
    cut:
      body: cube
      triangles: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
)",
               10, "events[0].cut.triangles", {"3 per triangle", "found 4"});
  expect_error("  - {time: 0.1, cut: {body: cube, triangles: []}}\n", 7, "events[0].cut.triangles",
               {"3 per triangle", "found 0"});
  expect_error("  - {time: 0.1, cut: {body: cube, quad: [[0, 0, 0], [1, 0, 0], [1, 1, 0]]}}\n", 7,
               "events[0].cut.quad", {"4 points", "found 3"});
  expect_error("  - {time: 0.1, cut: {body: cube, triangles: [[0, 0], [1, 0, 0], [1, 1, 0]]}}\n", 7,
               "events[0].cut.triangles[0]", {"a list of 3 numbers"});
  expect_error("  - {time: 0.1, cut: {body: cube}}\n", 7, "events[0].cut",
               {"exactly one of: triangles, quad", "none"});
  expect_error(
      "  - {time: 0.1, cut: {body: cube, triangles: [[0, 0, 0], [1, 0, 0], [1, 1, 0]], quad: [[0, "
      "0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}}\n",
      7, "events[0].cut", {"exactly one of: triangles, quad", "several"});
}

TEST(SceneEvents, CutPointsMustBeFinite) {
  for (const char* bad : {".inf", "-.inf", ".nan", "nan", "inf", "1e999"})
    expect_error(std::string("  - {time: 0.1, cut: {body: cube, triangles: [[0, 0, 0], [1, ") +
                     bad + ", 0], [1, 1, 0]]}}\n",
                 7, "events[0].cut.triangles[1][1]",
                 {"expected a number", std::string("found '") + bad + "'"});
}

TEST(SceneEvents, CutHasAtMostTenThousandTriangles) {
  std::string points;
  for (int i = 0; i < 3 * 10'001; ++i) points += i ? ", [0, 0, 0]" : "[0, 0, 0]";
  expect_error("  - {time: 0.1, cut: {body: cube, triangles: [" + points + "]}}\n", 7,
               "events[0].cut.triangles", {"at most 10000 triangles", "found 10001"});
}

TEST(SceneEvents, AnEventIsExactlyOneThing) {
  expect_error(
      "  - {time: 0.1, remove: cube, cut: {body: cube, quad: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, "
      "1, 0]]}}\n",
      7, "events[0]", {"exactly one of: add, remove, change_tool, cut"});
  expect_error("  - {time: 0.1, cut: {body: cube, blade: 3, quad: []}}\n", 7, "events[0].cut.blade",
               {"unknown key 'blade'"});
}

}  // namespace
}  // namespace tacta::testing
