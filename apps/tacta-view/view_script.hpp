// A scripted session for tests and demos (--script): GUI actions at given frame numbers, driven
// through the same paths as the hand (model panel, play/pause/step, pointer input).
//
//   "20:swap liver tensor_mass; 40:press 0.01 20; 70:wheel -2; 80:release; 90:pause; 95:step"
//
// Verbs: swap BODY MODEL | set BODY PARAM VALUE | play | pause | step | quit |
//        mark (records the simulated time shown, for the status file) |
//        drag DX DY FRAMES (pixels from the mouse target's pixel, released at the end) |
//        press DEPTH FRAMES (drags the target onto the line of sight of the bodies' highest rest
//        point lowered by DEPTH m, and holds) | release | wheel NOTCHES |
//        keydown KEY | keyup KEY (holds and lets go a key: C, the cut key)
#pragma once

#include <array>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "mouse_tool.hpp"

namespace tacta::view {

struct ScriptAction {
  int frame = 0;
  std::string verb;
  std::vector<std::string> args;
};

// Throws std::invalid_argument naming the entry and what was expected.
std::vector<ScriptAction> parse_script(const std::string& text);

class ScriptHost {
 public:
  virtual ~ScriptHost() = default;
  virtual bool swap(const std::string& body, const std::string& model) = 0;
  virtual bool set_param(const std::string& body, const std::string& name, double value) = 0;
  virtual void play() = 0;
  virtual void pause() = 0;
  virtual void step() = 0;
  virtual void quit() = 0;  // closes the window after this frame
  virtual void mark() = 0;  // records the frame and the simulated time shown
  virtual std::optional<std::array<double, 2>> pixel_of(const Vec3d& point) const = 0;
  virtual Vec3d mouse_target() const = 0;
  virtual Vec3d top_point() const = 0;  // m, the highest rest node of the bodies
  // Holds (down) or lets go a key as the keyboard would; false for a key the window ignores.
  virtual bool key(const std::string& name, bool down) = 0;
};

class ScriptPlayer {
 public:
  explicit ScriptPlayer(std::vector<ScriptAction> actions) : actions_(std::move(actions)) {}
  // Runs the actions due at `frame`; the pointer the script drives, once it has touched it.
  std::optional<PointerState> advance(int frame, ScriptHost& host);
  bool finished() const { return next_ >= actions_.size() && track_.empty(); }
  const std::vector<std::string>& failures() const { return failures_; }  // refused actions

 private:
  void start_track(const std::array<double, 2>& from, const std::array<double, 2>& to, int frames,
                   bool release);
  std::vector<ScriptAction> actions_;
  size_t next_ = 0;
  std::deque<PointerState> track_;
  std::optional<PointerState> pointer_;
  std::vector<std::string> failures_;
};

}  // namespace tacta::view
