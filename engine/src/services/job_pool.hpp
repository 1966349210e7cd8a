// Engine-owned worker threads for plugins' parallel_for (tacta_host_services): the calling
// thread and `threads - 1` workers split [0, count) into chunks taken from an atomic counter.
// No allocation, no mutex. A threaded solver calls parallel_for a few times per CG iteration
// (tens of times per 1 ms step), so waking a worker must cost far less than a microsecond: a
// worker spins (with pause) for kSpinBeforePark after its last job, watching the job
// generation, and only then parks on it (a futex); a parked worker costs the next job's caller
// one wake-up (a system call, ~10-50 us in a VM). The caller spins on the done count and parks
// only after a long wait. One job at a time; a second caller while a job runs gets a serial
// run on its own thread (two bodies stepping on two threads).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "tacta/model_api.h"

namespace tacta {

class JobPool {
 public:
  using Body = void (*)(void* user, uint32_t begin, uint32_t end, uint32_t worker);
  // How long an idle worker spins before it parks: covers the gaps between the parallel_for
  // calls of one step (and of back-to-back steps), not the idle part of a 1 ms tick.
  static constexpr std::chrono::microseconds kSpinBeforePark{250};

  explicit JobPool(uint32_t threads);  // 1: no workers, every job serial on the caller
  ~JobPool();
  JobPool(const JobPool&) = delete;
  JobPool& operator=(const JobPool&) = delete;

  uint32_t threads() const noexcept { return static_cast<uint32_t>(workers_.size()) + 1; }
  void parallel_for(uint32_t count, uint32_t grain, Body body, void* user) noexcept;
  // The C entry of tacta_host_services (jobs = this).
  static void parallel_for_entry(void* jobs, uint32_t count, uint32_t grain, Body body, void* user);
  // Threads a parallel_for called now from this thread can spread over: 1 inside a part of one
  // of this pool's split jobs (count > grain, spread or run serially) or on a thread that keeps
  // serial, else threads(). Set by the call's structure, not by timing
  // (tacta_host_services::workers_here).
  uint32_t workers_here() const noexcept;
  static uint32_t workers_here_entry(void* jobs);
  // For the rest of the calling thread's life workers_here answers 1 on it: a body stepping on a
  // thread of its own (BodyWorker) beside the tick's bodies keeps its serial solve rather than
  // holding the workers they share for a whole step (a threaded CG takes them ~50 times a step).
  static void keep_serial_on_this_thread() noexcept;
  // Workers that have parked (futex) since their last job, now; for tests.
  uint32_t parked() const noexcept { return parked_.load(); }

 private:
  void work(uint32_t worker) noexcept;
  void run_chunks(uint32_t job, uint32_t worker) noexcept;

  std::atomic<bool> busy_{false};  // a job is running
  // Bumped per job (its low 32 bits are the job's number); workers spin on it, then park on it.
  alignas(64) std::atomic<uint32_t> generation_{0};
  std::atomic<uint32_t> parked_{0};  // workers parked or about to: the caller must notify
  std::atomic<bool> quit_{false};
  // The current job (all seq_cst): a chunk is taken by a compare-exchange on ticket_, which
  // holds the job's number (high 32 bits) and its next index, so a worker late from an earlier
  // job can never take a chunk of a later one; it reads the job before it takes the chunk.
  alignas(64) std::atomic<uint64_t> ticket_{0};
  std::atomic<Body> body_{nullptr};
  std::atomic<void*> user_{nullptr};
  std::atomic<uint32_t> count_{0}, grain_{1};
  alignas(64) std::atomic<uint32_t> done_{0};  // indices finished
  std::vector<std::thread> workers_;
};

// Engine-owned memory for one model instance (tacta_host_services::scratch): 64-byte aligned,
// zeroed blocks, freed with the arena, at most kMaxBytes in all.
class ScratchArena {
 public:
  static constexpr size_t kMaxBytes = size_t{1} << 30;  // 1 GiB per instance
  ScratchArena() = default;
  ~ScratchArena();
  ScratchArena(const ScratchArena&) = delete;
  ScratchArena& operator=(const ScratchArena&) = delete;
  void* allocate(size_t bytes) noexcept;
  size_t bytes() const noexcept { return bytes_; }
  static void* allocate_entry(void* arena, size_t bytes);

 private:
  std::vector<void*> blocks_;
  size_t bytes_ = 0;
};

// The host services a model instance is handed, as the engine fills them: parallel_for on
// `jobs` (null: serial, on the caller) and scratch memory from `arena` (null: none).
tacta_host_services host_services(JobPool* jobs, ScratchArena* arena) noexcept;

}  // namespace tacta
