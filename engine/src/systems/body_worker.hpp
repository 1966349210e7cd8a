// A body that steps on its own thread at its own rate (scene: `step_thread: own` with
// `step_rate_hz`), for models that cannot step within the 1 ms haptic tick.
//
// The split: the worker thread owns a private copy of the node state and the model while a step
// is in flight; the haptic thread keeps rendering against the body's arrays in its NodeState, which
// are the last state the worker finished (the "local contact model" the proxy touches, see
// haptics/local_compliance.hpp for how it yields between refreshes). At each of the body's
// period boundaries the haptic thread collects the finished step (copies the new state into
// NodeState), takes any model swap, and posts the next step with the mean contact force of the
// period just ended, so the impulse the tool gave the body is handed over whole.
//
// Pipelined: the state the haptic thread sees at boundary k is the result of the step posted at
// k-1, driven by the forces of period k-2..k-1: one period of force latency, the price of never
// waiting for the model. Lockstep runs wait at the boundary for the step to finish (same result
// on any machine, bit for bit); realtime runs never wait: a step still running at its boundary
// is counted as late and collected at the first tick after it finishes.
//
// Hand-over is two atomic counters (posted, done) and futex waits: no lock shared with the
// haptic or render threads, nothing allocated after start().
#pragma once

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "systems/body_step.hpp"
#include "tacta/sim/tick_stats.hpp"

namespace tacta {

struct WorkerStats {
  uint64_t steps = 0;            // steps finished
  uint64_t late_boundaries = 0;  // realtime: boundaries at which the step in flight was not done
  double max_lateness_s = 0;     // realtime: longest wait past a boundary for a step, s
};

class BodyWorker {
 public:
  // Sizes every buffer for `body` (allocates; load time). expected_steps sizes the step timer.
  BodyWorker(const SoftBody& body, const Vec3& gravity, bool wait_at_boundaries,
             size_t expected_steps);
  ~BodyWorker();
  BodyWorker(const BodyWorker&) = delete;
  BodyWorker& operator=(const BodyWorker&) = delete;

  void start();          // launches the thread (start of a run)
  void stop() noexcept;  // lets a step in flight finish, collects it, joins (end of a run)

  // Haptic thread, every tick: this tick's contact forces (N) over its dt (s) join the period's
  // impulse.
  void accumulate(const std::vector<double>& contact, double dt) noexcept;
  // Haptic thread, when the body's clock has fallen due at `time`: collects the step in flight
  // (waiting for it in lockstep) into NodeState. Returns false when it is still running (realtime
  // only): the caller renders on against the old state and tries again next tick.
  bool finish_step(double time) noexcept;
  // Haptic thread, after finish_step (the model is idle: swaps may happen in between): posts the
  // next step of `dt` from `time`, driven by the mean contact force since the last post.
  void post(double time, double dt) noexcept;
  // The outcome of the last collected step (bits, why): a fault the caller must freeze on.
  const StepOutcome& last_outcome() const noexcept { return collected_; }

  // Values computed on the worker after each step (the model is busy there), for snapshots.
  double elastic_energy() const noexcept { return elastic_J_; }
  const std::vector<double>& von_mises() const noexcept { return von_mises_; }
  bool has_stress() const noexcept { return has_stress_; }

  const WorkerStats& stats() const noexcept { return stats_; }
  const TickRecorder& step_ms() const noexcept { return step_ms_; }

 private:
  void run() noexcept;       // the worker thread
  void step_job() noexcept;  // one step on the private arrays
  void collect() noexcept;   // haptic thread, worker idle: private state -> NodeState

  SoftBody body_;  // references into the World's pools, which never move
  Vec3 gravity_;
  bool wait_at_boundaries_;
  // Private state, touched by the worker only while a step is in flight.
  std::vector<double> positions_, velocities_, external_forces_, step_start_, contact_mean_;
  std::vector<double> von_mises_;
  ModelInstance* job_model_ = nullptr;
  double job_time_ = 0, job_dt_ = 0;
  StepOutcome job_outcome_{};
  double elastic_J_ = 0;
  double job_elastic_J_ = 0;
  bool has_stress_ = false, job_has_stress_ = false;
  std::vector<double> job_von_mises_;
  // The haptic thread's side.
  std::vector<double> impulse_;  // N s per node component, summed since the last post
  double impulse_time_ = 0;      // s summed since the last post
  bool in_flight_ = false;
  double due_time_ = 0;  // s, the boundary the step in flight was due at
  StepOutcome collected_{};
  WorkerStats stats_;
  TickRecorder step_ms_;
  // Hand-over: the haptic thread bumps posted_, the worker bumps done_ (futex-backed waits).
  std::atomic<uint32_t> posted_{0};
  std::atomic<uint32_t> done_{0};
  std::atomic<bool> quit_{false};
  std::thread thread_;
};

}  // namespace tacta
