// The realtime clock's wait (clock.spin_us) and what the kernel grants. spin_us 0 never spins and
// spin_us 1000 (a whole period) spins before most ticks, wherever this runs. As
// root with CAP_SYS_NICE (CI runs as root), SCHED_FIFO must be granted and the default 50 us spin
// must be what ends most waits (a FIFO thread's sleep wakes within microseconds: no timer slack);
// elsewhere that test skips and says why. A tick that burns 1.5 periods of CPU is over budget.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <time.h>
#include <unistd.h>

#include "tacta/sim/scheduler.hpp"

namespace {

using tacta::ClockMode;
using tacta::ScheduleOptions;
using tacta::ScheduleResult;

// A few microseconds of work per tick.
class LightTask final : public tacta::HapticTask {
 public:
  bool tick(uint64_t, double, double) noexcept override {
    volatile double sink = 0;
    for (int i = 0; i < 200; ++i) sink = sink + 1e-3 * i;
    return true;
  }
  void publish(double) noexcept override {}
};

// Burns `ms` of its own CPU time per tick (thread CPU clock, so a stall does not shorten it).
class BusyTask final : public tacta::HapticTask {
 public:
  explicit BusyTask(double ms) : ns_(static_cast<long>(ms * 1e6)) {}
  bool tick(uint64_t, double, double) noexcept override {
    timespec start{}, now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &start);
    do clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    while ((now.tv_sec - start.tv_sec) * 1000000000L + (now.tv_nsec - start.tv_nsec) < ns_);
    return true;
  }
  void publish(double) noexcept override {}

 private:
  long ns_;
};

class NoRender final : public tacta::RenderTask {
 public:
  void frame(double) override {}
};

ScheduleResult run_realtime(tacta::HapticTask& task, double duration_s, double spin_us,
                            int priority, int cpu) {
  NoRender render;
  ScheduleOptions o;
  o.mode = ClockMode::Realtime;
  o.duration_s = duration_s;
  o.realtime.spin_us = spin_us;
  o.realtime.priority = priority;
  o.realtime.cpu = cpu;
  o.realtime.lock_memory = false;
  o.warm_up_s = 0;  // every tick counts
  return tacta::run_schedule(task, render, o);
}

// CAP_SYS_NICE (bit 23) in this process's effective capabilities.
bool may_ask_for_fifo() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("CapEff:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> 23) & 1;
  }
  return false;
}

TEST(RealtimeWait, SpinUsZeroNeverSpins) {
  LightTask task;
  const ScheduleResult r = run_realtime(task, 0.1, 0, 0, -1);
  EXPECT_EQ(r.ticks, 100u);
  EXPECT_EQ(r.spun_waits, 0u) << "with spin_us 0 the sleep ends at the deadline, never before";
  EXPECT_EQ(r.late_wakeups, r.ticks);
}

TEST(RealtimeWait, SpinningAWholePeriodSpinsBeforeMostTicks) {
  LightTask task;
  const ScheduleResult r = run_realtime(task, 0.1, 1000, 0, -1);
  EXPECT_EQ(r.spun_waits + r.late_wakeups, r.ticks);
  // The sleep ends at once (its wake time is the previous deadline); only a thread kept off its
  // CPU past the deadline (tick 0, whose deadline is the start, or a loaded machine) wakes late.
  EXPECT_GE(r.spun_waits, r.ticks / 2) << "late wake-ups " << r.late_wakeups;
}

TEST(RealtimeWait, ATickThatBurnsMoreThanItsPeriodIsOverBudget) {
  BusyTask busy(1.5);
  const ScheduleResult r = run_realtime(busy, 0.05, 50, 0, -1);
  EXPECT_EQ(r.over_budget_ticks, r.ticks);
  EXPECT_EQ(r.deadline_misses, r.ticks);
  EXPECT_GE(r.max_tick_cpu_ms, 1.5);
  LightTask light;
  const ScheduleResult l = run_realtime(light, 0.1, 50, 0, -1);
  EXPECT_EQ(l.over_budget_ticks, 0u) << "max tick CPU " << l.max_tick_cpu_ms << " ms";
  EXPECT_GT(l.max_tick_cpu_ms, 0.0);
}

TEST(RealtimeWait, AsRootSchedFifoIsGrantedAndTheSpinEndsTheWaits) {
  if (geteuid() != 0) GTEST_SKIP() << "not root: SCHED_FIFO is not expected";
  if (!may_ask_for_fifo()) GTEST_SKIP() << "root without CAP_SYS_NICE (a container?)";
  LightTask task;
  const int cpu = sysconf(_SC_NPROCESSORS_ONLN) > 1 ? 1 : 0;
  const ScheduleResult r = run_realtime(task, 0.3, 50, 80, cpu);
  EXPECT_EQ(r.realtime.scheduler, "SCHED_FIFO") << r.realtime.scheduler_note;
  EXPECT_EQ(r.realtime.priority, 80);
  EXPECT_EQ(r.realtime.cpu, cpu) << r.realtime.cpu_note;
  EXPECT_EQ(r.realtime.spin_us, 50);
  EXPECT_EQ(r.over_budget_ticks, 0u);
  // A stalled VM can wake a FIFO thread late now and then, not most of the time.
  EXPECT_GE(r.spun_waits, r.ticks / 2) << "late wake-ups " << r.late_wakeups;
  std::printf("SCHED_FIFO %d on CPU %d: %llu of %llu waits spun, %llu woke late, %llu misses\n",
              r.realtime.priority, r.realtime.cpu, static_cast<unsigned long long>(r.spun_waits),
              static_cast<unsigned long long>(r.ticks),
              static_cast<unsigned long long>(r.late_wakeups),
              static_cast<unsigned long long>(r.deadline_misses));
}

}  // namespace
