// Simulation::cut and the scene's cut events: a cut is made on the thread that runs the ticks,
// between two of them (world/body_cut.hpp), then the collision surface, the haptic proxies and
// the render description follow the body's new mesh.
#include <algorithm>
#include <chrono>
#include <limits>
#include <utility>

#include "simulation/simulation_impl.hpp"
#include "tacta/log.hpp"
#include "world/body_cut.hpp"

namespace tacta {

CutSummary Simulation::Impl::cut(size_t slot, std::span<const double> triangles, CutMode mode) {
  const auto start = std::chrono::steady_clock::now();
  const double time = clock ? clock->time() : 0.0;
  // The halves a realtime cut runs on two threads, here in a row: the shape and its collision
  // surface (fresh plugin instances built over a copy of the view) prepared, then both applied.
  PreparedCut prepared = prepare_cut(world, slot, triangles, mode, world.body(slot).nodes.positions,
                                     world.body(slot).nodes.velocities);
  SurfaceReplacement replacement;
  if (prepared.changed && collision) {
    ViewCopy copy;
    collision->reserve_view_copy(copy);
    collision->copy_view(copy);
    replacement = collision->prepare_replacement(slot, prepared, copy);
  }
  const CutSummary summary = apply_cut(world, prepared, time);
  if (collision) collision->apply_replacement(replacement);
  retire_cut(world, prepared);
  if (summary.changed) {
    // The hierarchies refit now from the bodies as the last tick left them, so the next tick's
    // proxy pass goes on by slices.
    if (collision) collision->build_between_ticks(time, 1.0 / world.scene().clock.haptic_rate_hz);
    if (haptics) haptics->surface_changed(world, slot);
    if (clock) clock->body_reshaped(slot);
  }
  CutTotals& totals = world.body(slot).shape.cuts;
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  totals.wall_ms_total += ms;
  totals.wall_ms_max = std::max(totals.wall_ms_max, ms);
  return summary;
}

CutSummary Simulation::cut(BodyHandle body, std::span<const double> triangles, CutMode mode) {
  const size_t slot = impl_->body_at(body);
  if (impl_->running.load())
    throw InputError({impl_->world.scene().path, 0, 0, "cut"},
                     "cut: a body is cut between steps, not while run() runs");
  return impl_->cut(slot, triangles, mode);
}

uint32_t Simulation::body_revision(BodyHandle body) const {
  return impl_->world.body(impl_->body_at(body)).shape.cuts.revision;
}

SceneCuts::SceneCuts(World& world, Cut cut) : world_(world), cut_(std::move(cut)) {
  for (const BodyEventDesc& e : world.scene().events) {
    if (!e.cut) continue;
    // What makes a body uncuttable is known at load: say so now, at the event, not mid-run.
    const int slot = world.body_index(e.cut->body);
    if (slot >= 0)  // else a body an earlier event adds: checked when the cut comes
      if (const std::string why = cut_unsupported(world.body(static_cast<size_t>(slot)));
          !why.empty())
        throw InputError(e.cut->where, "the cut at " + std::to_string(e.time) + " s: " + why);
    events_.push_back(&e);
  }
  std::stable_sort(
      events_.begin(), events_.end(),
      [](const BodyEventDesc* a, const BodyEventDesc* b) { return a->time < b->time; });
}

double SceneCuts::next_due_s() const noexcept {
  double due =
      next_ < events_.size() ? events_[next_]->time : std::numeric_limits<double>::infinity();
  for (size_t d = 0; d < world_.device_count(); ++d) {
    const BladeSweep& blade = world_.tool(d).blade;
    if (blade.first_s < 0) continue;
    due = std::min(due, blade.released ? 0.0 : blade.first_s + blade.desc.interval_s);
  }
  return due;
}

void SceneCuts::skip_past(double time) noexcept {
  const double half_tick = 0.5 / world_.scene().clock.haptic_rate_hz;
  while (next_ < events_.size() && events_[next_]->time <= time + half_tick) ++next_;
}

const BodyEventDesc* SceneCuts::due_event(double time) const noexcept {
  const double half_tick = 0.5 / world_.scene().clock.haptic_rate_hz;
  return next_ < events_.size() && events_[next_]->time <= time + half_tick ? events_[next_]
                                                                            : nullptr;
}

bool SceneCuts::sweep_due(const BladeSweep& blade, double time) const noexcept {
  const double half_tick = 0.5 / world_.scene().clock.haptic_rate_hz;
  return blade.first_s >= 0 &&
         (blade.released || blade.first_s + blade.desc.interval_s <= time + half_tick);
}

bool SceneCuts::sweep_cuts(size_t device, size_t slot) const noexcept {
  const std::string& touches = world_.device(device).link.desc.touches;
  const SoftBody b = world_.body(slot);
  if (!b.present()) return false;
  return touches.empty() ? (b.model.instance->claims() & TACTA_MODEL_CLAIM_TOPOLOGY_EDITS) != 0
                         : b.info.name == touches;
}

void SceneCuts::run_due(double time) {
  for (; due_event(time) != nullptr; ++next_) {
    const CutEventDesc& cut = *events_[next_]->cut;
    const int slot = world_.body_index(cut.body);
    try {
      if (slot < 0 || !world_.body_present(static_cast<size_t>(slot)))
        throw InputError(cut.where, "body '" + cut.body + "' is not in the scene");
      cut_(static_cast<size_t>(slot), cut.triangles, cut.mode);
    } catch (const InputError& e) {
      log_warning(std::string("the cut at ") + std::to_string(events_[next_]->time) +
                  " s was not made: " + e.what());
    }
  }
  for (size_t d = 0; d < world_.device_count(); ++d)
    if (BladeSweep& blade = world_.tool(d).blade; sweep_due(blade, time)) cut_sweep(d, blade);
}

// The bodies a blade cuts: the one its device touches (`touches`), else every body in the scene
// whose model takes topology edits (a blade passing others by cuts nothing).
void SceneCuts::cut_sweep(size_t device, BladeSweep& blade) {
  const DeviceComponents dev = world_.device(device);
  dev.stats.blade_triangles_dropped += std::exchange(blade.dropped, 0);
  for (size_t slot = 0; slot < world_.body_count(); ++slot) {
    if (!sweep_cuts(device, slot)) continue;
    try {
      if (cut_(slot, blade.swept, blade.desc.mode).changed) ++dev.stats.blade_cuts;
    } catch (const InputError& e) {
      if (dev.stats.blade_cuts_refused++ == 0)  // once: a refusal repeats at every sweep
        log_warning("device '" + dev.link.name + "': its blade's cut was not made: " + e.what());
    }
  }
  blade.swept.clear();  // keeps its capacity: the tick adds to it without allocating
  blade.first_s = -1;
  blade.released = false;
}

}  // namespace tacta
