// The 1 kHz task, its stages named in tick(): device read, tool update, refit, proxy, coupling,
// model step (boundary motion and fault handling within), contact response, device write,
// records. Runs on the haptic thread; allocates nothing, takes no lock, throws nothing.
#pragma once

#include <array>
#include <memory>

#include "haptic_interaction/haptic_interaction.hpp"
#include "output/recorders.hpp"
#include "systems/body_systems.hpp"
#include "systems/body_worker.hpp"
#include "systems/status_bits.hpp"
#include "tacta/device_log.hpp"
#include "tacta/sim/scheduler.hpp"
#include "tacta/sim/snapshot.hpp"
#include "tacta/sim/tick_stats.hpp"
#include "tacta/sim/triple_buffer.hpp"
#include "world/world.hpp"

namespace tacta {

class CheckpointWriter;
class CheckpointReader;

// A fault as report.json lists it.
struct FaultRecord {
  double time_s;
  int body;    // -1 when it is a device's
  int device;  // -1 when it is a body's
  uint32_t bits;
  std::array<char, 256> reason;
};

class HapticLoop final : public HapticTask, private TickEvents {
 public:
  // Record buffers are reserved for `expected_ticks` ticks and `duration_s` s of frames
  // (negative: expected_ticks at the scene's haptic rate).
  HapticLoop(World& world, TripleBuffer<Snapshot>& snapshots, size_t expected_ticks,
             double duration_s = -1);
  // Grows the record buffers for `expected_ticks` (`duration_s` s of frames) more; allocates.
  void reserve(size_t expected_ticks, double duration_s = -1);
  // The haptic side (devices' tools, proxies and couplings) and the contact response this loop
  // runs; either may be absent (no device; collision off). Not owned.
  void set_haptics(HapticInteraction* haptics) noexcept { haptics_ = haptics; }
  void set_response(CollisionResponse* response) noexcept { response_ = response; }
  // Keeps the first device's samples and sent forces (a replayable session log), `ticks` at most.
  void enable_device_log(size_t ticks) { device_log_ = std::make_unique<DeviceLogRecorder>(ticks); }
  const DeviceLogRecorder* device_log() const { return device_log_.get(); }

  // Bodies with step_thread: own get their worker threads here (start of run(); allocates) and
  // lose them in stop_workers (end of run(): a step in flight is finished and kept). Lockstep
  // waits for each step at its boundary; realtime never waits.
  void start_workers(bool lockstep, size_t expected_ticks);
  void stop_workers() noexcept;
  const BodyWorker* worker(size_t body) const {
    return body < workers_.size() ? workers_[body].get() : nullptr;
  }

  // False only when the run should end: every body is frozen (nothing left to step) and no
  // device is connected or waiting to reconnect (nobody holds a tool).
  bool tick(uint64_t index, double time, double dt) noexcept override;
  const TickStatus& last_status() const noexcept { return last_status_; }
  // Ticks each status bit was seen on, per body (model steps), per device, for collision.
  const StatusCounter& body_status(size_t body) const { return body_status_[body]; }
  const StatusCounter& device_status(size_t device) const { return device_status_[device]; }
  const StatusCounter& collision_status() const { return collision_status_; }
  void publish(double time) noexcept override;
  // Copies the current state into `s` (sized by make_prototype) without recording it: what
  // publish() hands the render task, and what a picture between steps draws.
  void capture(Snapshot& s, double time) const noexcept;

  // Checkpoints: the records so far, status counters and the record cadence
  // (checkpoint/loop_state.cpp). Between ticks only.
  void save_state(CheckpointWriter& out) const;
  void load_state(CheckpointReader& in);

  const Recorder<TraceRow>& trace() const { return trace_; }
  const Recorder<TrajectoryRow>& trajectory() const { return trajectory_; }
  const Recorder<ProbeRow>& probes() const { return probes_; }
  const Recorder<EnergyRow>& energy() const { return energy_; }
  const Recorder<FaultRecord>& faults() const { return faults_; }
  // A cut installed at a tick boundary while the render task runs: body `slot`'s snapshot entries
  // for its new revision, one per triple-buffer slot, built off the tick. publish() exchanges one
  // into each slot it fills that still follows an older revision; `entries` gets back what was
  // pending before (to be freed off the tick). Allocates nothing.
  void take_reshaped(size_t slot, std::array<BodySnapshot, 3>& entries) noexcept;
  // A prototype snapshot with every buffer sized, for building the triple buffer.
  static BodySnapshot body_prototype(const SoftBody& body);  // one body's entry, sized for it
  // An entry sized for `nodes` nodes, von Mises values when `stress`, `surface_vertices` embedded
  // surface vertices, at mesh `revision` (zeros; `model` reserved for a swap's longer name).
  static BodySnapshot sized_entry(size_t nodes, bool stress, size_t surface_vertices,
                                  const std::string& model, uint32_t revision);
  static Snapshot make_prototype(World& world);

  // Where a tick's time goes (ms per tick, every tick), for report.json's tick_breakdown_ms.
  enum Stage {
    kDeviceRead,
    kHaptics,
    kModels,
    kResponse,
    kDeviceWrite,
    kSurfaceUpkeep,  // after the write: the proxy's hierarchies follow the tick's motion
    kStageCount
  };
  static const char* stage_name(int stage) noexcept;
  const TickRecorder& stage(int s) const { return stages_[s]; }
  // The haptics stage's parts (HapticParts, in that order), each tick.
  enum HapticPart { kSurfaceUpdate, kProxyQuery, kCoupling, kHapticPartCount };
  static const char* haptic_part_name(int part) noexcept;
  const TickRecorder& haptic_part(int p) const { return haptic_parts_[p]; }

 private:
  void record(double time) noexcept;
  // Snapshot entries waiting for the slots publish() fills next (take_reshaped), per body slot.
  struct Reshaped {
    std::array<BodySnapshot, 3> entries;
    size_t used = 3;  // entries already exchanged into a slot
  };
  std::vector<Reshaped> reshaped_;
  // TickEvents: counts each step's and device's status bits; on a body fault marks the body
  // frozen (its state is already back at the last trusted one) and records it, as a device's.
  void stepped(size_t body, uint32_t bits, double time) noexcept override;
  void faulted(size_t body, uint32_t bits, const char* why, double time) noexcept override;
  void device_raised(size_t device, uint32_t bit) noexcept override;
  void device_stopped(size_t device, double time) noexcept override;

  World& world_;
  TripleBuffer<Snapshot>& snapshots_;
  HapticInteraction* haptics_ = nullptr;
  CollisionResponse* response_ = nullptr;
  std::vector<std::unique_ptr<BodyWorker>> workers_;  // per body; null for haptic-thread bodies
  Recorder<TraceRow> trace_;
  Recorder<TrajectoryRow> trajectory_;
  Recorder<ProbeRow> probes_;
  Recorder<EnergyRow> energy_;
  Recorder<FaultRecord> faults_;
  double record_interval_s_ = 0;
  double next_record_s_ = 0;
  double last_tick_ms_ = 0;
  uint64_t tick_index_ = 0;
  std::unique_ptr<DeviceLogRecorder> device_log_;
  TickRecorder stages_[kStageCount];
  TickRecorder haptic_parts_[kHapticPartCount];
  double tick_time_ = 0;  // s, start of the current tick (when devices were read)
  TickStatus last_status_;
  std::vector<StatusCounter> body_status_, device_status_;  // sized at construction
  StatusCounter collision_status_;
  bool should_continue() const noexcept;
};

}  // namespace tacta
