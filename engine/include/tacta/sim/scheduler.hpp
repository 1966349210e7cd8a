// The two clocks. Lockstep: simulated time, 1 ms ticks as fast as the CPU allows, a frame every
// 1/60 s of simulated time, all on the calling thread: same inputs, same outputs, bit for bit.
// Realtime: a haptic thread on absolute 1 kHz deadlines and a render thread at 60 Hz; they share
// only a triple buffer. Both measure every tick's duration.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "tacta/sim/realtime.hpp"
#include "tacta/sim/tick_stats.hpp"

namespace tacta {

// What the haptic thread runs every tick. Must not allocate, lock or throw.
class HapticTask {
 public:
  virtual ~HapticTask() = default;
  // Advances the world from `time` by `dt` (s). Returns false to stop the run early.
  virtual bool tick(uint64_t index, double time, double dt) noexcept = 0;
  // Called at each frame boundary of simulated time, on the haptic thread: publish a snapshot.
  virtual void publish(double time) noexcept = 0;
  // Lockstep only, after each tick and before its frame, with the time the tick ended at (s):
  // work no tick may do (a scene's cuts allocate and rebuild), on the one thread of the run.
  virtual void between_ticks(double /*time*/) {}
};

// What the render thread runs at the frame rate: take the newest snapshot and draw or save it.
class RenderTask {
 public:
  virtual ~RenderTask() = default;
  virtual void frame(double wall_time) = 0;
};

enum class ClockMode { Lockstep, Realtime };

// Frame boundaries of simulated time: a frame falls due when time crosses k / render_rate,
// checked after each tick (by the lockstep scheduler and by Simulation::step).
struct FrameClock {
  double period_s;
  uint64_t next_frame = 1;
  // True when a boundary was crossed; moves past every boundary up to `time_s`.
  bool due(double time_s) {
    // A small tolerance (1 ns) keeps 1/60 s boundaries from slipping a tick through rounding.
    if (time_s + 1e-9 < static_cast<double>(next_frame) * period_s) return false;
    while (time_s + 1e-9 >= static_cast<double>(next_frame) * period_s) ++next_frame;
    return true;
  }
};

struct ScheduleOptions {
  ClockMode mode = ClockMode::Lockstep;
  double haptic_rate_hz = 1000;
  double render_rate_hz = 60;
  double duration_s = 1;
  std::atomic<bool>* stop = nullptr;                 // set from outside to end the run early
  std::function<void(double fraction)> on_progress;  // called from the scheduling thread, ~10 Hz
  RealtimeOptions realtime;                          // realtime: scheduling, memory, CPU, wait
  // s of wall (realtime) or simulated (lockstep) time: memory_warm is taken here, and ticks
  // before it are start-up (cold caches, the first hierarchy build), counted apart.
  double warm_up_s = 1.0;
};

// Resident memory every 10 s of the run (a leak shows as growth between samples); 64 samples
// cover the first 640 s, the last sample is memory_end.
struct RssTimeline {
  static constexpr double kEveryS = 10;
  static constexpr size_t kCapacity = 64;
  uint64_t kb[kCapacity] = {};
  size_t count = 0;
  // Samples when `time_s` has reached the next multiple of kEveryS. Reads /proc: not for the tick.
  void sample_if_due(double time_s) noexcept;
};

struct ScheduleResult {
  uint64_t ticks = 0;
  uint64_t frames = 0;
  uint64_t deadline_misses = 0;    // realtime: ticks that ended after their deadline
  double max_start_jitter_ms = 0;  // realtime: latest tick start after its scheduled start
  // realtime: ticks after the warm-up whose own CPU time (CLOCK_THREAD_CPUTIME_ID, which leaves
  // out time the thread was off its CPU, a VM's stolen time included where the kernel accounts
  // it) exceeded the period. Such a tick misses its deadline by the engine's own work; every
  // other miss is the thread waiting for its CPU (a stall, preemption or a late wake-up).
  uint64_t over_budget_ticks = 0;
  // Which ticks, the first kMaxListedOverBudget of them: the engine's work at a tick repeats
  // run after run (realtime states equal lockstep's), a host's stall does not, so two runs' lists
  // tell the two apart where the kernel does not account steal time (tests/soak).
  static constexpr size_t kMaxListedOverBudget = 64;
  uint64_t over_budget_tick_list[kMaxListedOverBudget] = {};
  uint64_t warm_up_over_budget_ticks = 0;  // the same during the warm-up (warm_up_s)
  double max_tick_cpu_ms = 0;              // after the warm-up
  // realtime: how each wait for a tick's start ended (clock.spin_us): woken before the deadline
  // and spun to it, or woken already past it (nothing left to spin).
  uint64_t spun_waits = 0, late_wakeups = 0;
  RssTimeline rss_timeline;
  double wall_time_s = 0;
  bool stopped_early = false;
  TickSummary tick;
  RealtimeGrant realtime;  // realtime: what the kernel granted the haptic thread
  // Before the first tick, at the first frame 1 s into the run (after the renderer and the
  // records have warmed up: growth after this is what a leak would show), after the last tick.
  ResidentMemory memory_start, memory_warm, memory_end;
};

ScheduleResult run_schedule(HapticTask& haptic, RenderTask& render, const ScheduleOptions& options);

}  // namespace tacta
