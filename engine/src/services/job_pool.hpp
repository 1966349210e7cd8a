// Engine-owned worker threads for plugins' parallel_for (tacta_host_services): the calling
// thread and `threads - 1` workers split [0, count) into chunks taken from an atomic counter.
// No allocation, no mutex: workers sleep on an atomic generation (a futex) between jobs, and
// the caller spins briefly then waits on the done count. One job at a time; a second caller
// while a job runs gets a serial run on its own thread (two bodies stepping on two threads).
#pragma once

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace tacta {

class JobPool {
 public:
  using Body = void (*)(void* user, uint32_t begin, uint32_t end, uint32_t worker);

  explicit JobPool(uint32_t threads);  // 1: no workers, every job serial on the caller
  ~JobPool();
  JobPool(const JobPool&) = delete;
  JobPool& operator=(const JobPool&) = delete;

  uint32_t threads() const noexcept { return static_cast<uint32_t>(workers_.size()) + 1; }
  void parallel_for(uint32_t count, uint32_t grain, Body body, void* user) noexcept;
  // The C entry of tacta_host_services (jobs = this).
  static void parallel_for_entry(void* jobs, uint32_t count, uint32_t grain, Body body, void* user);

 private:
  void work(uint32_t worker) noexcept;
  void run_chunks(uint32_t job, uint32_t worker) noexcept;

  std::atomic<bool> busy_{false};        // a job is running
  std::atomic<uint64_t> generation_{0};  // bumped per job; workers wait on it
  std::atomic<bool> quit_{false};
  // The current job (all seq_cst): a chunk is taken by a compare-exchange on ticket_, which
  // holds the job's number (high 32 bits) and its next index, so a worker late from an earlier
  // job can never take a chunk of a later one; it reads the job before it takes the chunk.
  std::atomic<uint64_t> ticket_{0};
  std::atomic<Body> body_{nullptr};
  std::atomic<void*> user_{nullptr};
  std::atomic<uint32_t> count_{0}, grain_{1};
  std::atomic<uint32_t> done_{0};  // indices finished
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

}  // namespace tacta
