// ECS: stale handles are detected, slots are recycled with a new generation, pools stay dense
// after removals, and views visit exactly the entities having every requested component.
#include <algorithm>
#include <gtest/gtest.h>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "tacta/ecs.hpp"

namespace {

using tacta::ecs::Entity;
using tacta::ecs::Registry;

struct Position {
  double x = 0, y = 0, z = 0;  // m
};
struct Mass {
  double kg = 0;
};
struct Tag {
  int value = 0;
};

TEST(Ecs, CreatedEntitiesAreValidAndDistinct) {
  Registry registry;
  const Entity a = registry.create();
  const Entity b = registry.create();
  EXPECT_TRUE(registry.valid(a));
  EXPECT_TRUE(registry.valid(b));
  EXPECT_NE(a, b);
  EXPECT_EQ(registry.alive_count(), 2u);
  EXPECT_FALSE(registry.valid(Entity{}));  // default handle is null, never valid
}

TEST(Ecs, DestroyedHandleIsStale) {
  Registry registry;
  const Entity e = registry.create();
  registry.emplace<Position>(e, 1.0, 2.0, 3.0);
  registry.destroy(e);
  EXPECT_FALSE(registry.valid(e));
  EXPECT_EQ(registry.try_get<Position>(e), nullptr);
  EXPECT_FALSE(registry.has<Position>(e));
  try {
    registry.get<Position>(e);
    FAIL() << "get on a destroyed entity must throw";
  } catch (const std::out_of_range& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("index 0"), std::string::npos) << what;
    EXPECT_NE(what.find("generation 1"), std::string::npos) << what;
    EXPECT_NE(what.find("destroyed"), std::string::npos) << what;
  }
  EXPECT_THROW(registry.destroy(e), std::out_of_range);
  EXPECT_THROW(registry.emplace<Mass>(e, 1.0), std::out_of_range);
  EXPECT_THROW(registry.remove<Position>(e), std::out_of_range);
}

TEST(Ecs, RecycledSlotGetsNewGenerationAndOldHandleStaysStale) {
  Registry registry;
  const Entity old_handle = registry.create();
  registry.emplace<Mass>(old_handle, 5.0);
  registry.destroy(old_handle);
  const Entity reused = registry.create();
  ASSERT_EQ(reused.index, old_handle.index);  // the slot is recycled
  EXPECT_EQ(reused.generation, old_handle.generation + 1);
  EXPECT_TRUE(registry.valid(reused));
  EXPECT_FALSE(registry.valid(old_handle));
  EXPECT_FALSE(registry.has<Mass>(reused));  // components do not survive into the new entity
  registry.emplace<Mass>(reused, 7.0);
  EXPECT_EQ(registry.try_get<Mass>(old_handle), nullptr);
  try {
    registry.get<Mass>(old_handle);
    FAIL() << "get through an old handle to a recycled slot must throw";
  } catch (const std::out_of_range& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("index 0 generation 1"), std::string::npos) << what;
    EXPECT_NE(what.find("generation 2"), std::string::npos) << what;
  }
  EXPECT_DOUBLE_EQ(registry.get<Mass>(reused).kg, 7.0);
}

TEST(Ecs, NeverCreatedIndexIsReported) {
  Registry registry;
  registry.create();
  try {
    registry.get<Mass>(Entity{42, 1});
    FAIL();
  } catch (const std::out_of_range& error) {
    EXPECT_NE(std::string(error.what()).find("index 42 was never created"), std::string::npos);
  }
}

TEST(Ecs, EmplaceGetTryGetRemoveHas) {
  Registry registry;
  const Entity e = registry.create();
  Position& p = registry.emplace<Position>(e, 0.5, -1.0, 2.0);
  EXPECT_DOUBLE_EQ(p.y, -1.0);
  EXPECT_TRUE(registry.has<Position>(e));
  EXPECT_FALSE((registry.has<Position, Mass>(e)));
  EXPECT_EQ(registry.try_get<Mass>(e), nullptr);
  EXPECT_THROW(registry.get<Mass>(e), std::out_of_range);
  EXPECT_THROW(registry.emplace<Position>(e), std::logic_error);
  registry.get<Position>(e).z = 9.0;
  EXPECT_DOUBLE_EQ(registry.try_get<Position>(e)->z, 9.0);
  EXPECT_TRUE(registry.remove<Position>(e));
  EXPECT_FALSE(registry.remove<Position>(e));
  EXPECT_FALSE(registry.has<Position>(e));
  EXPECT_TRUE(registry.valid(e));  // removing a component keeps the entity
}

TEST(Ecs, PoolStaysDenseAfterRemovals) {
  Registry registry;
  std::vector<Entity> entities;
  for (int i = 0; i < 10; ++i) {
    entities.push_back(registry.create());
    registry.emplace<Tag>(entities.back(), i);
  }
  // Remove the even tags: the survivors must be packed at the front with no holes.
  for (int i = 0; i < 10; i += 2) registry.remove<Tag>(entities[static_cast<size_t>(i)]);
  auto& pool = registry.pool<Tag>();
  ASSERT_EQ(pool.size(), 5u);
  ASSERT_EQ(pool.components().size(), 5u);
  ASSERT_EQ(pool.entities().size(), 5u);
  std::set<int> seen;
  for (size_t k = 0; k < pool.size(); ++k) {
    const Entity owner = pool.entities()[k];
    const int value = pool.components()[k].value;
    EXPECT_EQ(value % 2, 1);
    EXPECT_EQ(owner, entities[static_cast<size_t>(value)]);  // entity and component stay paired
    EXPECT_EQ(&registry.get<Tag>(owner), &pool.components()[k]);
    seen.insert(value);
  }
  EXPECT_EQ(seen, (std::set<int>{1, 3, 5, 7, 9}));
  // Destroying entities also empties their pool slots.
  registry.destroy(entities[1]);
  registry.destroy(entities[9]);
  EXPECT_EQ(pool.size(), 3u);
}

TEST(Ecs, MultiComponentViewVisitsExactlyTheIntersection) {
  Registry registry;
  std::vector<Entity> both;
  for (int i = 0; i < 20; ++i) {
    const Entity e = registry.create();
    registry.emplace<Position>(e, double(i), 0.0, 0.0);
    if (i % 3 == 0) {
      registry.emplace<Mass>(e, 0.1 * i);
      both.push_back(e);
    }
  }
  auto view = registry.view<Position, Mass>();
  EXPECT_EQ(view.size_hint(), 7u);  // iteration is driven by the smaller pool (Mass)
  EXPECT_EQ(view.count(), 7u);
  std::vector<Entity> visited;
  view.each([&](Entity e, Position& p, Mass& m) {
    EXPECT_DOUBLE_EQ(m.kg, 0.1 * p.x);
    p.y = 1.0;  // written through the view
    visited.push_back(e);
  });
  EXPECT_EQ(visited, both);
  for (const Entity e : both) EXPECT_DOUBLE_EQ(registry.get<Position>(e).y, 1.0);

  // Removing Mass from one entity drops it from the view; the other pool drives nothing new.
  registry.remove<Mass>(both[2]);
  EXPECT_EQ((registry.view<Position, Mass>().count()), 6u);
  EXPECT_EQ(registry.view<Position>().count(), 20u);
  EXPECT_EQ((registry.view<Position, Mass, Tag>().count()), 0u);
}

TEST(Ecs, ViewSkipsDestroyedEntities) {
  Registry registry;
  const Entity a = registry.create();
  const Entity b = registry.create();
  registry.emplace<Mass>(a, 1.0);
  registry.emplace<Mass>(b, 2.0);
  registry.destroy(a);
  double total = 0;
  registry.view<Mass>().each([&](Entity e, Mass& m) {
    EXPECT_EQ(e, b);
    total += m.kg;
  });
  EXPECT_DOUBLE_EQ(total, 2.0);
}

// Reserved room: creating, emplacing and destroying within it never moves the components (the
// haptic task takes bodies in and out at tick boundaries without allocating).
TEST(Ecs, ReserveKeepsComponentsInPlace) {
  Registry registry;
  registry.reserve<Mass>(64);
  std::vector<Entity> es;
  for (int i = 0; i < 64; ++i) {
    es.push_back(registry.create());
    registry.emplace<Mass>(es.back(), 1.0 * i);
  }
  const Mass* first = registry.pool<Mass>().components().data();
  for (int i = 0; i < 32; ++i) registry.destroy(es[static_cast<size_t>(2 * i)]);
  for (int i = 0; i < 32; ++i) registry.emplace<Mass>(registry.create(), 2.0);
  EXPECT_EQ(registry.pool<Mass>().components().data(), first);
  EXPECT_EQ(registry.pool<Mass>().size(), 64u);
  EXPECT_FALSE(registry.valid(es[0]))
      << "the destroyed handle stays stale after its slot is reused";
}

}  // namespace
