// The threaded element pass's schedule (sparse::ElementTiles): every item in exactly one tile and
// every tile in exactly one colour; no two tiles of a colour share a node (the pass's tiles
// scatter into their nodes' rows at once); items in index order within a tile; the same
// schedule every time; runs of consecutive items where the items' order is spatial, compact
// tiles (Morton order) where it is not.
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numeric>
#include <random>
#include <vector>

#include "element_tiles.hpp"
#include "tacta/models/test_meshes.hpp"

namespace tacta::models::sparse {
namespace {

constexpr uint32_t kTetsPerItem = 4;  // a batch of the corotational pass

// Items of kTetsPerItem consecutive tets of `tets` (4 node indices each): their nodes and centres.
struct Items {
  std::vector<uint32_t> nodes;
  std::vector<double> centres;
  Items(const std::vector<uint32_t>& tets, const std::vector<double>& positions) {
    const size_t items = tets.size() / (4 * kTetsPerItem);
    nodes.assign(tets.begin(),
                 tets.begin() + static_cast<std::ptrdiff_t>(items * 4 * kTetsPerItem));
    centres.assign(3 * items, 0.0);
    for (size_t i = 0; i < items; ++i)
      for (size_t k = 0; k < 4 * kTetsPerItem; ++k)
        for (size_t c = 0; c < 3; ++c)
          centres[3 * i + c] +=
              positions[3 * size_t{nodes[4 * kTetsPerItem * i + k]} + c] / (4.0 * kTetsPerItem);
  }
  size_t count() const { return centres.size() / 3; }
};

ElementTiles tile(const Items& items, uint32_t node_count) {
  return ElementTiles(items.nodes, 4 * kTetsPerItem, items.centres, node_count);
}

// The mean over tiles of the diagonal of their items' centres' bounding box, m.
double mean_tile_diagonal(const ElementTiles& tiles, const Items& items) {
  double sum = 0.0;
  uint32_t count = 0;
  for (uint32_t c = 0; c < tiles.colours(); ++c)
    for (uint32_t t : tiles.tiles_of(c)) {
      std::array<double, 3> low{1e30, 1e30, 1e30}, high{-1e30, -1e30, -1e30};
      for (uint32_t i : tiles.items_of(t))
        for (size_t k = 0; k < 3; ++k) {
          low[k] = std::min(low[k], items.centres[3 * size_t{i} + k]);
          high[k] = std::max(high[k], items.centres[3 * size_t{i} + k]);
        }
      sum += std::hypot(high[0] - low[0], high[1] - low[1], high[2] - low[2]);
      ++count;
    }
  return sum / count;
}

TEST(ElementTiles, EveryItemOnceAndNoTwoTilesOfAColourShareANode) {
  const TestMesh mesh = box_tet_mesh({12, 6, 6}, {0.24, 0.06, 0.06}, 1000.0);
  const Items items(mesh.tets, mesh.positions);
  const ElementTiles tiles = tile(items, mesh.node_count());
  ASSERT_FALSE(tiles.empty());
  std::vector<int> item_seen(items.count(), 0), tile_seen;
  size_t largest_colour = 0;
  for (uint32_t c = 0; c < tiles.colours(); ++c) {
    std::vector<int> node_owner(mesh.node_count(), -1);
    largest_colour = std::max(largest_colour, tiles.tiles_of(c).size());
    for (uint32_t t : tiles.tiles_of(c)) {
      if (t >= tile_seen.size()) tile_seen.resize(t + 1, 0);
      ++tile_seen[t];
      const auto tile_items = tiles.items_of(t);
      EXPECT_LE(tile_items.size(), ElementTiles::kItemsPerTile);
      EXPECT_TRUE(std::is_sorted(tile_items.begin(), tile_items.end()));
      for (uint32_t i : tile_items) {
        ++item_seen[i];
        for (size_t k = 0; k < 4 * kTetsPerItem; ++k) {
          int& owner = node_owner[items.nodes[4 * kTetsPerItem * i + k]];
          EXPECT_TRUE(owner == -1 || owner == static_cast<int>(t))
              << "tiles " << owner << " and " << t << " of colour " << c << " share a node";
          owner = static_cast<int>(t);
        }
      }
    }
  }
  EXPECT_TRUE(std::all_of(item_seen.begin(), item_seen.end(), [](int n) { return n == 1; }));
  EXPECT_TRUE(std::all_of(tile_seen.begin(), tile_seen.end(), [](int n) { return n == 1; }));
  EXPECT_EQ(tile_seen.size(),
            (items.count() + ElementTiles::kItemsPerTile - 1) / ElementTiles::kItemsPerTile);
  EXPECT_GE(largest_colour, 4u) << "a colour this body's threads can share";
  // The box's items are in a spatial order already: its tiles are runs of consecutive items.
  for (uint32_t c = 0; c < tiles.colours(); ++c)
    for (uint32_t t : tiles.tiles_of(c)) {
      const auto run = tiles.items_of(t);
      EXPECT_EQ(run.back() - run.front() + 1, run.size()) << "tile " << t;
    }
}

TEST(ElementTiles, TheSameScheduleEveryTime) {
  const TestMesh mesh = box_tet_mesh({7, 7, 7}, {0.07, 0.07, 0.07}, 1000.0);
  const Items items(mesh.tets, mesh.positions);
  const ElementTiles a = tile(items, mesh.node_count()), b = tile(items, mesh.node_count());
  ASSERT_EQ(a.colours(), b.colours());
  for (uint32_t c = 0; c < a.colours(); ++c) {
    ASSERT_TRUE(std::ranges::equal(a.tiles_of(c), b.tiles_of(c)));
    for (uint32_t t : a.tiles_of(c)) EXPECT_TRUE(std::ranges::equal(a.items_of(t), b.items_of(t)));
  }
}

TEST(ElementTiles, ItemsInARandomOrderStillGetCompactTiles) {
  const TestMesh mesh = box_tet_mesh({10, 10, 10}, {0.1, 0.1, 0.1}, 1000.0);
  const Items in_order(mesh.tets, mesh.positions);
  // The same items in a random order: tiles of consecutive ones would clash everywhere.
  std::vector<uint32_t> order(in_order.count());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  std::vector<uint32_t> shuffled;
  for (uint32_t i : order)
    shuffled.insert(shuffled.end(), &mesh.tets[4 * kTetsPerItem * i],
                    &mesh.tets[4 * kTetsPerItem * (i + 1)]);
  const Items scattered(shuffled, mesh.positions);
  const ElementTiles tiles = tile(scattered, mesh.node_count());
  // 16 items of 4 tets are about 11 of the 1 cm cells: a compact tile spans a few cells (a cube
  // of 11 cells has a 3.8 cm diagonal), where 16 items taken at random span the 17 cm body.
  EXPECT_LT(mean_tile_diagonal(tiles, scattered), 0.06);
  size_t largest_colour = 0;
  for (uint32_t c = 0; c < tiles.colours(); ++c)
    largest_colour = std::max(largest_colour, tiles.tiles_of(c).size());
  EXPECT_GE(largest_colour, 4u) << "a colour the threads can share";
}

TEST(ElementTiles, NoItemsNoTiles) {
  const ElementTiles tiles({}, 16, {}, 10);
  EXPECT_TRUE(tiles.empty());
  EXPECT_EQ(tiles.colours(), 0u);
}

}  // namespace
}  // namespace tacta::models::sparse
