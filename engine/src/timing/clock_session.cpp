#include "timing/clock_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "systems/device_surface_feed.hpp"
#include "timing/body_descriptions.hpp"

namespace tacta {

namespace {

using SteadyClock = std::chrono::steady_clock;

// run_schedule counts its ticks from 0; this puts them on the session's clock (tick `base` on).
class OffsetTask final : public HapticTask {
 public:
  OffsetTask(HapticLoop& loop, uint64_t base, double dt, BetweenTicks* between,
             AtTickBoundary* at_boundary)
      : loop_(loop), base_(base), dt_(dt), between_(between), at_boundary_(at_boundary) {}
  bool tick(uint64_t index, double, double dt) noexcept override {
    // Time from the tick index, not by accumulation, so long sessions do not drift.
    const double time = static_cast<double>(base_ + index) * dt_;
    if (at_boundary_ != nullptr) at_boundary_->at_boundary(time);
    return loop_.tick(base_ + index, time, dt);
  }
  void publish(double time) noexcept override {
    const auto index = static_cast<uint64_t>(std::llround(time / dt_));
    loop_.publish(static_cast<double>(base_ + index) * dt_);
  }
  void between_ticks(double time) override {
    if (between_ != nullptr) between_->after_tick(time + static_cast<double>(base_) * dt_, dt_);
  }

 private:
  HapticLoop& loop_;
  uint64_t base_;
  double dt_;
  BetweenTicks* between_;
  AtTickBoundary* at_boundary_;  // realtime runs only
};

}  // namespace

SceneStatic describe_scene(World& world) {
  SceneStatic s;
  s.name = world.scene().name;
  s.haptic_rate_hz = world.scene().clock.haptic_rate_hz;
  for (size_t i = 0; i < world.body_count(); ++i) s.bodies.push_back(describe_body(world.body(i)));
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceComponents dev = world.device(d);
    s.devices.push_back(
        {dev.link.name, dev.link.desc.tool.radius, dev.link.device->capabilities().peak_force});
  }
  return s;
}

namespace {

// Every model starts from its body's initial state; the energy at t = 0 is kept for the report.
std::vector<double> begin_models(World& world) {
  std::vector<double> energy;
  const double haptic_dt = 1.0 / world.scene().clock.haptic_rate_hz;
  for (size_t i = 0; i < world.body_count(); ++i)
    energy.push_back(begin_model(world.body(i), 0.0, haptic_dt));
  return energy;
}

}  // namespace

ClockSession::ClockSession(World& world, HapticInteraction* haptics, CollisionResponse* response)
    : initial_energy_J(begin_models(world)),
      world_(world),
      dt_(1.0 / world.scene().clock.haptic_rate_hz),
      frame_clock_{1.0 / world.scene().clock.render_rate_hz},
      scene_static_(describe_scene(world)),
      snapshots_(HapticLoop::make_prototype(world)),
      loop_(world, snapshots_, 0, 0.0),
      chains_(world.body_capacity()),
      render_(snapshots_, scene_static_, chains_),
      surface_feed_(make_device_surface_feed(world)) {
  loop_.set_haptics(haptics);
  loop_.set_response(response);
  if (surface_feed_) attach(surface_feed_.get());
}

ClockSession::~ClockSession() { loop_.stop_workers(); }

void ClockSession::add_body(size_t slot) {
  // Slots are filled in order; the snapshots and the description grow to cover this one.
  while (scene_static_.bodies.size() <= slot) {
    const SoftBody b = world_.body(scene_static_.bodies.size());
    scene_static_.bodies.push_back(describe_body(b));
    const BodySnapshot prototype = HapticLoop::body_prototype(b);
    snapshots_.for_each_slot([&](Snapshot& s) { s.bodies.push_back(prototype); });
  }
}

void ClockSession::body_reshaped(size_t slot) {
  if (slot >= scene_static_.bodies.size()) return;
  const SoftBody b = world_.body(slot);
  scene_static_.bodies[slot] = describe_body(b);
  const BodySnapshot prototype = HapticLoop::body_prototype(b);
  snapshots_.for_each_slot([&](Snapshot& s) { s.bodies[slot] = prototype; });
}

PreparedPicture ClockSession::prepare_picture(const PreparedCut& cut) const {
  PreparedPicture p;
  p.slot = cut.slot;
  if (!cut.changed) return p;
  const SoftBody b = world_.body(cut.slot);
  p.description = std::make_unique<DescribedRevision>();
  p.description->body = describe_prepared(b, cut);
  const size_t surface_vertices = cut.shape.surface ? cut.shape.surface->positions.size() / 3 : 0;
  for (BodySnapshot& e : p.entries)
    e = HapticLoop::sized_entry(cut.node_source.size(), cut.models.instance->has_stress(),
                                surface_vertices, cut.models.instance->name(),
                                p.description->body.revision);
  return p;
}

void ClockSession::reshaped_at_tick(PreparedPicture& picture) noexcept {
  if (!picture.description) return;
  chains_.publish(picture.slot, std::move(picture.description));
  loop_.take_reshaped(picture.slot, picture.entries);
}

void ClockSession::follow_reshaped_bodies() {
  for (size_t i = 0; i < scene_static_.bodies.size(); ++i) {
    const uint32_t revision = world_.body(i).shape.cuts.revision;
    if (scene_static_.bodies[i].revision == revision) continue;
    if (const BodyStatic* d = chains_.find(i, revision)) scene_static_.bodies[i] = *d;
  }
}

const SceneStatic& ObserverRenderTask::follow(const Snapshot& s) {
  bool behind = false;  // some snapshot entry follows another revision than the description
  for (size_t i = 0; i < s.bodies.size() && i < scene_.bodies.size(); ++i)
    behind = behind || s.bodies[i].revision != scene_.bodies[i].revision;
  if (!behind) return scene_;
  if (view_.bodies.size() != scene_.bodies.size()) view_ = scene_;
  for (size_t i = 0; i < s.bodies.size() && i < view_.bodies.size(); ++i) {
    const uint32_t want = s.bodies[i].revision;
    if (view_.bodies[i].revision == want) continue;
    if (scene_.bodies[i].revision == want)
      view_.bodies[i] = scene_.bodies[i];
    else if (const BodyStatic* d = chains_.find(i, want))
      view_.bodies[i] = *d;
  }
  return view_;
}

void ClockSession::reserve(uint64_t ticks) {
  loop_.reserve(ticks, static_cast<double>(ticks) * dt_);
  step_ms_.grow(ticks, kMaxRunTicks);
}

void ClockSession::attach(FrameObserver* observer) {
  if (std::find(render_.observers.begin(), render_.observers.end(), observer) !=
      render_.observers.end())
    return;
  observer->on_start(scene_static_);
  render_.observers.push_back(observer);
}

void ClockSession::detach(FrameObserver* observer) { std::erase(render_.observers, observer); }

void ClockSession::start_workers(bool lockstep, uint64_t ticks) {
  const int mode = lockstep ? 1 : 0;
  if (workers_mode_ == mode) return;
  loop_.stop_workers();
  loop_.start_workers(lockstep, ticks);
  workers_mode_ = mode;
}

uint64_t ClockSession::step(uint64_t ticks, const std::atomic<bool>* stop) {
  reserve(ticks);
  start_workers(true, ticks);
  if (tick_ == 0 && frames_ == 0) {  // the state before any tick, shown once
    loop_.publish(0.0);
    render_.frame(0.0);
    ++frames_;
  }
  uint64_t ran = 0;
  step_status_ = {};
  for (; ran < ticks; ++ran) {
    const auto t0 = SteadyClock::now();
    const bool keep_going = loop_.tick(tick_, time(), dt_);
    step_ms_.record(std::chrono::duration<double, std::milli>(SteadyClock::now() - t0).count());
    step_status_.merge(loop_.last_status());
    ++tick_;
    if (between_ != nullptr) between_->after_tick(time(), dt_);
    const bool stopped = !keep_going || (stop != nullptr && stop->load(std::memory_order_relaxed));
    if (frame_clock_.due(time()) || stopped) {
      loop_.publish(time());
      render_.frame(time());
      ++frames_;
    }
    if (stopped) {
      ++ran;
      break;
    }
  }
  return ran;
}

ScheduleResult ClockSession::run(const ScheduleOptions& options) {
  const auto ticks =
      static_cast<uint64_t>(std::llround(options.duration_s * options.haptic_rate_hz));
  reserve(ticks + 1);
  start_workers(options.mode == ClockMode::Lockstep, ticks + 1);
  const bool realtime = options.mode == ClockMode::Realtime;
  AtTickBoundary* at_boundary = realtime ? at_boundary_ : nullptr;
  if (at_boundary != nullptr) at_boundary->start();
  OffsetTask task(loop_, tick_, dt_, between_, at_boundary);
  last_run_ = run_schedule(task, render_, options);
  if (at_boundary != nullptr)
    at_boundary->finish(static_cast<double>(tick_ + last_run_.ticks) * dt_);
  follow_reshaped_bodies();
  tick_ += last_run_.ticks;
  frames_ += last_run_.frames;
  // Stopping the workers finishes and keeps a step still in flight, so the run's final state
  // (and its state hash) includes it; the next batch starts them again in its own mode.
  loop_.stop_workers();
  workers_mode_ = -1;
  frame_clock_.due(time());  // the run drew its own frames: the next step's frame is past its end
  return last_run_;
}

ScheduleResult ClockSession::totals() const {
  ScheduleResult r = last_run_;
  r.ticks = tick_;
  r.frames = frames_;
  if (step_ms_.count() > 0 && last_run_.ticks == 0) r.tick = step_ms_.summary();
  return r;
}

}  // namespace tacta
