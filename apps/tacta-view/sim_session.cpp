#include "sim_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

namespace tacta::view {
namespace {

// Whether a new snapshot's scene is not the one held: a body was cut (its revision) or added.
bool reshaped(const SceneStatic& held, const SceneStatic& now) {
  if (held.bodies.size() != now.bodies.size()) return true;
  for (size_t i = 0; i < now.bodies.size(); ++i)
    if (held.bodies[i].revision != now.bodies[i].revision) return true;
  return false;
}

}  // namespace

SimSession::SimSession(Simulation& simulation, double frame_period_s,
                       std::function<void(const SceneStatic&)> before_first_tick)
    : simulation_(simulation),
      frame_period_s_(frame_period_s),
      before_first_tick_(std::move(before_first_tick)),
      worker_([this] { work(); }) {}

SimSession::~SimSession() {
  {
    std::lock_guard lock(command_mutex_);
    mode_ = Mode::Quitting;
  }
  simulation_.request_stop();
  wake_.notify_all();
  worker_.join();
}

void SimSession::play() {
  {
    std::lock_guard lock(command_mutex_);
    if (mode_ != Mode::Paused) return;
    mode_ = Mode::Playing;
    pending_steps_ = 0;
  }
  wake_.notify_all();
}

void SimSession::pause() {
  {
    std::lock_guard lock(command_mutex_);
    if (mode_ != Mode::Playing) return;
    mode_ = Mode::Paused;
  }
  // Consumed when the run returns; should the run have just ended, the next run stops after
  // one tick and the worker simply waits again.
  simulation_.request_stop();
}

void SimSession::step() {
  {
    std::lock_guard lock(command_mutex_);
    if (mode_ != Mode::Paused) return;
    ++pending_steps_;
  }
  wake_.notify_all();
}

bool SimSession::playing() const {
  std::lock_guard lock(command_mutex_);
  return mode_ == Mode::Playing;
}

std::string SimSession::error() const {
  std::lock_guard lock(command_mutex_);
  return error_;
}

void SimSession::work() {
  // Frames reach the window from run() and step() alike; the clock is the Simulation's own.
  try {
    simulation_.attach(this);
  } catch (const std::exception& e) {
    std::lock_guard lock(command_mutex_);
    error_ = e.what();
  }
  const auto frame_ticks =
      static_cast<uint64_t>(std::max(1.0, std::round(frame_period_s_ / simulation_.dt())));
  for (;;) {
    RunOptions options;
    bool stepping = false;
    {
      std::unique_lock lock(command_mutex_);
      wake_.wait(lock, [this] { return mode_ != Mode::Paused || pending_steps_ > 0; });
      if (mode_ == Mode::Quitting) {
        simulation_.detach(this);
        return;
      }
      if (mode_ == Mode::Playing) {
        options.realtime = true;
        options.duration_s = kSessionSeconds;
      } else {
        --pending_steps_;
        stepping = true;
      }
      running_.store(true, std::memory_order_release);
    }
    try {
      if (stepping) {
        // Tick by tick up to the next frame: after a pause mid-frame, a whole frame period of
        // ticks would pass the frame it shows and stop between two.
        const uint64_t frames_before = frames_seen_.load(std::memory_order_relaxed);
        if (simulation_.tick() == 0) simulation_.step(0);  // the state before any tick is a frame
        for (uint64_t t = 0;
             t < frame_ticks && frames_seen_.load(std::memory_order_relaxed) == frames_before; ++t)
          simulation_.step(1);
      } else
        simulation_.run(options);
    } catch (const std::exception& e) {
      std::lock_guard lock(command_mutex_);
      error_ = e.what();
      if (mode_ == Mode::Playing) mode_ = Mode::Paused;
    }
    running_.store(false, std::memory_order_release);
  }
}

void SimSession::on_start(const SceneStatic& scene) {
  {
    std::lock_guard lock(slot_mutex_);
    if (have_scene_) return;
    scene_ = scene;
    have_scene_ = true;
  }
  if (before_first_tick_) before_first_tick_(scene);
}

void SimSession::on_frame(const SceneStatic& scene, const Snapshot& snapshot) {
  frames_seen_.fetch_add(1, std::memory_order_relaxed);
  std::lock_guard lock(slot_mutex_);
  slot_ = snapshot;  // assignment reuses the slot's buffers after the first frame
  slot_new_ = true;
  if (have_scene_ && reshaped(scene_, scene)) {  // the snapshot's node counts are the new mesh's
    scene_ = scene;
    ++scene_version_;
  }
}

bool SimSession::take_latest(Snapshot& out, SceneStatic& scene, uint64_t& scene_version) {
  std::lock_guard lock(slot_mutex_);
  if (!slot_new_) return false;
  out = slot_;
  slot_new_ = false;
  if (scene_version != scene_version_) {
    scene = scene_;
    scene_version = scene_version_;
  }
  return true;
}

bool SimSession::scene(SceneStatic& out) const {
  std::lock_guard lock(slot_mutex_);
  if (!have_scene_) return false;
  out = scene_;
  return true;
}

}  // namespace tacta::view
