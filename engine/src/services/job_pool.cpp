#include "job_pool.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <new>
#include <pthread.h>
#include <string>

namespace tacta {

namespace {
// After its own chunks the caller waits for the workers' last chunks: it spins this long, then
// parks on done_ (a chunk is tens of microseconds; parking only guards against a worker that
// was preempted).
constexpr std::chrono::microseconds kCallerSpin{200};
// Spinning starts with pause only, for the quickest hand-over; past this it yields the CPU at
// each turn, so that on an oversubscribed machine a spinning thread does not hold the core the
// thread it waits for (the caller, or a worker holding a chunk) needs.
constexpr std::chrono::microseconds kPauseOnly{20};

inline void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// The pool whose split job this thread is running a part of, if any (workers_here).
thread_local const JobPool* splitting_here = nullptr;
thread_local bool serial_thread = false;  // keep_serial_on_this_thread was called

// Marks this thread as running a part of `pool`'s split job for its scope (nested: restored).
class SplitMark {
 public:
  explicit SplitMark(const JobPool* pool) noexcept : outer_(splitting_here) {
    splitting_here = pool;
  }
  ~SplitMark() { splitting_here = outer_; }
  SplitMark(const SplitMark&) = delete;
  SplitMark& operator=(const SplitMark&) = delete;

 private:
  const JobPool* outer_;
};
}  // namespace

JobPool::JobPool(uint32_t threads) {
  const uint32_t workers = threads > 1 ? threads - 1 : 0;
  workers_.reserve(workers);
  for (uint32_t w = 0; w < workers; ++w)
    workers_.emplace_back([this, w] {
      // "tacta-body..." names keep their priority in a realtime session: this is simulation work.
      pthread_setname_np(pthread_self(), ("tacta-body-job" + std::to_string(w + 1)).c_str());
      work(w + 1);
    });
}

JobPool::~JobPool() {
  quit_.store(true);
  generation_.fetch_add(1);
  generation_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void JobPool::run_chunks(uint32_t job, uint32_t worker) noexcept {
  const SplitMark mark(this);  // every chunk run here is a part of a split job
  for (;;) {
    uint64_t ticket = ticket_.load();
    if (static_cast<uint32_t>(ticket >> 32) != job) return;
    const Body body = body_.load();
    void* const user = user_.load();
    const uint32_t count = count_.load(), grain = grain_.load();
    const auto begin = static_cast<uint32_t>(ticket);
    if (begin >= count) return;
    const uint32_t end = begin + std::min(grain, count - begin);
    if (!ticket_.compare_exchange_weak(ticket, (ticket & ~uint64_t{0xffffffff}) | end)) continue;
    body(user, begin, end, worker);
    if (done_.fetch_add(end - begin) + (end - begin) == count) done_.notify_one();
  }
}

void JobPool::work(uint32_t worker) noexcept {
  using Clock = std::chrono::steady_clock;
  uint32_t seen = 0;
  for (;;) {
    uint32_t now = generation_.load();
    if (now == seen) {  // idle: spin, then park
      const Clock::time_point start = Clock::now();
      bool yielding = false;
      for (uint32_t spin = 1; (now = generation_.load()) == seen; ++spin) {
        if (yielding)
          std::this_thread::yield();
        else
          cpu_relax();
        if (spin % 64 != 0) continue;
        const Clock::duration idle = Clock::now() - start;
        yielding = idle >= kPauseOnly;
        if (idle < kSpinBeforePark) continue;
        // Announce the park before the last look (seq_cst both): a caller that bumps the
        // generation after that look sees parked_ and wakes us.
        parked_.fetch_add(1);
        while ((now = generation_.load()) == seen) generation_.wait(seen);
        parked_.fetch_sub(1);
        break;
      }
    }
    seen = now;
    if (quit_.load()) return;
    run_chunks(seen, worker);
  }
}

void JobPool::parallel_for(uint32_t count, uint32_t grain, Body body, void* user) noexcept {
  if (count == 0) return;
  grain = std::max<uint32_t>(grain, 1);
  if (count <= grain) {  // one part: it runs alone, as the call's caller would
    body(user, 0, count, 0);
    return;
  }
  bool expected = false;
  if (workers_.empty() || !busy_.compare_exchange_strong(expected, true)) {
    const SplitMark mark(this);
    body(user, 0, count, 0);
    return;
  }
  const uint32_t job = generation_.load() + 1;
  // The ticket first: from here no late worker can take a chunk of the last job's numbering.
  ticket_.store(uint64_t{job} << 32);
  body_.store(body);
  user_.store(user);
  count_.store(count);
  grain_.store(grain);
  done_.store(0);
  generation_.fetch_add(1);
  if (parked_.load() != 0) generation_.notify_all();  // spinning workers see the bump alone
  run_chunks(job, 0);
  using Clock = std::chrono::steady_clock;
  if (done_.load() != count) {
    const Clock::time_point start = Clock::now();
    bool yielding = false;
    for (uint32_t spin = 1; done_.load() != count; ++spin) {
      if (yielding)
        std::this_thread::yield();
      else
        cpu_relax();
      if (spin % 64 != 0) continue;
      const Clock::duration waited = Clock::now() - start;
      yielding = waited >= kPauseOnly;
      if (waited < kCallerSpin) continue;
      for (uint32_t seen = done_.load(); seen != count; seen = done_.load()) done_.wait(seen);
    }
  }
  busy_.store(false);
}

uint32_t JobPool::workers_here() const noexcept {
  return serial_thread || splitting_here == this ? 1u : threads();
}

void JobPool::keep_serial_on_this_thread() noexcept { serial_thread = true; }

uint32_t JobPool::workers_here_entry(void* jobs) {
  return static_cast<const JobPool*>(jobs)->workers_here();
}

void JobPool::parallel_for_entry(void* jobs, uint32_t count, uint32_t grain, Body body,
                                 void* user) {
  static_cast<JobPool*>(jobs)->parallel_for(count, grain, body, user);
}

ScratchArena::~ScratchArena() {
  for (void* b : blocks_) std::free(b);
}

void* ScratchArena::allocate(size_t bytes) noexcept {
  constexpr size_t kAlign = 64;
  const size_t rounded = (bytes + kAlign - 1) / kAlign * kAlign;
  if (bytes == 0 || rounded > kMaxBytes - bytes_) return nullptr;
  void* block = std::aligned_alloc(kAlign, rounded);
  if (block == nullptr) return nullptr;
  try {
    blocks_.push_back(block);
  } catch (...) {
    std::free(block);
    return nullptr;
  }
  std::memset(block, 0, rounded);
  bytes_ += rounded;
  return block;
}

void* ScratchArena::allocate_entry(void* arena, size_t bytes) {
  return static_cast<ScratchArena*>(arena)->allocate(bytes);
}

namespace {
// parallel_for without an engine pool (a model created alone, e.g. by a test): the caller does all.
void serial_for(void*, uint32_t count, uint32_t, void (*body)(void*, uint32_t, uint32_t, uint32_t),
                void* user) {
  if (count > 0) body(user, 0, count, 0);
}
}  // namespace

tacta_host_services host_services(JobPool* jobs, ScratchArena* arena) noexcept {
  tacta_host_services services{};
  services.struct_size = sizeof services;
  services.worker_count = jobs != nullptr ? jobs->threads() : 1;
  services.parallel_for = jobs != nullptr ? &JobPool::parallel_for_entry : &serial_for;
  services.jobs = jobs;
  services.scratch = arena != nullptr ? &ScratchArena::allocate_entry : nullptr;
  services.arena = arena;
  services.workers_here = jobs != nullptr ? &JobPool::workers_here_entry : nullptr;
  return services;
}

}  // namespace tacta
