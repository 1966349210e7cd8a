// EntityCommandRing: requesters on one thread post add and remove commands while the tick's
// thread drains them, as a realtime run does. Every command arrives once and in order, a full
// ring refuses instead of overwriting. Part of sim_concurrency_test (ThreadSanitizer: preset tsan).
#include <atomic>
#include <gtest/gtest.h>
#include <thread>

#include "world/entity_commands.hpp"

namespace {

using tacta::EntityCommand;
using tacta::EntityCommandRing;

TEST(EntityCommandRing, FullRingRefuses) {
  EntityCommandRing ring(2);
  EXPECT_TRUE(ring.push({EntityCommand::kAddBody, 1, 0}));
  EXPECT_TRUE(ring.push({EntityCommand::kRemoveBody, 1, 0}));
  EXPECT_FALSE(ring.push({EntityCommand::kAddBody, 2, 0}));
  EntityCommand c;
  ASSERT_TRUE(ring.pop(c));
  EXPECT_EQ(c.kind, EntityCommand::kAddBody);
  ASSERT_TRUE(ring.pop(c));
  EXPECT_EQ(c.kind, EntityCommand::kRemoveBody);
  EXPECT_FALSE(ring.pop(c));
}

TEST(EntityCommandRing, RequesterAndTickThreadsHandOverInOrder) {
  constexpr uint32_t kCommands = 20000;
  EntityCommandRing ring(16);
  std::thread tick([&] {
    uint32_t expected = 0;
    EntityCommand c;
    while (expected < kCommands) {
      if (!ring.pop(c)) continue;
      ASSERT_EQ(c.slot, expected);
      ASSERT_EQ(c.kind, expected % 2 ? EntityCommand::kRemoveBody : EntityCommand::kAddBody);
      ++expected;
    }
  });
  for (uint32_t i = 0; i < kCommands;) {
    const EntityCommand c{i % 2 ? EntityCommand::kRemoveBody : EntityCommand::kAddBody, i, 0};
    if (ring.push(c)) ++i;
  }
  tick.join();
}

}  // namespace
