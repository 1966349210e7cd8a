// Lockstep and realtime scheduling of the haptic and render tasks (see scheduler.hpp).
#include "tacta/sim/scheduler.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <pthread.h>
#include <thread>
#include <time.h>

namespace tacta {

namespace {

using SteadyClock = std::chrono::steady_clock;

double ms_between(SteadyClock::time_point a, SteadyClock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

uint64_t tick_count(const ScheduleOptions& o) {
  return static_cast<uint64_t>(std::llround(o.duration_s * o.haptic_rate_hz));
}

bool stop_requested(const ScheduleOptions& o) {
  return o.stop != nullptr && o.stop->load(std::memory_order_relaxed);
}

ScheduleResult run_lockstep(HapticTask& haptic, RenderTask& render, const ScheduleOptions& o) {
  ScheduleResult result;
  const uint64_t ticks = tick_count(o);
  const double dt = 1.0 / o.haptic_rate_hz;
  TickRecorder recorder(ticks);
  FrameClock frames{1.0 / o.render_rate_hz};
  const auto run_start = SteadyClock::now();
  auto last_progress = run_start;
  result.memory_start = resident_memory();
  result.realtime.scheduler_note = "lockstep: no real-time scheduling asked for";
  haptic.publish(0.0);
  render.frame(0.0);
  ++result.frames;
  for (uint64_t k = 0; k < ticks; ++k) {
    // Time from the tick index, not by accumulation, so long runs do not drift.
    const double time = static_cast<double>(k) * dt;
    const auto t0 = SteadyClock::now();
    const bool keep_going = haptic.tick(k, time, dt);
    const auto t1 = SteadyClock::now();
    recorder.record(ms_between(t0, t1));
    ++result.ticks;
    const double end_time = static_cast<double>(k + 1) * dt;
    haptic.between_ticks(end_time);
    // The run's last tick is always shown, a stop's too: a paused window shows where the clock is.
    const bool last = k + 1 == ticks || !keep_going || stop_requested(o);
    if (frames.due(end_time) || last) {
      haptic.publish(end_time);
      render.frame(ms_between(run_start, SteadyClock::now()) * 1e-3);
      ++result.frames;
      if (result.memory_warm.rss_kb == 0 && end_time >= o.warm_up_s)
        result.memory_warm = resident_memory();
      result.rss_timeline.sample_if_due(end_time);
    }
    if (o.on_progress && ms_between(last_progress, t1) > 100) {
      last_progress = t1;
      o.on_progress(static_cast<double>(k + 1) / static_cast<double>(ticks));
    }
    if (last) {
      result.stopped_early = k + 1 < ticks;
      break;
    }
  }
  result.memory_end = resident_memory();
  result.wall_time_s = ms_between(run_start, SteadyClock::now()) * 1e-3;
  result.tick = recorder.summary();
  return result;
}

timespec add_ns(timespec t, int64_t ns) {
  t.tv_sec += static_cast<time_t>(ns / 1000000000);
  t.tv_nsec += static_cast<long>(ns % 1000000000);
  if (t.tv_nsec >= 1000000000) {
    t.tv_nsec -= 1000000000;
    ++t.tv_sec;
  } else if (t.tv_nsec < 0) {
    t.tv_nsec += 1000000000;
    --t.tv_sec;
  }
  return t;
}

double ms_after(const timespec& a, const timespec& b) {  // b - a in ms
  return static_cast<double>(b.tv_sec - a.tv_sec) * 1e3 +
         static_cast<double>(b.tv_nsec - a.tv_nsec) * 1e-6;
}

// Absolute-deadline wait on the monotonic clock (so the period does not drift): sleeps to
// `spin_ns` before the deadline, then spins, since a sleep's wake-up is late by the timer slack
// and the scheduler's latency (tens of microseconds to milliseconds on a loaded machine).
// Returns true when it spun (woke before the deadline), false when the sleep woke past it.
bool wait_until(const timespec& deadline, int64_t spin_ns) {
  const timespec wake = add_ns(deadline, -spin_ns);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) != 0) {
  }
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  if (ms_after(now, deadline) <= 0) return false;
  do {
    clock_gettime(CLOCK_MONOTONIC, &now);
  } while (ms_after(now, deadline) > 0);
  return true;
}

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

ScheduleResult run_realtime(HapticTask& haptic, RenderTask& render, const ScheduleOptions& o) {
  ScheduleResult result;
  const uint64_t ticks = tick_count(o);
  const double dt = 1.0 / o.haptic_rate_hz;
  const auto period_ns = static_cast<int64_t>(std::llround(1e9 / o.haptic_rate_hz));
  const double period_ms = static_cast<double>(period_ns) * 1e-6;
  TickRecorder recorder(ticks);
  std::atomic<bool> haptic_done{false};
  std::atomic<uint64_t> frames{0};
  std::atomic<uint64_t> ticks_done{0};  // read by the render thread for progress reports
  const auto run_start = SteadyClock::now();
  haptic.publish(0.0);

  // The render thread: draws the newest snapshot at the render rate until the haptic task ends.
  std::thread render_thread([&] {
    pthread_setname_np(pthread_self(), "tacta-render");
    const auto frame_period = std::chrono::duration<double>(1.0 / o.render_rate_hz);
    auto next = SteadyClock::now();
    while (!haptic_done.load(std::memory_order_acquire)) {
      const double wall_s = ms_between(run_start, SteadyClock::now()) * 1e-3;
      render.frame(wall_s);
      frames.fetch_add(1, std::memory_order_relaxed);
      if (result.memory_warm.rss_kb == 0 && wall_s >= o.warm_up_s)
        result.memory_warm = resident_memory();
      result.rss_timeline.sample_if_due(wall_s);
      // Progress is printed from here, never from the haptic thread (stdout takes a lock).
      if (o.on_progress)
        o.on_progress(static_cast<double>(ticks_done.load(std::memory_order_relaxed)) /
                      static_cast<double>(ticks));
      next += std::chrono::duration_cast<SteadyClock::duration>(frame_period);
      std::this_thread::sleep_until(next);
    }
    render.frame(ms_between(run_start, SteadyClock::now()) * 1e-3);  // the final state
    frames.fetch_add(1, std::memory_order_relaxed);
  });

  // The haptic loop runs on this thread: tick k is due at start + k * period. The session is
  // entered after the render thread exists, so that thread is lowered and kept off the haptic CPU.
  std::optional<RealtimeSession> session(std::in_place, o.realtime);
  result.realtime = session->grant();
  const auto spin_ns =
      static_cast<int64_t>(std::llround(std::clamp(o.realtime.spin_us, 0.0, 1e6) * 1e3));
  result.memory_start = resident_memory();
  FrameClock frame_clock{1.0 / o.render_rate_hz};
  timespec start{};
  clock_gettime(CLOCK_MONOTONIC, &start);
  uint32_t misses_in_a_row = 0;
  for (uint64_t k = 0; k < ticks; ++k) {
    const timespec due = add_ns(start, static_cast<int64_t>(k) * period_ns);
    ++(wait_until(due, spin_ns) ? result.spun_waits : result.late_wakeups);
    timespec begin{};
    clock_gettime(CLOCK_MONOTONIC, &begin);
    const double cpu_begin_ms = thread_cpu_ms();
    result.max_start_jitter_ms = std::max(result.max_start_jitter_ms, ms_after(due, begin));
    const double time = static_cast<double>(k) * dt;
    const bool keep_going = haptic.tick(k, time, dt);
    const double end_time = static_cast<double>(k + 1) * dt;
    const bool last = k + 1 == ticks || !keep_going || stop_requested(o);  // shown, as in lockstep
    if (frame_clock.due(end_time) || last) haptic.publish(end_time);
    timespec end{};
    clock_gettime(CLOCK_MONOTONIC, &end);
    recorder.record(ms_after(begin, end));
    const double cpu_ms = thread_cpu_ms() - cpu_begin_ms;
    if (time < o.warm_up_s) {
      if (cpu_ms > period_ms) ++result.warm_up_over_budget_ticks;
    } else {
      result.max_tick_cpu_ms = std::max(result.max_tick_cpu_ms, cpu_ms);
      if (cpu_ms > period_ms) {
        if (result.over_budget_ticks < ScheduleResult::kMaxListedOverBudget)
          result.over_budget_tick_list[result.over_budget_ticks] = k;
        ++result.over_budget_ticks;
      }
    }
    if (ms_after(add_ns(due, period_ns), end) > 0) {
      ++result.deadline_misses;
      if (++misses_in_a_row == kStarvingTicks) session->demote(static_cast<int64_t>(k));
    } else {
      misses_in_a_row = 0;
    }
    ++result.ticks;
    ticks_done.store(k + 1, std::memory_order_relaxed);
    if (last) {
      result.stopped_early = k + 1 < ticks;
      break;
    }
  }
  result.memory_end = resident_memory();
  result.realtime.demoted_at_tick = session->grant().demoted_at_tick;
  result.realtime.nice = session->grant().nice;
  session.reset();  // back to the thread's own policy before the render thread's last frame
  haptic_done.store(true, std::memory_order_release);
  render_thread.join();
  result.frames = frames.load();
  result.wall_time_s = ms_between(run_start, SteadyClock::now()) * 1e-3;
  result.tick = recorder.summary();
  return result;
}

}  // namespace

void RssTimeline::sample_if_due(double time_s) noexcept {
  if (count >= kCapacity || time_s < static_cast<double>(count + 1) * kEveryS) return;
  kb[count++] = resident_memory().rss_kb;
}

ScheduleResult run_schedule(HapticTask& haptic, RenderTask& render,
                            const ScheduleOptions& options) {
  return options.mode == ClockMode::Realtime ? run_realtime(haptic, render, options)
                                             : run_lockstep(haptic, render, options);
}

}  // namespace tacta
