// A whole HapticLoop tick allocates nothing once warm: engine, model plugin, device plugin, the
// god-object proxy's surface queries and (second case) collision detection and response, over
// the shipped liver palpation scene through its first press. malloc and friends are interposed
// in this executable (tests/support/allocation_counter.hpp); skipped under the sanitizers.
#include "sim_test_support.hpp"

#include "allocation_counter.hpp"

namespace tacta::simtest {
namespace {

constexpr int kWarmUpTicks = 10;  // first steps size solver workspaces and warm-start caches
// Through the approach (0.4 s), the first contact and press (0.3 s) and into the dwell.
constexpr int kCountedTicks = 900;

struct Counted {
  long allocations = 0;
  uint64_t contact_ticks = 0;
  bool frozen = false;
};

Counted count_ticks(const std::vector<std::string>& overrides) {
  const SceneDesc scene = load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml",
                                     schemas(), overrides);
  LoopHarness h(scene, kWarmUpTicks + kCountedTicks);
  for (int i = 0; i < kWarmUpTicks; ++i) h.tick();
  const uint64_t contacts_before = h.world.device(0).stats.contact_ticks;
  g_allocations = 0;
  g_counting = true;
  for (int i = 0; i < kCountedTicks; ++i) h.tick();
  g_counting = false;
  return {g_allocations, h.world.device(0).stats.contact_ticks - contacts_before,
          h.world.body(0).fault.frozen};
}

// The counter sees an allocation made through operator new (so a zero below means something).
TEST(HapticTickAllocations, CounterSeesNew) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  g_allocations = 0;
  g_counting = true;
  auto box = std::make_unique<std::vector<double>>(16);
  g_counting = false;
  EXPECT_EQ(g_allocations, 2) << "the vector object and its storage";
}

TEST(HapticTickAllocations, LiverPalpationAsShipped) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const Counted run = count_ticks({});
  EXPECT_EQ(run.allocations, 0) << "heap allocations in " << kCountedTicks << " ticks";
  EXPECT_GT(run.contact_ticks, 100u) << "the counted ticks must include the stylus pressing";
  EXPECT_FALSE(run.frozen);
}

TEST(HapticTickAllocations, LiverPalpationWithCollisionResponse) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  const Counted run = count_ticks({"collision.enabled=true"});
  EXPECT_EQ(run.allocations, 0) << "heap allocations in " << kCountedTicks << " ticks";
  EXPECT_GT(run.contact_ticks, 100u);
  EXPECT_FALSE(run.frozen);
}

}  // namespace
}  // namespace tacta::simtest
