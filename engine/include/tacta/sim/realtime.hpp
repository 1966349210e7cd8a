// Real-time hygiene for the realtime clock, as haptic servo loops do it on Linux: the haptic
// thread asks for SCHED_FIFO (falling back to a raised nice value, then to nothing), memory is
// locked (mlockall) so no page fault lands in a tick, the haptic thread may be pinned to a CPU
// with every other thread of the process moved off it, the render and helper threads run at a
// lower priority, and each tick's deadline is met by sleeping to just before it and spinning
// the last microseconds. What was asked and what the kernel granted is reported, never assumed.
#pragma once

#include <atomic>
#include <cstdint>
#include <pthread.h>
#include <string>
#include <vector>

namespace tacta {

struct RealtimeOptions {
  int priority = 80;        // SCHED_FIFO priority, 1..99; 0: do not ask for SCHED_FIFO
  int cpu = -1;             // CPU the haptic thread is pinned to; -1: no pinning
  bool lock_memory = true;  // mlockall(MCL_CURRENT | MCL_FUTURE) for the run
  // Hold the CPUs in shallow idle states for the run (a 0 us PM QoS request on
  // /dev/cpu_dma_latency, as cyclictest makes): between ticks a deep idle state flushes the
  // core's caches and wakes late, and the next tick's step pays for both.
  bool shallow_idle = true;
  // Pinned runs: while the haptic thread sleeps, a SCHED_IDLE thread on its CPU spins, so that
  // CPU never idles at all. Needed where PM QoS cannot help: a VM's guest idles by halting, which
  // hands the vCPU back to the host, and the next tick finds its caches cold (the liver demo's
  // realtime model step p50 0.30-0.34 -> 0.23-0.29 ms on a 2-vCPU VM, its lockstep cost). The
  // CPU shows busy for the whole run.
  bool poll_idle = true;
  double spin_us = 50;  // the last microseconds before a deadline are spun, not slept
};

// What the kernel granted (report.json "realtime").
struct RealtimeGrant {
  std::string scheduler = "SCHED_OTHER";  // the haptic thread's policy during the run
  int priority = 0;                       // SCHED_FIFO priority granted (0 with SCHED_OTHER)
  int nice = 0;                           // the haptic thread's nice value with SCHED_OTHER
  std::string scheduler_note;             // why SCHED_FIFO was not granted, and the fallback
  bool memory_locked = false;
  std::string memory_note;              // why mlockall failed, when it did
  bool shallow_idle = false;            // the PM QoS request is held for the run
  std::string idle_note;                // why it is not, when it is not
  bool poll_idle = false;               // a spinning SCHED_IDLE thread holds the haptic CPU
  std::string poll_note;                // why not, when not
  int cpu = -1;                         // the haptic thread's CPU; -1: not pinned
  std::string cpu_note;                 // why pinning failed, when it did
  uint32_t helper_threads_lowered = 0;  // other threads moved to a lower priority (and off `cpu`)
  double spin_us = 0;
  // The haptic thread's timer slack for the run, ns: how late the kernel may end its sleeps.
  uint64_t timer_slack_ns = 0;
  // Tick at which a SCHED_FIFO haptic thread that missed every deadline for
  // kStarvingTicks ticks was dropped to SCHED_OTHER; -1: never.
  int64_t demoted_at_tick = -1;
};

// A SCHED_FIFO thread whose tick takes longer than its period never sleeps: after this many
// deadline misses in a row it would starve its CPU (and any peer process on it), so it is demoted.
constexpr uint32_t kStarvingTicks = 100;

// Resident memory of this process, kB (VmRSS), and its peak (VmHWM); 0 when /proc is not there.
struct ResidentMemory {
  uint64_t rss_kb = 0, peak_kb = 0;
};
ResidentMemory resident_memory() noexcept;

// Applies `options` to the calling (haptic) thread and lowers every other thread of the process;
// `leave` restores what `enter` changed. Not for the 1 kHz path: called once around the loop.
class RealtimeSession {
 public:
  explicit RealtimeSession(const RealtimeOptions& options);
  ~RealtimeSession();
  RealtimeSession(const RealtimeSession&) = delete;
  RealtimeSession& operator=(const RealtimeSession&) = delete;

  const RealtimeGrant& grant() const noexcept { return grant_; }
  // Lowers the calling thread (a render or I/O thread started after the session began).
  void lower_this_thread() noexcept;
  // Drops a SCHED_FIFO haptic thread to SCHED_OTHER at the fallback nice value and records the
  // tick; returns false (and does nothing) when the thread is not SCHED_FIFO. Allocates nothing.
  bool demote(int64_t tick) noexcept;

 private:
  void start_idle_poller();
  RealtimeOptions options_;
  RealtimeGrant grant_;
  int old_policy_ = 0, old_priority_ = 0, old_nice_ = 0;
  long old_timer_slack_ns_ = -1;
  std::string old_name_;
  std::vector<int> original_cpus_;  // the haptic thread's CPUs before pinning; empty: not pinned
  struct LoweredThread {
    int tid, nice;  // a helper thread and its nice value before the run
  };
  std::vector<LoweredThread> lowered_;
  int latency_fd_ = -1;  // /dev/cpu_dma_latency, open while the request holds
  // poll_idle: a thread spinning on the haptic CPU at SCHED_IDLE while poller_state_ is 1.
  std::atomic<int> poller_state_{0};
  pthread_t idle_poller_{};
  bool polling_ = false;
};

}  // namespace tacta
