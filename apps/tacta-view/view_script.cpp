#include "view_script.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace tacta::view {
namespace {

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\n");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\n") - a + 1);
}

double number(const ScriptAction& a, size_t i) {
  try {
    return std::stod(a.args.at(i));
  } catch (const std::exception&) {
    throw std::invalid_argument("--script: '" + a.verb + "' at frame " + std::to_string(a.frame) +
                                ": argument " + std::to_string(i + 1) + " must be a number");
  }
}

}  // namespace

std::vector<ScriptAction> parse_script(const std::string& text) {
  const std::vector<std::pair<std::string, size_t>> arity{
      {"swap", 2},  {"set", 3},     {"play", 0}, {"pause", 0}, {"step", 0},
      {"quit", 0},  {"mark", 0},    {"drag", 3}, {"press", 2}, {"release", 0},
      {"wheel", 1}, {"keydown", 1}, {"keyup", 1}};
  std::vector<ScriptAction> actions;
  std::istringstream entries(text);
  for (std::string entry; std::getline(entries, entry, ';');) {
    entry = trim(entry);
    if (entry.empty()) continue;
    const size_t colon = entry.find(':');
    ScriptAction a;
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      size_t used = 0;
      a.frame = std::stoi(entry.substr(0, colon), &used);
      if (trim(entry.substr(0, colon)).size() != used || a.frame < 0)
        throw std::invalid_argument("frame");
    } catch (const std::exception&) {
      throw std::invalid_argument("--script: '" + entry +
                                  "': expected FRAME:VERB ARGS with FRAME >= 0");
    }
    std::istringstream words(entry.substr(colon + 1));
    words >> a.verb;
    for (std::string w; words >> w;) a.args.push_back(w);
    const auto known =
        std::find_if(arity.begin(), arity.end(), [&](const auto& p) { return p.first == a.verb; });
    if (known == arity.end())
      throw std::invalid_argument(
          "--script: '" + entry + "': unknown verb '" + a.verb +
          "' (swap, set, play, pause, step, quit, mark, drag, press, release, wheel, keydown, "
          "keyup)");
    if (a.args.size() != known->second)
      throw std::invalid_argument("--script: '" + entry + "': '" + a.verb + "' takes " +
                                  std::to_string(known->second) + " arguments");
    const size_t first_number = a.verb == "swap" || a.verb == "set"        ? 2  // after the names
                                : a.verb == "keydown" || a.verb == "keyup" ? 1  // a key's name
                                                                           : 0;
    for (size_t i = first_number; i < a.args.size(); ++i) number(a, i);
    actions.push_back(std::move(a));
  }
  std::stable_sort(actions.begin(), actions.end(),
                   [](const auto& x, const auto& y) { return x.frame < y.frame; });
  return actions;
}

void ScriptPlayer::start_track(const std::array<double, 2>& from, const std::array<double, 2>& to,
                               int frames, bool release) {
  track_.clear();
  frames = std::max(frames, 1);
  for (int k = 0; k <= frames; ++k) {
    const double s = static_cast<double>(k) / frames;
    PointerState p;
    p.x = from[0] + s * (to[0] - from[0]);
    p.y = from[1] + s * (to[1] - from[1]);
    p.left_down = true;
    track_.push_back(p);
  }
  if (release) {
    PointerState up = track_.back();
    up.left_down = false;
    track_.push_back(up);
  }
}

std::optional<PointerState> ScriptPlayer::advance(int frame, ScriptHost& host) {
  if (pointer_) pointer_->wheel = 0;
  for (; next_ < actions_.size() && actions_[next_].frame <= frame; ++next_) {
    const ScriptAction& a = actions_[next_];
    bool ok = true;
    if (a.verb == "swap")
      ok = host.swap(a.args[0], a.args[1]);
    else if (a.verb == "set")
      ok = host.set_param(a.args[0], a.args[1], number(a, 2));
    else if (a.verb == "play")
      host.play();
    else if (a.verb == "pause")
      host.pause();
    else if (a.verb == "step")
      host.step();
    else if (a.verb == "quit")
      host.quit();
    else if (a.verb == "mark")
      host.mark();
    else if (a.verb == "keydown" || a.verb == "keyup")
      ok = host.key(a.args[0], a.verb == "keydown");
    else if (a.verb == "release") {
      track_.clear();
      if (pointer_) pointer_->left_down = false;
    } else if (a.verb == "wheel") {
      if (!pointer_) pointer_ = PointerState{};
      pointer_->wheel = number(a, 0);
    } else {  // drag, press: from the target's pixel
      const auto from = host.pixel_of(host.mouse_target());
      std::optional<std::array<double, 2>> to;
      if (from && a.verb == "drag")
        to = std::array<double, 2>{(*from)[0] + number(a, 0), (*from)[1] + number(a, 1)};
      if (from && a.verb == "press") {
        Vec3d p = host.top_point();
        p[1] -= number(a, 0);
        to = host.pixel_of(p);
      }
      ok = from && to;
      if (ok)
        start_track(*from, *to, static_cast<int>(number(a, a.verb == "drag" ? 2 : 1)),
                    a.verb == "drag");
    }
    if (!ok) failures_.push_back(std::to_string(a.frame) + ":" + a.verb);
  }
  if (!track_.empty()) {
    const double wheel = pointer_ ? pointer_->wheel : 0;
    pointer_ = track_.front();
    pointer_->wheel = wheel;
    track_.pop_front();
  }
  return pointer_;
}

}  // namespace tacta::view
