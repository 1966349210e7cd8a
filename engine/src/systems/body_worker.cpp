#include "systems/body_worker.hpp"

#include <algorithm>
#include <chrono>
#include <pthread.h>

#include "services/job_pool.hpp"

namespace tacta {

BodyWorker::BodyWorker(const SoftBody& body, const Vec3& gravity, bool wait_at_boundaries,
                       size_t expected_steps)
    : body_(body), gravity_(gravity), wait_at_boundaries_(wait_at_boundaries) {
  const size_t n3 = body.nodes.positions.size();
  positions_ = body.nodes.positions;
  velocities_ = body.nodes.velocities;
  external_forces_.assign(n3, 0.0);
  step_start_ = body.nodes.positions;
  contact_mean_.assign(n3, 0.0);
  impulse_.assign(n3, 0.0);
  von_mises_.assign(body.node_count(), 0.0);
  job_von_mises_.assign(body.node_count(), 0.0);
  step_ms_.reserve(expected_steps + 4);
}

BodyWorker::~BodyWorker() { stop(); }

void BodyWorker::start() {
  if (thread_.joinable()) return;
  // The body may have changed between runs (a viewer pausing and playing on): start from it.
  std::copy(body_.nodes.positions.begin(), body_.nodes.positions.end(), positions_.begin());
  std::copy(body_.nodes.velocities.begin(), body_.nodes.velocities.end(), velocities_.begin());
  elastic_J_ = body_.model.instance->elastic_energy(positions_.data());
  has_stress_ = body_.model.instance->has_stress();
  if (has_stress_) body_.model.instance->node_stress(positions_.data(), von_mises_.data());
  quit_.store(false, std::memory_order_relaxed);
  thread_ = std::thread([this] { run(); });
  // The name lets a realtime run tell body workers (simulation work) from helper threads.
  pthread_setname_np(thread_.native_handle(), "tacta-body");
}

void BodyWorker::stop() noexcept {
  if (!thread_.joinable()) return;
  if (in_flight_) {
    // The run ended mid-period: the step in flight finishes and becomes the body's final state,
    // so a later run continues from where the model is.
    for (uint32_t d = done_.load(std::memory_order_acquire);
         d != posted_.load(std::memory_order_relaxed); d = done_.load(std::memory_order_acquire))
      done_.wait(d, std::memory_order_acquire);
    collect();
  }
  quit_.store(true, std::memory_order_relaxed);
  posted_.fetch_add(1, std::memory_order_release);  // wakes the worker to see quit_
  posted_.notify_one();
  thread_.join();
  // The wake-up above was not a job: bring the counters back in step for a later start().
  done_.store(posted_.load(std::memory_order_relaxed), std::memory_order_relaxed);
}

void BodyWorker::accumulate(const std::vector<double>& contact, double dt) noexcept {
  for (size_t i = 0; i < impulse_.size(); ++i) impulse_[i] += contact[i] * dt;
  impulse_time_ += dt;
}

bool BodyWorker::finish_step(double time) noexcept {
  if (!in_flight_) return true;
  uint32_t d = done_.load(std::memory_order_acquire);
  const uint32_t posted = posted_.load(std::memory_order_relaxed);
  if (d != posted) {
    if (!wait_at_boundaries_) {
      // Realtime: never wait for the model. Count the boundary once, retry next tick.
      if (time <= due_time_ + 1e-9) ++stats_.late_boundaries;
      return false;
    }
    while (d != posted) {
      done_.wait(d, std::memory_order_acquire);
      d = done_.load(std::memory_order_acquire);
    }
  }
  stats_.max_lateness_s = std::max(stats_.max_lateness_s, time - due_time_);
  collect();
  return true;
}

void BodyWorker::collect() noexcept {
  in_flight_ = false;
  collected_ = job_outcome_;
  ++body_.progress.refreshes;
  // The state the haptic thread renders against moves to the finished step; the one it replaces
  // becomes the start of the body's motion for the collision layer's swept queries.
  std::copy(body_.nodes.positions.begin(), body_.nodes.positions.end(),
            body_.nodes.step_start.begin());
  std::copy(positions_.begin(), positions_.end(), body_.nodes.positions.begin());
  std::copy(velocities_.begin(), velocities_.end(), body_.nodes.velocities.begin());
  if (!(collected_.bits & TACTA_STEP_FAULT_MASK))
    body_.fault.max_displacement_m =
        std::max(body_.fault.max_displacement_m, collected_.max_displacement);
  elastic_J_ = job_elastic_J_;
  has_stress_ = job_has_stress_;
  if (has_stress_) std::copy(job_von_mises_.begin(), job_von_mises_.end(), von_mises_.begin());
}

void BodyWorker::post(double time, double dt) noexcept {
  // The period's mean contact force: the same impulse the haptic ticks gave, spread over the step.
  const double span = impulse_time_ > 0 ? impulse_time_ : 1.0;  // s; 0 before any tick
  collected_ = {};
  for (size_t i = 0; i < impulse_.size(); ++i) contact_mean_[i] = impulse_[i] / span;
  std::fill(impulse_.begin(), impulse_.end(), 0.0);
  impulse_time_ = 0;
  job_model_ = body_.model.instance.get();
  job_time_ = time;
  job_dt_ = dt;
  due_time_ = time + dt;
  in_flight_ = true;
  posted_.fetch_add(1, std::memory_order_release);
  posted_.notify_one();
}

void BodyWorker::run() noexcept {
  JobPool::keep_serial_on_this_thread();  // the tick's bodies share the workers (JobPool)
  uint32_t seen = done_.load(std::memory_order_relaxed);
  for (;;) {
    posted_.wait(seen, std::memory_order_acquire);
    if (quit_.load(std::memory_order_relaxed)) return;
    step_job();
    seen += 1;
    done_.store(seen, std::memory_order_release);
    done_.notify_one();
  }
}

void BodyWorker::step_job() noexcept {
  const auto start = std::chrono::steady_clock::now();
  const StepArrays arrays{positions_, velocities_, external_forces_, step_start_, contact_mean_};
  job_outcome_ = step_body_arrays(*job_model_, *body_.shape.topology, gravity_,
                                  body_.settings.divergence_limit_m, arrays, job_time_, job_dt_,
                                  body_.constraints.boundary.get());
  // What snapshots want from the model is computed here, where the model lives during a step.
  job_elastic_J_ = job_model_->elastic_energy(positions_.data());
  job_has_stress_ = job_model_->has_stress();
  if (job_has_stress_) job_model_->node_stress(positions_.data(), job_von_mises_.data());
  ++stats_.steps;
  step_ms_.record(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace tacta
