// TripleBuffer: one producer thread publishes versioned snapshots (every element holds the
// version), one consumer reads them. Every read must be whole (no element from another version),
// versions must only go up, and the last version published must be seen. Built with the scheduler
// test into sim_concurrency_test, which also runs under ThreadSanitizer (preset tsan).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <gtest/gtest.h>
#include <thread>
#include <vector>

#include "tacta/sim/triple_buffer.hpp"

namespace {

using Versioned = std::vector<uint64_t>;

TEST(TripleBuffer, SingleThreadSequence) {
  tacta::TripleBuffer<Versioned> buffer(Versioned(8, 0));
  EXPECT_FALSE(buffer.acquire()) << "nothing was published yet";
  EXPECT_EQ(buffer.read_slot().size(), 8u) << "slots are built from the prototype";
  for (uint64_t v : {1u, 2u}) {
    std::fill(buffer.write_slot().begin(), buffer.write_slot().end(), v);
    buffer.publish();
  }
  ASSERT_TRUE(buffer.acquire());
  EXPECT_EQ(buffer.read_slot().front(), 2u)
      << "the consumer gets the newest snapshot, not the oldest";
  EXPECT_FALSE(buffer.acquire()) << "a snapshot is new only once";
  EXPECT_EQ(buffer.read_slot().front(), 2u)
      << "the read slot stays readable after a failed acquire";
  std::fill(buffer.write_slot().begin(), buffer.write_slot().end(), 3u);
  EXPECT_EQ(buffer.read_slot().front(), 2u) << "the producer's slot is not the consumer's";
  buffer.publish();
  ASSERT_TRUE(buffer.acquire());
  EXPECT_EQ(buffer.read_slot().back(), 3u);
}

TEST(TripleBuffer, ProducerConsumerReadsAreWholeAndMonotonic) {
  // The producer keeps publishing until it has made kMinVersions and the consumer has read
  // kMinReads, so the two threads really overlap even when one of them starts late.
  constexpr uint64_t kMinVersions = 20000, kMinReads = 50;
  constexpr size_t kElements = 512;
  tacta::TripleBuffer<Versioned> buffer(Versioned(kElements, 0));
  std::atomic<uint64_t> consumer_reads{0}, final_version{0};
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);

  std::thread producer([&] {
    uint64_t v = 0;
    while ((v < kMinVersions || consumer_reads.load(std::memory_order_relaxed) < kMinReads) &&
           std::chrono::steady_clock::now() < give_up) {
      ++v;
      Versioned& slot = buffer.write_slot();
      for (uint64_t& e : slot) e = v;  // every element = version
      buffer.publish();
    }
    final_version.store(v, std::memory_order_release);
  });

  uint64_t last = 0, reads = 0, torn = 0, backwards = 0;
  while (std::chrono::steady_clock::now() < give_up) {
    const uint64_t done = final_version.load(std::memory_order_acquire);
    if (done != 0 && last == done) break;
    if (!buffer.acquire()) continue;
    const Versioned& slot = buffer.read_slot();
    const uint64_t v = slot.front();
    if (std::any_of(slot.begin(), slot.end(), [v](uint64_t e) { return e != v; })) ++torn;
    if (v <= last) ++backwards;  // a snapshot taken as new must be newer than the last one
    last = std::max(last, v);
    consumer_reads.store(++reads, std::memory_order_relaxed);
  }
  producer.join();
  EXPECT_EQ(torn, 0u) << "a read mixed two versions";
  EXPECT_EQ(backwards, 0u) << "a new read was not newer than the previous one";
  EXPECT_GE(final_version.load(), kMinVersions);
  EXPECT_EQ(last, final_version.load()) << "the final version was never seen";
  EXPECT_GE(reads, kMinReads) << "the consumer hardly ran while the producer published";
  EXPECT_EQ(buffer.read_slot().size(), kElements) << "no slot was reallocated";
}

}  // namespace
