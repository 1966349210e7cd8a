// The command buffer between whoever adds or removes entities (or changes a tool) while a scene runs and the thread
// that owns the tick: a single-producer single-consumer ring of fixed capacity (requesters are
// serialised among themselves), drained at a tick boundary. Neither side waits or allocates.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

namespace tacta {

struct EntityCommand {
  enum Kind : uint8_t { kAddBody, kRemoveBody, kChangeTool };
  Kind kind = kAddBody;
  uint32_t slot = 0;  // the body slot; kChangeTool: the device
  double time_s = 0;  // s; for a scene's timed events, when it applies
  uint32_t item = 0;  // kChangeTool from a scene event: its prebuilt tool
};

class EntityCommandRing {
 public:
  // Allocates the ring once; `capacity` commands can wait at a time.
  explicit EntityCommandRing(size_t capacity = 0) : buffer_(capacity + 1) {}
  void resize(size_t capacity) { buffer_.assign(capacity + 1, {}); }

  // Producer: false when full.
  bool push(const EntityCommand& command) noexcept {
    const size_t head = head_.load(std::memory_order_relaxed);
    const size_t next = (head + 1) % buffer_.size();
    if (next == tail_.load(std::memory_order_acquire)) return false;
    buffer_[head] = command;
    head_.store(next, std::memory_order_release);
    return true;
  }

  // Consumer: false when empty.
  bool pop(EntityCommand& command) noexcept {
    const size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    command = buffer_[tail];
    tail_.store((tail + 1) % buffer_.size(), std::memory_order_release);
    return true;
  }

 private:
  std::vector<EntityCommand> buffer_;
  std::atomic<size_t> head_{0};  // next slot the producer writes
  std::atomic<size_t> tail_{0};  // next slot the consumer reads
};

}  // namespace tacta
