// The --script driver: parsing (with clear errors) and the pointer tracks it plays.
#include <gtest/gtest.h>
#include <stdexcept>

#include "view_script.hpp"

namespace tacta::view {
namespace {

class FakeHost final : public ScriptHost {
 public:
  bool swap(const std::string& body, const std::string& model) override {
    calls.push_back("swap " + body + " " + model);
    return model != "refused";
  }
  bool set_param(const std::string& body, const std::string& name, double value) override {
    calls.push_back("set " + body + " " + name + " " + std::to_string(value));
    return true;
  }
  void play() override { calls.push_back("play"); }
  void pause() override { calls.push_back("pause"); }
  void step() override { calls.push_back("step"); }
  void quit() override { calls.push_back("quit"); }
  void mark() override { calls.push_back("mark"); }
  // A fake projection: x, y in pixels = 1000 * world x, -1000 * world y, offset to the centre.
  std::optional<std::array<double, 2>> pixel_of(const Vec3d& p) const override {
    return std::array<double, 2>{400 + 1000 * p[0], 300 - 1000 * p[1]};
  }
  Vec3d mouse_target() const override { return {0, 0.05, 0}; }
  Vec3d top_point() const override { return {0.01, 0.03, 0}; }
  bool key(const std::string& name, bool down) override {
    calls.push_back((down ? "keydown " : "keyup ") + name);
    return name == "c";
  }
  std::vector<std::string> calls;
};

std::string message_of(const std::string& script) {
  try {
    parse_script(script);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ViewScript, ParsesAndSortsByFrame) {
  const auto actions = parse_script("30:pause; 5:swap liver tensor_mass;;  10:drag 0 -40 4 ");
  ASSERT_EQ(actions.size(), 3u);
  EXPECT_EQ(actions[0].frame, 5);
  EXPECT_EQ(actions[0].args, (std::vector<std::string>{"liver", "tensor_mass"}));
  EXPECT_EQ(actions[1].verb, "drag");
  EXPECT_EQ(actions[2].verb, "pause");
}

TEST(ViewScript, BadEntriesNameWhatWasExpected) {
  EXPECT_NE(message_of("swap liver x").find("expected FRAME:VERB"), std::string::npos);
  EXPECT_NE(message_of("-3:play").find("FRAME >= 0"), std::string::npos);
  EXPECT_NE(message_of("4:jump").find("unknown verb 'jump'"), std::string::npos);
  EXPECT_NE(message_of("4:swap liver").find("takes 2 arguments"), std::string::npos);
  EXPECT_NE(message_of("4:wheel lots").find("must be a number"), std::string::npos);
  EXPECT_NE(message_of("4:set liver damping x").find("must be a number"), std::string::npos);
  EXPECT_NE(message_of("4:keydown").find("takes 1 arguments"), std::string::npos);
}

TEST(ViewScript, DragPlaysALinearTrackAndReleases) {
  FakeHost host;
  ScriptPlayer player(parse_script("2:drag 0 -40 4"));
  EXPECT_FALSE(player.advance(0, host).has_value());  // the real mouse until the script moves it
  std::vector<PointerState> seen;
  for (int frame = 2; frame < 9; ++frame) seen.push_back(*player.advance(frame, host));
  // From the target's pixel (400, 250) to 40 px higher over 4 frames, then released.
  ASSERT_EQ(seen.size(), 7u);
  for (int k = 0; k <= 4; ++k) {
    EXPECT_TRUE(seen[k].left_down);
    EXPECT_DOUBLE_EQ(seen[k].x, 400);
    EXPECT_DOUBLE_EQ(seen[k].y, 250 - 10.0 * k);
  }
  EXPECT_FALSE(seen[5].left_down);
  EXPECT_DOUBLE_EQ(seen[5].y, 210);
  EXPECT_FALSE(seen[6].left_down);  // held where it ended
  EXPECT_TRUE(player.finished());
}

TEST(ViewScript, PressAimsBelowTheTopPointAndHolds) {
  FakeHost host;
  ScriptPlayer player(parse_script("0:press 0.01 2; 5:wheel -2; 6:release"));
  PointerState p;
  for (int frame = 0; frame < 5; ++frame) p = *player.advance(frame, host);
  EXPECT_TRUE(p.left_down);
  EXPECT_DOUBLE_EQ(p.x, 410);  // top point x = 0.01 m
  EXPECT_DOUBLE_EQ(p.y, 280);  // top point y = 0.03 m, 0.01 m lower
  p = *player.advance(5, host);
  EXPECT_EQ(p.wheel, -2);
  EXPECT_TRUE(p.left_down);
  p = *player.advance(6, host);
  EXPECT_EQ(p.wheel, 0);  // one frame only
  EXPECT_FALSE(p.left_down);
}

TEST(ViewScript, ActionsReachTheHostAndRefusalsAreKept) {
  FakeHost host;
  ScriptPlayer player(
      parse_script("1:swap liver refused; 1:swap liver mass_spring; 2:set liver damping 3; "
                   "3:pause; 3:step; 4:play; 5:mark; 9:quit"));
  for (int frame = 0; frame < 10; ++frame) player.advance(frame, host);
  EXPECT_EQ(host.calls, (std::vector<std::string>{"swap liver refused", "swap liver mass_spring",
                                                  "set liver damping 3.000000", "pause", "step",
                                                  "play", "mark", "quit"}));
  EXPECT_EQ(player.failures(), (std::vector<std::string>{"1:swap"}));
}

// The cut key: held and let go by name, a key the window ignores is a refusal; the pointer is
// left to the hand (a key is not a pointer action).
TEST(ViewScript, KeysAreHeldAndLetGoByName) {
  FakeHost host;
  ScriptPlayer player(parse_script("2:keydown c; 6:keyup c; 7:keydown q"));
  for (int frame = 0; frame < 10; ++frame) EXPECT_FALSE(player.advance(frame, host).has_value());
  EXPECT_EQ(host.calls, (std::vector<std::string>{"keydown c", "keyup c", "keydown q"}));
  EXPECT_EQ(player.failures(), (std::vector<std::string>{"7:keydown"}));
}

}  // namespace
}  // namespace tacta::view
