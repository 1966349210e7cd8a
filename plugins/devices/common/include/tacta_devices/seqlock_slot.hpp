// A value of N doubles handed from one writer thread to readers without a lock: a sequence
// lock over atomics (a reader retries while a write is in progress; a write takes nanoseconds).
// How the devices pass a host's or a network thread's data to the 1 kHz path and back.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace tacta::devices {

template <size_t N>
class SeqlockSlot {
 public:
  using Value = std::array<double, N>;

  // One writer at a time.
  void store(const Value& v) noexcept {
    const uint64_t s = sequence_.load(std::memory_order_relaxed);
    sequence_.store(s + 1, std::memory_order_relaxed);  // odd: writing
    std::atomic_thread_fence(std::memory_order_release);
    for (size_t i = 0; i < N; ++i) value_[i].store(v[i], std::memory_order_relaxed);
    sequence_.store(s + 2, std::memory_order_release);
  }
  // False while nothing was ever stored (out untouched).
  bool load(Value& out) const noexcept {
    for (;;) {
      const uint64_t before = sequence_.load(std::memory_order_acquire);
      if (before == 0) return false;
      if (before & 1) continue;
      Value v;
      for (size_t i = 0; i < N; ++i) v[i] = value_[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (sequence_.load(std::memory_order_relaxed) == before) {
        out = v;
        return true;
      }
    }
  }

 private:
  std::atomic<uint64_t> sequence_{0};
  std::array<std::atomic<double>, N> value_{};
};

}  // namespace tacta::devices
