// The engine's job pool (host services' parallel_for): every index runs exactly once on any
// thread count and grain, the chunks really spread over workers, a second caller while a job
// runs is served serially on its own thread, workers_here is 1 inside a split job's parts and
// on serial threads, idle workers park after their spin and wake for the next job, and the
// scratch arena hands out aligned zeroed blocks up to its limit. Runs under ThreadSanitizer
// (label tsan).
#include <atomic>
#include <chrono>
#include <cstdint>
#include <gtest/gtest.h>
#include <set>
#include <thread>
#include <vector>

#include "services/job_pool.hpp"

namespace {

struct Counts {
  std::vector<std::atomic<int>> hits;
  std::atomic<uint32_t> workers_seen{0};  // bit w: worker w ran a chunk
  explicit Counts(size_t n) : hits(n) {}
};

void count_body(void* user, uint32_t begin, uint32_t end, uint32_t worker) {
  auto& c = *static_cast<Counts*>(user);
  for (uint32_t i = begin; i < end; ++i) c.hits[i].fetch_add(1);
  c.workers_seen.fetch_or(1u << worker);
  // Long enough chunks that the workers, not only the caller, get some.
  std::this_thread::yield();
}

TEST(JobPool, EveryIndexRunsExactlyOnce) {
  for (uint32_t threads : {1u, 2u, 3u}) {
    tacta::JobPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (uint32_t grain : {1u, 7u, 64u}) {
      for (int job = 0; job < 20; ++job) {
        Counts counts(1000);
        pool.parallel_for(1000, grain, &count_body, &counts);
        for (size_t i = 0; i < counts.hits.size(); ++i) ASSERT_EQ(counts.hits[i].load(), 1) << i;
      }
    }
  }
}

TEST(JobPool, ChunksSpreadOverTheWorkers) {
  tacta::JobPool pool(2);
  uint32_t seen = 0;
  for (int job = 0; job < 50 && seen != 3u; ++job) {
    Counts counts(4000);
    pool.parallel_for(4000, 8, &count_body, &counts);
    seen |= counts.workers_seen.load();
  }
  EXPECT_EQ(seen, 3u) << "the worker thread never took a chunk";
}

TEST(JobPool, TwoCallersAtOnceBothFinish) {
  tacta::JobPool pool(2);
  Counts a(3000), b(3000);
  std::thread other([&] {
    for (int job = 0; job < 20; ++job) pool.parallel_for(3000, 16, &count_body, &b);
  });
  for (int job = 0; job < 20; ++job) pool.parallel_for(3000, 16, &count_body, &a);
  other.join();
  for (size_t i = 0; i < 3000; ++i) {
    ASSERT_EQ(a.hits[i].load(), 20);
    ASSERT_EQ(b.hits[i].load(), 20);
  }
}

// How many parts of a job saw workers_here() as 1, and how many as the pool's threads.
struct WorkersSeen {
  const tacta::JobPool* pool = nullptr;
  std::atomic<uint32_t> one{0}, all{0};
};

void note_workers_here(void* user, uint32_t, uint32_t, uint32_t) {
  auto& seen = *static_cast<WorkersSeen*>(user);
  const uint32_t here = seen.pool->workers_here();
  if (here == 1) seen.one.fetch_add(1);
  if (here == seen.pool->threads()) seen.all.fetch_add(1);
  std::this_thread::yield();
}

TEST(JobPool, WorkersHereIsOneInsideTheSplitJobsPartsAndOnSerialThreads) {
  tacta::JobPool pool(3), other(3);
  EXPECT_EQ(pool.workers_here(), 3u);
  WorkersSeen split{&pool}, alone{&pool}, busy{&pool}, foreign{&pool};
  pool.parallel_for(64, 1, &note_workers_here, &split);  // spread: caller and workers
  EXPECT_EQ(split.one.load(), 64u);
  pool.parallel_for(1, 1, &note_workers_here, &alone);  // one part: it has the workers
  EXPECT_EQ(alone.all.load(), 1u);
  // A split job run serially because another caller holds the workers is still split: the
  // answer follows the call, not the timing.
  std::atomic<bool> held{false}, release{false};
  std::thread holder([&] {
    struct Hold {
      std::atomic<bool>* held;
      std::atomic<bool>* release;
    } hold{&held, &release};
    pool.parallel_for(
        2, 1,
        [](void* user, uint32_t, uint32_t, uint32_t) {
          auto& h = *static_cast<Hold*>(user);
          h.held->store(true);
          while (!h.release->load()) std::this_thread::yield();
        },
        &hold);
  });
  while (!held.load()) std::this_thread::yield();
  pool.parallel_for(8, 1, &note_workers_here, &busy);
  release.store(true);
  holder.join();
  EXPECT_EQ(busy.one.load(), 1u);  // one serial run of all 8
  EXPECT_EQ(busy.all.load(), 0u);
  // Another pool's job does not take this pool's workers.
  other.parallel_for(8, 1, &note_workers_here, &foreign);
  EXPECT_EQ(foreign.all.load(), 8u);
  EXPECT_EQ(pool.workers_here(), 3u);
  // A thread that keeps serial (a body on its own thread) is answered 1 by every pool.
  uint32_t on_serial_thread[2] = {0, 0};
  std::thread([&] {
    tacta::JobPool::keep_serial_on_this_thread();
    on_serial_thread[0] = pool.workers_here();
    on_serial_thread[1] = other.workers_here();
  }).join();
  EXPECT_EQ(on_serial_thread[0], 1u);
  EXPECT_EQ(on_serial_thread[1], 1u);
  EXPECT_EQ(pool.workers_here(), 3u) << "only that thread";
}

TEST(JobPool, IdleWorkersSpinThenParkAndWakeForTheNextJob) {
  tacta::JobPool pool(3);
  Counts first(2000);
  pool.parallel_for(2000, 8, &count_body, &first);
  // Idle past the spin window: both workers park (futex) and stop burning their cores.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (pool.parked() != 2 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(tacta::JobPool::kSpinBeforePark);
  EXPECT_EQ(pool.parked(), 2u);
  // A job wakes them: every index still runs once, and the workers take chunks again.
  uint32_t seen = 0;
  for (int job = 0; job < 50 && seen != 7u; ++job) {
    Counts counts(4000);
    pool.parallel_for(4000, 8, &count_body, &counts);
    for (size_t i = 0; i < counts.hits.size(); ++i) ASSERT_EQ(counts.hits[i].load(), 1) << i;
    seen |= counts.workers_seen.load();
  }
  EXPECT_EQ(seen, 7u) << "a parked worker never woke for a job";
}

TEST(ScratchArena, AlignedZeroedAndBounded) {
  tacta::ScratchArena arena;
  auto* p = static_cast<unsigned char*>(tacta::ScratchArena::allocate_entry(&arena, 100));
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(p) % 64, 0u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(p[i], 0);
  EXPECT_EQ(arena.bytes(), 128u);
  EXPECT_EQ(arena.allocate(0), nullptr);
  EXPECT_EQ(arena.allocate(tacta::ScratchArena::kMaxBytes), nullptr) << "past the limit";
}

}  // namespace
