#include "simulation/realtime_cuts.hpp"

#include <algorithm>
#include <pthread.h>
#include <string>
#include <utility>

#include "simulation/simulation_impl.hpp"
#include "tacta/error.hpp"
#include "tacta/log.hpp"

namespace tacta {

RealtimeCuts::RealtimeCuts(World& world, SceneCuts& schedule, CollisionContext* collision,
                           HapticInteraction* haptics, ClockSession& clock)
    : world_(world), schedule_(schedule), collision_(collision), haptics_(haptics), clock_(clock) {
  sweep_.reserve(9 * BladeSweep::kCapacityTriangles);
  warned_.assign(world.device_count(), 0);
}

RealtimeCuts::~RealtimeCuts() {
  if (!worker_.joinable()) return;
  // The worker's hand-over would overwrite a stop given while it prepares or tidies up.
  for (uint32_t state = state_.load(); state == kPosted || state == kApplied; state = state_.load())
    state_.wait(state);
  hand_over(kStop);
  worker_.join();
}

void RealtimeCuts::start() {
  if (worker_.joinable()) return;
  reserve();
  state_.store(kIdle);
  worker_ = std::thread([this] { run(); });
  // Named so the realtime session lowers it and keeps it off the haptic CPU like the others.
  pthread_setname_np(worker_.native_handle(), "tacta-cut");
}

void RealtimeCuts::reserve() {
  size_t most = 0;
  for (size_t slot = 0; slot < world_.body_count(); ++slot)
    most = std::max(most, world_.body_nodes(slot).positions.size());
  request_.positions.reserve(most + most / 4);
  request_.velocities.reserve(most + most / 4);
  if (collision_ != nullptr) collision_->reserve_view_copy(request_.view);
}

void RealtimeCuts::at_boundary(double time) noexcept {
  const uint32_t state = state_.load(std::memory_order_acquire);
  if (state == kReady)
    install(time);
  else if (state == kIdle)
    post_next(time);
}

bool RealtimeCuts::post_next(double time) noexcept {
  if (repost_) {
    repost_ = false;
    return post(request_.slot, request_.device, request_.event, request_.triangles, request_.mode);
  }
  while (sweeping_) {  // a blade's sweep, body by body
    if (sweep_next_ >= world_.body_count()) {
      sweeping_ = false;
      break;
    }
    const size_t slot = sweep_next_++;
    if (schedule_.sweep_cuts(sweep_device_, slot))
      return post(slot, static_cast<int>(sweep_device_), nullptr, sweep_,
                  world_.tool(sweep_device_).blade.desc.mode);
  }
  if (const BodyEventDesc* e = schedule_.due_event(time)) {
    schedule_.pass_event();
    const int slot = world_.body_index(e->cut->body);
    return post(slot < 0 ? world_.body_count() : static_cast<size_t>(slot), -1, e,
                e->cut->triangles, e->cut->mode);
  }
  for (size_t d = 0; d < world_.device_count(); ++d) {
    BladeSweep& blade = world_.tool(d).blade;
    if (!schedule_.sweep_due(blade, time)) continue;
    // Taken whole: the blade starts its next sweep in its own buffer while this one is cut.
    sweep_.assign(blade.swept.begin(), blade.swept.end());  // same capacity: no allocation
    world_.device(d).stats.blade_triangles_dropped += std::exchange(blade.dropped, 0);
    blade.swept.clear();
    blade.first_s = -1;
    blade.released = false;
    sweeping_ = true;
    sweep_device_ = d;
    sweep_next_ = 0;
    return post_next(time);
  }
  return false;
}

bool RealtimeCuts::post(size_t slot, int device, const BodyEventDesc* event,
                        std::span<const double> triangles, CutMode mode) noexcept {
  Request& r = request_;
  r.slot = slot;
  r.device = device;
  r.event = event;
  r.triangles = triangles;
  r.mode = mode;
  r.asked = std::chrono::steady_clock::now();
  r.positions.clear();
  r.velocities.clear();
  if (slot < world_.body_count()) {
    const SoftBody b = world_.body(slot);
    const bool room = b.nodes.positions.size() <= r.positions.capacity() &&
                      (collision_ == nullptr || collision_->copy_view(r.view));
    if (!room) {  // outgrown (a body added while running): the worker reserves, then it is asked again
      repost_ = true;
      prepared_.ok = false;
      hand_over(kApplied);
      return false;
    }
    r.positions.assign(b.nodes.positions.begin(), b.nodes.positions.end());
    r.velocities.assign(b.nodes.velocities.begin(), b.nodes.velocities.end());
  }
  hand_over(kPosted);
  return true;
}

void RealtimeCuts::prepare() noexcept {
  Prepared& p = prepared_;
  const Request& r = request_;
  try {
    if (r.slot >= world_.body_count())
      throw InputError(
          {world_.scene().path, 0, 0, "events"},
          "body '" + (r.event ? r.event->cut->body : std::string()) + "' is not in the scene");
    p.cut = prepare_cut(world_, r.slot, r.triangles, r.mode, r.positions, r.velocities);
    if (p.cut.changed) {
      if (collision_ != nullptr) p.surface = collision_->prepare_replacement(r.slot, p.cut, r.view);
      p.picture = clock_.prepare_picture(p.cut);
    }
    p.ok = true;
  } catch (const std::exception& e) {
    p = Prepared{};
    if (r.event != nullptr)
      log_warning("the cut at " + std::to_string(r.event->time) + " s was not made: " + e.what());
    else if (r.device >= 0 && !std::exchange(warned_[static_cast<size_t>(r.device)], 1))
      log_warning("device '" + world_.device(static_cast<size_t>(r.device)).link.name +
                  "': its blade's cut was not made: " + e.what());
  }
  hand_over(kReady);
}

void RealtimeCuts::install(double time) noexcept {
  const auto start = std::chrono::steady_clock::now();
  Prepared& p = prepared_;
  const Request& r = request_;
  // A model swap or a body's surface added since: prepared again from the state now.
  if (p.ok && (!still_fits(world_, p.cut) ||
               (collision_ != nullptr && !collision_->replacement_fits(p.surface)))) {
    p.ok = false;
    repost_ = true;
    hand_over(kApplied);
    return;
  }
  if (p.ok) {
    const CutSummary summary = apply_cut(world_, p.cut, time);
    p.installed = true;
    if (summary.changed) {
      if (collision_ != nullptr) collision_->apply_replacement(p.surface);
      if (haptics_ != nullptr) haptics_->surface_changed(world_, r.slot);
      clock_.reshaped_at_tick(p.picture);
      if (r.device >= 0) ++world_.device(static_cast<size_t>(r.device)).stats.blade_cuts;
    }
    // From the moment the cut was asked to the new mesh in place, and the install's own part.
    CutTotals& totals = world_.body(r.slot).shape.cuts;
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - r.asked).count();
    totals.wall_ms_total += ms;
    totals.wall_ms_max = std::max(totals.wall_ms_max, ms);
    double& install_ms = world_.body(r.slot).shape.install_ms_max;
    install_ms =
        std::max(install_ms, std::chrono::duration<double, std::milli>(now - start).count());
  } else if (r.device >= 0) {
    ++world_.device(static_cast<size_t>(r.device)).stats.blade_cuts_refused;
  }
  hand_over(kApplied);
}

void RealtimeCuts::run() noexcept {
  for (;;) {
    uint32_t state = state_.load(std::memory_order_acquire);
    while (state == kIdle || state == kReady) {
      state_.wait(state, std::memory_order_acquire);
      state = state_.load(std::memory_order_acquire);
    }
    if (state == kStop) return;
    if (state == kPosted) {
      prepare();
      continue;
    }
    // kApplied: keep or free what the install replaced, then room for the next request.
    try {
      if (prepared_.installed && prepared_.cut.changed) retire_cut(world_, prepared_.cut);
      prepared_ = Prepared{};
      reserve();
    } catch (const std::exception& e) {
      log_warning(std::string("realtime cut: ") + e.what());
    }
    hand_over(kIdle);
  }
}

void RealtimeCuts::finish(double time) noexcept {
  if (!worker_.joinable()) return;
  // What fell due in the run is made before it returns, at its end: the cut in flight, then
  // any still waiting for it (the next run would otherwise make them late).
  for (;;) {
    const uint32_t state = state_.load(std::memory_order_acquire);
    if (state == kPosted || state == kApplied) {
      state_.wait(state, std::memory_order_acquire);
    } else if (state == kReady) {
      install(time);
    } else {
      post_next(time);
      if (state_.load(std::memory_order_acquire) == kIdle) break;  // nothing was due
    }
  }
  hand_over(kStop);
  worker_.join();
}

}  // namespace tacta
