// Scheduler: lockstep gives exactly duration * rate ticks at time k * dt (no drift over 100 000
// ticks) and a frame at every 1/60 s of simulated time; a stop flag ends the run early. Realtime
// for 0.3 s: 300 ticks on absolute deadlines, measured durations, a render thread that took
// several frames through a triple buffer. Also runs under ThreadSanitizer (preset tsan).
#include <atomic>
#include <cmath>
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <time.h>
#include <vector>

#include "tacta/sim/scheduler.hpp"
#include "tacta/sim/triple_buffer.hpp"

namespace {

using tacta::ClockMode;
using tacta::ScheduleOptions;
using tacta::ScheduleResult;

// Counts ticks and checks their times as they come; keeps the publish times (reserved up front).
class CountingTask final : public tacta::HapticTask {
 public:
  explicit CountingTask(double rate_hz, size_t max_publishes) : dt_expected_(1.0 / rate_hz) {
    publishes.reserve(max_publishes);
  }
  bool tick(uint64_t index, double time, double dt) noexcept override {
    if (index != ticks) ++index_errors;
    // Against the exact tick time index / rate: accumulation would drift by ~1e-11 s at 1e5 ticks.
    max_time_error =
        std::max(max_time_error, std::fabs(time - static_cast<double>(index) / rate()));
    if (dt != dt_expected_) ++dt_errors;
    last_time = time;
    ++ticks;
    if (stop != nullptr && index == stop_at) stop->store(true);
    return index != return_false_at;
  }
  void publish(double time) noexcept override {
    if (publishes.size() < publishes.capacity()) publishes.push_back(time);
  }
  double rate() const { return 1.0 / dt_expected_; }

  uint64_t ticks = 0, index_errors = 0, dt_errors = 0;
  double max_time_error = 0, last_time = -1;
  std::vector<double> publishes;
  std::atomic<bool>* stop = nullptr;
  uint64_t stop_at = ~0ull, return_false_at = ~0ull;

 private:
  double dt_expected_;
};

class CountingRender final : public tacta::RenderTask {
 public:
  void frame(double) override { ++frames; }
  uint64_t frames = 0;
};

TEST(SchedulerLockstep, ExactTickCountAndTimesWithoutDrift) {
  ScheduleOptions o;
  o.duration_s = 100.0;  // 100 000 ticks at 1 kHz
  CountingTask task(o.haptic_rate_hz, 7000);
  CountingRender render;
  const ScheduleResult r = tacta::run_schedule(task, render, o);
  EXPECT_EQ(r.ticks, 100000u);
  EXPECT_EQ(task.ticks, 100000u);
  EXPECT_EQ(task.index_errors, 0u);
  EXPECT_EQ(task.dt_errors, 0u);
  EXPECT_LE(task.max_time_error, 1e-12) << "tick time is not k * dt";
  EXPECT_NEAR(task.last_time, 99.999, 1e-9);
  EXPECT_FALSE(r.stopped_early);
  EXPECT_EQ(r.tick.ticks, 100000u) << "every tick's duration is recorded";
  EXPECT_GT(r.tick.max_ms, 0.0);
  EXPECT_GE(r.tick.max_ms, r.tick.p99_ms);
  EXPECT_GE(r.tick.p99_ms, r.tick.p50_ms);
}

TEST(SchedulerLockstep, AFrameAtEverySixtiethOfSimulatedTime) {
  ScheduleOptions o;
  o.duration_s = 10.0;
  CountingTask task(o.haptic_rate_hz, 1000);
  CountingRender render;
  const ScheduleResult r = tacta::run_schedule(task, render, o);
  // One frame at t = 0, then one per boundary j / 60 for j = 1..600 (the last at t = 10 s).
  EXPECT_EQ(r.frames, 601u);
  EXPECT_EQ(render.frames, 601u);
  ASSERT_EQ(task.publishes.size(), 601u);
  EXPECT_EQ(task.publishes.front(), 0.0);
  for (size_t j = 1; j < task.publishes.size(); ++j) {
    const double boundary = static_cast<double>(j) / 60.0, t = task.publishes[j];
    // Published at the end of the first tick that reaches the boundary: within one tick after it.
    EXPECT_GE(t, boundary - 1e-9) << "frame " << j;
    EXPECT_LT(t, boundary + 1e-3 - 1e-9) << "frame " << j;
  }
  EXPECT_NEAR(task.publishes.back(), 10.0, 1e-9);
}

// A 5 s run in `mode` that the stop flag ends after tick `stop_at`: the state it stopped at is
// published (a paused window shows where the clock is, not the frame before it).
void expect_a_stop_to_publish_its_tick(ClockMode mode, uint64_t stop_at) {
  std::atomic<bool> stop{false};
  ScheduleOptions o;
  o.mode = mode;
  o.duration_s = 5.0;
  o.stop = &stop;
  CountingTask task(o.haptic_rate_hz, 1000);
  task.stop = &stop;
  task.stop_at = stop_at;
  CountingRender render;
  const ScheduleResult r = tacta::run_schedule(task, render, o);
  EXPECT_EQ(r.ticks, stop_at + 1);
  EXPECT_TRUE(r.stopped_early);
  ASSERT_FALSE(task.publishes.empty());
  EXPECT_DOUBLE_EQ(task.publishes.back(), static_cast<double>(stop_at + 1) * 1e-3);
}

TEST(SchedulerLockstep, StopFlagAndFalseReturnEndTheRunEarly) {
  expect_a_stop_to_publish_its_tick(ClockMode::Lockstep, 508);  // 0.509 s: between two frames

  ScheduleOptions o;
  o.duration_s = 5.0;
  CountingRender render;
  CountingTask quitter(o.haptic_rate_hz, 1000);
  quitter.return_false_at = 99;
  std::atomic<bool> never{false};
  o.stop = &never;
  const ScheduleResult q = tacta::run_schedule(quitter, render, o);
  EXPECT_EQ(q.ticks, 100u);
  EXPECT_TRUE(q.stopped_early);
}

// Realtime: the haptic thread publishes its tick count into a triple buffer, the render thread
// reads it; what the render thread sees must be whole and must not go backwards.
struct Counter {
  uint64_t tick = 0;
  uint64_t copy = 0;  // always equal to tick in a whole snapshot
};

class PublishingTask final : public tacta::HapticTask {
 public:
  explicit PublishingTask(tacta::TripleBuffer<Counter>& buffer) : buffer_(buffer) {}
  bool tick(uint64_t index, double, double) noexcept override {
    ticks_ = index + 1;
    volatile double sink = 0;
    for (int i = 0; i < 2000; ++i) sink = sink + 1e-3 * i;  // some work to measure
    return true;
  }
  void publish(double) noexcept override {
    Counter& c = buffer_.write_slot();
    c.tick = ticks_;
    c.copy = ticks_;
    buffer_.publish();
  }

 private:
  tacta::TripleBuffer<Counter>& buffer_;
  uint64_t ticks_ = 0;
};

class ReadingRender final : public tacta::RenderTask {
 public:
  explicit ReadingRender(tacta::TripleBuffer<Counter>& buffer) : buffer_(buffer) {}
  void frame(double wall_time) override {
    ++frames;
    if (wall_time < last_wall) ++wall_backwards;
    last_wall = wall_time;
    if (!buffer_.acquire()) return;
    const Counter& c = buffer_.read_slot();
    if (c.tick != c.copy) ++torn;
    if (c.tick < last_tick) ++backwards;
    last_tick = c.tick;
  }
  uint64_t frames = 0, torn = 0, backwards = 0, last_tick = 0, wall_backwards = 0;
  double last_wall = 0;

 private:
  tacta::TripleBuffer<Counter>& buffer_;
};

TEST(SchedulerRealtime, ThreeHundredMillisecondsOnDeadlines) {
  tacta::TripleBuffer<Counter> buffer;
  PublishingTask task(buffer);
  ReadingRender render(buffer);
  ScheduleOptions o;
  o.mode = ClockMode::Realtime;
  o.duration_s = 0.3;
  const ScheduleResult r = tacta::run_schedule(task, render, o);
  EXPECT_EQ(r.ticks, 300u);
  EXPECT_FALSE(r.stopped_early);
  // Tick k starts no earlier than k ms after the start: 300 ticks take at least 299 ms.
  EXPECT_GE(r.wall_time_s, 0.299);
  EXPECT_LT(r.wall_time_s, 3.0) << "the haptic thread fell far behind its deadlines";
  EXPECT_EQ(r.tick.ticks, 300u);
  EXPECT_GT(r.tick.p50_ms, 0.0) << "tick durations are measured in realtime mode";
  EXPECT_GT(r.tick.max_ms, 0.0);
  EXPECT_GE(r.tick.max_ms, r.tick.p50_ms);
  EXPECT_GE(r.max_start_jitter_ms, 0.0);
  EXPECT_LE(r.deadline_misses, r.ticks);
  // 0.3 s at 60 Hz is 18 frames; a loaded CI machine may take fewer, but several.
  EXPECT_GE(r.frames, 5u);
  EXPECT_EQ(render.frames, r.frames);
  EXPECT_EQ(render.torn, 0u);
  EXPECT_EQ(render.backwards, 0u);
  EXPECT_EQ(render.wall_backwards, 0u);
  EXPECT_EQ(render.last_tick, 300u) << "the render thread's last frame shows the final state";
}

// A tick that takes 1.5 periods: at SCHED_FIFO the thread would never sleep, so after
// kStarvingTicks misses in a row it is dropped to SCHED_OTHER (when SCHED_FIFO was granted at all).
class SlowTask final : public tacta::HapticTask {
 public:
  bool tick(uint64_t, double, double) noexcept override {
    timespec until{};
    clock_gettime(CLOCK_MONOTONIC, &until);
    until.tv_nsec += 1500000;
    if (until.tv_nsec >= 1000000000) {
      until.tv_nsec -= 1000000000;
      ++until.tv_sec;
    }
    timespec now{};
    do clock_gettime(CLOCK_MONOTONIC, &now);
    while (now.tv_sec < until.tv_sec ||
           (now.tv_sec == until.tv_sec && now.tv_nsec < until.tv_nsec));
    int policy = 0;
    sched_param p{};
    pthread_getschedparam(pthread_self(), &policy, &p);
    last_policy = policy;
    return true;
  }
  void publish(double) noexcept override {}
  int last_policy = -1;
};

TEST(SchedulerRealtime, AStopPublishesTheStateItStoppedAt) {
  expect_a_stop_to_publish_its_tick(ClockMode::Realtime, 58);  // 0.059 s: between 3/60 and 4/60
}

TEST(SchedulerRealtime, AHapticThreadThatMissesEveryDeadlineLeavesSchedFifo) {
  SlowTask task;
  CountingRender render;
  ScheduleOptions o;
  o.mode = ClockMode::Realtime;
  o.duration_s = 0.15;
  o.realtime.priority = 10;
  o.realtime.lock_memory = false;
  const ScheduleResult r = tacta::run_schedule(task, render, o);
  EXPECT_EQ(r.deadline_misses, r.ticks);
  if (r.realtime.scheduler == "SCHED_FIFO") {
    EXPECT_EQ(r.realtime.demoted_at_tick, static_cast<int64_t>(tacta::kStarvingTicks) - 1);
    EXPECT_EQ(task.last_policy, SCHED_OTHER);
  } else {
    EXPECT_EQ(r.realtime.demoted_at_tick, -1) << "only a SCHED_FIFO thread is demoted";
  }
}

}  // namespace
