// A single-producer, single-consumer triple buffer: the haptic task publishes snapshots at its
// own rate, the render task reads the newest one, and neither ever waits for the other. No lock,
// no allocation after construction: the three slots are built once and reused.
#pragma once

#include <atomic>
#include <cstdint>

namespace tacta {

template <class T>
class TripleBuffer {
 public:
  TripleBuffer() = default;
  // Builds every slot from the same prototype so slots have the same capacities (no allocation
  // later when the producer fills them).
  explicit TripleBuffer(const T& prototype) : slots_{prototype, prototype, prototype} {}

  // Producer: the slot to fill. Stays the producer's until publish().
  T& write_slot() noexcept { return slots_[write_]; }

  // Producer: hands the filled slot over; the previous middle slot becomes the next write slot.
  void publish() noexcept {
    const uint8_t previous =
        middle_.exchange(static_cast<uint8_t>(write_ | kFresh), std::memory_order_acq_rel);
    write_ = previous & kIndexMask;
  }

  // Consumer: takes the newest published slot if there is one; returns true when it is new.
  bool acquire() noexcept {
    if ((middle_.load(std::memory_order_relaxed) & kFresh) == 0) return false;
    const uint8_t previous = middle_.exchange(read_, std::memory_order_acq_rel);
    read_ = previous & kIndexMask;
    return true;
  }

  // Every slot, for a change of shape made while neither side runs (allocates).
  template <class F>
  void for_each_slot(F&& change) {
    for (T& slot : slots_) change(slot);
  }

  // Consumer: the slot taken by the last acquire() (a default slot before the first).
  const T& read_slot() const noexcept { return slots_[read_]; }

 private:
  static constexpr uint8_t kIndexMask = 0x3;
  static constexpr uint8_t kFresh = 0x4;  // set when the middle slot holds an unread snapshot
  T slots_[3];
  uint8_t write_ = 0;               // owned by the producer
  uint8_t read_ = 1;                // owned by the consumer
  std::atomic<uint8_t> middle_{2};  // shared: index of the middle slot plus the fresh bit
};

}  // namespace tacta
