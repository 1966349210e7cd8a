#include "systems/haptic_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "systems/body_systems.hpp"
#include "systems/device_systems.hpp"

namespace tacta {

HapticLoop::HapticLoop(World& world, TripleBuffer<Snapshot>& snapshots, size_t expected_ticks,
                       double duration_s)
    : world_(world), snapshots_(snapshots) {
  record_interval_s_ = world.scene().output.record_interval_s;
  faults_.reserve(64 + world.body_count() + world.device_count());
  body_status_.resize(world.body_capacity());  // bodies added while running count here too
  reshaped_.resize(world.body_capacity());
  device_status_.resize(world.device_count());
  reserve(expected_ticks, duration_s);
}

void HapticLoop::reserve(size_t expected_ticks, double duration_s) {
  // A session stepped on for hours stops growing its records at what the longest single run
  // keeps (kMaxRunTicks trace rows and tick durations, ~200 MB of node and energy rows); past
  // that, rows are dropped and counted and percentiles come from the ticks kept.
  constexpr size_t kRecordBytes = 200'000'000;
  constexpr size_t kTickDurations = kMaxRunTicks;
  const SceneDesc& scene = world_.scene();
  const size_t devices = world_.device_count();
  trace_.grow(expected_ticks * std::max<size_t>(devices, 1) + 16, kMaxRunTicks);
  size_t recorded_nodes = 0, probes = 0;
  for (size_t i = 0; i < world_.body_count(); ++i) {
    recorded_nodes += world_.body(i).recording.recorded_nodes.size();
    probes += world_.body(i).recording.probes.size();
  }
  const double interval_ticks =
      record_interval_s_ > 0 ? record_interval_s_ * scene.clock.haptic_rate_hz : 1.0;
  trajectory_.grow(
      static_cast<size_t>(static_cast<double>(expected_ticks) / std::max(interval_ticks, 1.0) + 2) *
          recorded_nodes,
      kRecordBytes / sizeof(TrajectoryRow));
  // From the run's duration (--duration may differ from the scene's), bounded with it at load.
  if (duration_s < 0) duration_s = static_cast<double>(expected_ticks) / scene.clock.haptic_rate_hz;
  const size_t records =
      static_cast<size_t>(static_cast<double>(expected_ticks) / std::max(interval_ticks, 1.0) + 2);
  probes_.grow(records * probes, kRecordBytes / sizeof(ProbeRow));
  const size_t frames = static_cast<size_t>(duration_s * scene.clock.render_rate_hz) + 4;
  energy_.grow(frames * world_.body_capacity() + 16, kRecordBytes / sizeof(EnergyRow));
  for (TickRecorder& r : stages_) r.grow(expected_ticks, kTickDurations);
  for (TickRecorder& r : haptic_parts_) r.grow(expected_ticks, kTickDurations);
}

const char* HapticLoop::stage_name(int stage) noexcept {
  static const char* const names[kStageCount] = {
      "device_read", "haptics", "models", "collision_response", "device_write", "surface_upkeep"};
  return stage >= 0 && stage < kStageCount ? names[stage] : "?";
}

const char* HapticLoop::haptic_part_name(int part) noexcept {
  static const char* const names[kHapticPartCount] = {"surface_update", "proxy_query", "coupling"};
  return part >= 0 && part < kHapticPartCount ? names[part] : "?";
}

BodySnapshot HapticLoop::sized_entry(size_t nodes, bool stress, size_t surface_vertices,
                                     const std::string& model, uint32_t revision) {
  BodySnapshot bs;
  bs.positions.assign(3 * nodes, 0.0);
  bs.velocities.assign(3 * nodes, 0.0);
  if (stress) bs.von_mises.assign(nodes, 0.0);
  bs.surface_positions.assign(3 * surface_vertices, 0.0);
  bs.model = model;
  bs.model.reserve(64);  // a swap copies the new name without reallocating
  bs.revision = revision;
  return bs;
}

BodySnapshot HapticLoop::body_prototype(const SoftBody& b) {
  BodySnapshot bs = sized_entry(b.node_count(), b.model.instance->has_stress(),
                                b.surface.mesh ? b.surface.mesh->positions.size() / 3 : 0,
                                b.model.instance->name(), b.shape.cuts.revision);
  bs.positions = b.nodes.positions;
  bs.velocities = b.nodes.velocities;
  if (b.surface.mesh) bs.surface_positions = b.surface.mesh->positions;
  return bs;
}

void HapticLoop::take_reshaped(size_t slot, std::array<BodySnapshot, 3>& entries) noexcept {
  if (slot >= reshaped_.size()) return;
  std::swap(reshaped_[slot].entries, entries);
  reshaped_[slot].used = 0;
}

Snapshot HapticLoop::make_prototype(World& world) {
  Snapshot s;
  for (size_t i = 0; i < world.body_count(); ++i) s.bodies.push_back(body_prototype(world.body(i)));
  s.devices.resize(world.device_count());
  return s;
}

bool HapticLoop::tick(uint64_t index, double time, double dt) noexcept {
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  const auto start = Clock::now();
  tick_index_ = index;
  tick_time_ = time;
  last_status_ = {};
  // The tick boundary: bodies requested in or out since the last tick (or due by the scene's
  // events) enter or leave before anything reads the world.
  world_.apply_entity_commands(time);
  take_model_swaps(world_, time);
  read_devices(world_, *this, time);
  sweep_blades(world_, time);
  const auto read_done = Clock::now();
  start_contact_sums(world_);
  if (haptics_ != nullptr) {
    haptics_->update_tools(world_);
    haptics_->refit_surfaces(time, dt);
    haptics_->move_proxies(world_);
    haptics_->couple(world_, time, dt);
    const HapticParts& parts = haptics_->parts();
    haptic_parts_[kSurfaceUpdate].record(parts.surface_update);
    haptic_parts_[kProxyQuery].record(parts.proxy_query);
    haptic_parts_[kCoupling].record(parts.coupling);
    last_status_.collision_bits |= haptics_->collision_bits();
  }
  const auto haptics_done = Clock::now();
  const bool healthy = step_bodies(world_, workers_, *this, time, dt);
  const auto models_done = Clock::now();
  if (healthy && response_ != nullptr) last_status_.collision_bits |= response_->respond(time, dt);
  collision_status_.add(last_status_.collision_bits, time);
  const auto response_done = Clock::now();
  // A fault anywhere this tick: no device renders a force from a state that cannot be trusted.
  write_devices(world_, *this, time + dt, time, !healthy, device_log_.get());
  if (haptics_ != nullptr) haptics_->after_write(world_);
  record(time + dt);
  const auto write_done = Clock::now();
  // The force is out: the hierarchies' upkeep for the next tick's queries waits no device.
  if (haptics_ != nullptr) {
    const uint32_t bits = haptics_->upkeep_surfaces(time + dt, dt);
    collision_status_.add(bits & ~last_status_.collision_bits, time);  // a tick counts once
    last_status_.collision_bits |= bits;
  }
  const auto end = Clock::now();
  stages_[kDeviceRead].record(ms(start, read_done));
  stages_[kHaptics].record(ms(read_done, haptics_done));
  stages_[kModels].record(ms(haptics_done, models_done));
  stages_[kResponse].record(ms(models_done, response_done));
  stages_[kDeviceWrite].record(ms(response_done, write_done));
  stages_[kSurfaceUpkeep].record(ms(write_done, end));
  last_tick_ms_ = ms(start, end);
  last_status_.error =
      last_status_.error || has_error_bit(StatusSource::Collision, last_status_.collision_bits);
  return should_continue();
}

bool HapticLoop::should_continue() const noexcept {
  // Every body gone (removed, or still to come) is not the end: one may be added.
  bool any_present = false;
  for (size_t i = 0; i < world_.body_count(); ++i) {
    const SoftBody b = world_.body(i);
    if (b.presence.state == BodyPresence::kPending) return true;
    if (!b.present()) continue;
    any_present = true;
    if (!b.fault.frozen) return true;
  }
  if (!any_present) return true;
  for (size_t d = 0; d < world_.device_count(); ++d) {
    const tacta_device_state s = world_.device(d).link.state;
    if (s == TACTA_DEVICE_CONNECTED || s == TACTA_DEVICE_DISCONNECTED) return true;
  }
  return false;
}

void HapticLoop::device_raised(size_t device, uint32_t bit) noexcept {
  last_status_.device_bits |= bit;
  last_status_.error = last_status_.error || has_error_bit(StatusSource::Device, bit);
  device_status_[device].add(bit, tick_time_);
}

void HapticLoop::device_stopped(size_t device, double time) noexcept {
  const DeviceComponents dev = world_.device(device);
  FaultRecord f{time, -1, static_cast<int>(device), static_cast<uint32_t>(dev.link.state), {}};
  std::snprintf(f.reason.data(), f.reason.size(), "device '%.40s': %.150s", dev.link.name.c_str(),
                dev.link.status_reason.data());
  faults_.push(f);
}

void HapticLoop::stepped(size_t body, uint32_t bits, double time) noexcept {
  last_status_.model_bits |= bits;
  last_status_.error = last_status_.error || has_error_bit(StatusSource::Model, bits);
  body_status_[body].add(bits, time);
}

void HapticLoop::start_workers(bool lockstep, size_t expected_ticks) {
  workers_.resize(world_.body_count());
  const double haptic_rate = world_.scene().clock.haptic_rate_hz;
  for (size_t i = 0; i < world_.body_count(); ++i) {
    const SoftBody b = world_.body(i);
    if (!b.settings.own_thread) continue;
    const auto steps = static_cast<size_t>(static_cast<double>(expected_ticks) / haptic_rate /
                                           b.settings.period_s) +
                       2;
    if (!workers_[i])
      workers_[i] = std::make_unique<BodyWorker>(b, world_.scene().gravity, lockstep, steps);
    workers_[i]->start();
  }
}

void HapticLoop::stop_workers() noexcept {
  for (size_t i = 0; i < workers_.size(); ++i) {
    if (!workers_[i]) continue;
    workers_[i]->stop();
    // The step still in flight when the run ended was collected by stop(): a fault in it is
    // reported like any other, not lost with the run.
    const StepOutcome& out = workers_[i]->last_outcome();
    const SoftBody b = world_.body(i);
    if (out.why != nullptr && !b.fault.frozen && b.present())
      faulted(i, out.bits, out.why, tick_time_);
  }
}

void HapticLoop::faulted(size_t index, uint32_t bits, const char* why, double time) noexcept {
  const SoftBody b = world_.body(index);
  b.fault.frozen = true;
  b.fault.bits = bits;
  b.fault.time_s = time;
  std::snprintf(b.fault.reason.data(), b.fault.reason.size(),
                "%s (model '%s', step bits 0x%x); body frozen at t = %.6g s", why,
                b.model.instance->name(), bits, time);
  FaultRecord f{time, static_cast<int>(index), -1, bits, {}};
  std::snprintf(f.reason.data(), f.reason.size(), "body '%.40s': %.150s", b.info.name.c_str(),
                b.fault.reason.data());
  faults_.push(f);
}

void HapticLoop::record(double time) noexcept {
  trace_devices(world_, time, last_tick_ms_, trace_);
  if (record_interval_s_ > 0 && time + 1e-12 < next_record_s_) return;
  next_record_s_ += record_interval_s_;
  record_bodies(world_, time, trajectory_, probes_);
}

void HapticLoop::capture(Snapshot& s, double time) const noexcept {
  s.time_s = time;
  s.tick = tick_index_;
  s.last_tick_ms = last_tick_ms_;
  for (size_t i = 0; i < world_.body_count(); ++i) {
    const SoftBody b = world_.body(i);
    if (i >= s.bodies.size())
      continue;  // added after the render task started (publish: energy rows)
    BodySnapshot& bs = s.bodies[i];
    bs.present = b.present();
    if (b.presence.state == BodyPresence::kPending) continue;
    // An entry of an older revision (a cut whose entries have not reached this slot) keeps what
    // it drew: its arrays follow that revision's description.
    if (bs.revision != b.shape.cuts.revision || bs.positions.size() != b.nodes.positions.size())
      continue;
    std::copy(b.nodes.positions.begin(), b.nodes.positions.end(), bs.positions.begin());
    std::copy(b.nodes.velocities.begin(), b.nodes.velocities.end(), bs.velocities.begin());
    if (b.surface.mesh)
      interpolate_to_surface(*b.surface.mesh, b.nodes.positions.data(),
                             bs.surface_positions.data());
    const BodyWorker* w = worker(i);
    // A worker body's model may be mid-step on its thread: use what the worker computed.
    if (w != nullptr) {
      if (!bs.von_mises.empty() && w->has_stress())
        std::copy(w->von_mises().begin(), w->von_mises().end(), bs.von_mises.begin());
    } else if (!bs.von_mises.empty() && b.model.instance->has_stress()) {
      b.model.instance->node_stress(b.nodes.positions.data(), bs.von_mises.data());
    }
    if (bs.model != b.model.instance->name())
      bs.model.assign(b.model.instance->name());  // capacity reserved up front
    bs.frozen = b.fault.frozen;
    bs.kinetic_J = b.kinetic_energy();
    bs.elastic_J = w != nullptr ? w->elastic_energy()
                                : b.model.instance->elastic_energy(b.nodes.positions.data());
    bs.max_displacement_m = b.fault.max_displacement_m;
  }
  for (size_t d = 0; d < world_.device_count(); ++d) {
    const DeviceComponents dev = world_.device(d);
    DeviceSnapshot& ds = s.devices[d];
    for (int a = 0; a < 3; ++a) ds.position[static_cast<size_t>(a)] = dev.link.sample.position[a];
    ds.proxy = dev.contact.proxy;
    ds.force = dev.contact.force;
    ds.contact = dev.contact.in_contact;
    ds.touched_body = dev.contact.touched_body;
  }
}

void HapticLoop::publish(double time) noexcept {
  Snapshot& s = snapshots_.write_slot();
  for (size_t i = 0; i < s.bodies.size() && i < reshaped_.size(); ++i) {
    Reshaped& r = reshaped_[i];
    if (r.used < r.entries.size() && s.bodies[i].revision != r.entries[r.used].revision &&
        r.entries[r.used].revision == world_.body(i).shape.cuts.revision)
      std::swap(s.bodies[i], r.entries[r.used++]);
  }
  capture(s, time);
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    const BodySnapshot& bs = s.bodies[i];
    if (bs.present)
      energy_.push(
          {time, static_cast<uint32_t>(i), bs.kinetic_J, bs.elastic_J, bs.max_displacement_m});
  }
  for (size_t i = s.bodies.size(); i < world_.body_count();
       ++i) {  // added after the render task started
    const SoftBody b = world_.body(i);
    if (b.present())
      energy_.push({time, static_cast<uint32_t>(i), b.kinetic_energy(),
                    b.model.instance->elastic_energy(b.nodes.positions.data()),
                    b.fault.max_displacement_m});
  }
  snapshots_.publish();
}

}  // namespace tacta
