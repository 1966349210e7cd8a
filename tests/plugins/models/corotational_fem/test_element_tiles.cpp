// The threaded element pass's schedule (sparse::ElementTiles), on every path it takes (runs of
// consecutive items, Morton order, small bodies): every item in exactly one tile and every tile
// in exactly one colour; at most items_per_tile items a tile, in index order; no two tiles of a
// colour share a node (the pass's tiles scatter into their nodes' rows at once). Runs of
// consecutive items where the items' order is spatial, compact tiles where it is not; an input
// that is not a list of items gives no schedule. Items are batches of 4 tets (the corotational
// pass, 16 a tile) or single tets (the hyperelastic pass, 64 a tile).
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "element_tiles.hpp"
#include "tacta/models/test_meshes.hpp"

namespace tacta::models::sparse {
namespace {

constexpr uint32_t kTetsPerItem = 4;  // a batch of the corotational pass
constexpr uint32_t kNodesPerItem = 4 * kTetsPerItem;

// Items of tets_per_item consecutive tets of `tets` (4 node indices each): their nodes and
// centres, and the tile length their pass uses.
struct Items {
  uint32_t nodes_per_item = kNodesPerItem, items_per_tile = ElementTiles::kItemsPerTile;
  std::vector<uint32_t> nodes;
  std::vector<double> centres;
  Items(const std::vector<uint32_t>& tets, const std::vector<double>& positions,
        uint32_t tets_per_item = kTetsPerItem, uint32_t tile_length = ElementTiles::kItemsPerTile)
      : nodes_per_item(4 * tets_per_item), items_per_tile(tile_length) {
    const size_t items = tets.size() / nodes_per_item;
    nodes.assign(tets.begin(), tets.begin() + static_cast<std::ptrdiff_t>(items * nodes_per_item));
    centres.assign(3 * items, 0.0);
    for (size_t i = 0; i < items; ++i)
      for (size_t k = 0; k < nodes_per_item; ++k)
        for (size_t c = 0; c < 3; ++c)
          centres[3 * i + c] += positions[3 * size_t{nodes[nodes_per_item * i + k]} + c] /
                                static_cast<double>(nodes_per_item);
  }
  size_t count() const { return centres.size() / 3; }
  // The same items in a random order: tiles of consecutive ones would clash everywhere.
  Items shuffled(unsigned seed) const {
    std::vector<uint32_t> order(count());
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), std::mt19937(seed));
    Items out = *this;
    for (size_t i = 0; i < order.size(); ++i) {
      std::copy_n(&nodes[nodes_per_item * order[i]], nodes_per_item,
                  &out.nodes[nodes_per_item * i]);
      std::copy_n(&centres[3 * order[i]], 3, &out.centres[3 * i]);
    }
    return out;
  }
};

ElementTiles tile(const Items& items, uint32_t node_count) {
  return ElementTiles(items.nodes, items.nodes_per_item, items.centres, node_count,
                      items.items_per_tile);
}

// Every invariant the threaded pass relies on.
void expect_valid_schedule(const ElementTiles& tiles, const Items& items, uint32_t node_count) {
  ASSERT_FALSE(tiles.empty());
  std::vector<int> item_seen(items.count(), 0), tile_seen;
  for (uint32_t c = 0; c < tiles.colours(); ++c) {
    std::vector<int> node_owner(node_count, -1);
    for (uint32_t t : tiles.tiles_of(c)) {
      if (t >= tile_seen.size()) tile_seen.resize(t + 1, 0);
      ++tile_seen[t];
      const auto tile_items = tiles.items_of(t);
      EXPECT_LE(tile_items.size(), items.items_per_tile);
      EXPECT_TRUE(std::is_sorted(tile_items.begin(), tile_items.end())) << "tile " << t;
      for (uint32_t i : tile_items) {
        ++item_seen[i];
        for (size_t k = 0; k < items.nodes_per_item; ++k) {
          int& owner = node_owner[items.nodes[items.nodes_per_item * i + k]];
          ASSERT_TRUE(owner == -1 || owner == static_cast<int>(t))
              << "tiles " << owner << " and " << t << " of colour " << c << " share a node";
          owner = static_cast<int>(t);
        }
      }
    }
  }
  EXPECT_TRUE(std::all_of(item_seen.begin(), item_seen.end(), [](int n) { return n == 1; }));
  EXPECT_TRUE(std::all_of(tile_seen.begin(), tile_seen.end(), [](int n) { return n == 1; }));
  EXPECT_EQ(tile_seen.size(), (items.count() + items.items_per_tile - 1) / items.items_per_tile);
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

TEST(ElementTiles, ItemsInASpatialOrderGetRunsOfConsecutiveItems) {
  const TestMesh mesh = box_tet_mesh({12, 6, 6}, {0.24, 0.06, 0.06}, 1000.0);
  const Items items(mesh.tets, mesh.positions);
  const ElementTiles tiles = tile(items, mesh.node_count());
  expect_valid_schedule(tiles, items, mesh.node_count());
  EXPECT_GE(tiles.largest_colour(), 4u) << "a colour this body's threads can share";
  for (uint32_t c = 0; c < tiles.colours(); ++c)
    for (uint32_t t : tiles.tiles_of(c)) {
      const auto run = tiles.items_of(t);
      EXPECT_EQ(run.back() - run.front() + 1, run.size()) << "tile " << t;
    }
}

TEST(ElementTiles, ItemsInARandomOrderGetCompactTiles) {
  const TestMesh mesh = box_tet_mesh({10, 10, 10}, {0.1, 0.1, 0.1}, 1000.0);
  const Items scattered = Items(mesh.tets, mesh.positions).shuffled(7);
  const ElementTiles tiles = tile(scattered, mesh.node_count());
  expect_valid_schedule(tiles, scattered, mesh.node_count());
  // 16 items of 4 tets are about 11 of the 1 cm cells: a compact tile spans a few cells (a cube
  // of 11 cells has a 3.8 cm diagonal), where 16 items taken at random span the 17 cm body.
  EXPECT_LT(mean_tile_diagonal(tiles, scattered), 0.06);
  EXPECT_GE(tiles.largest_colour(), 4u) << "a colour the threads can share";
}

TEST(ElementTiles, SingleTetsInARandomOrderGetCompactTilesOf64) {
  // The hyperelastic pass: items of one tet, 64 a tile, in a mesher's order (here shuffled).
  const TestMesh mesh = box_tet_mesh({10, 10, 10}, {0.1, 0.1, 0.1}, 1000.0);
  const Items in_order(mesh.tets, mesh.positions, 1, 64);
  const Items scattered = in_order.shuffled(11);
  for (const Items* items : {&in_order, &scattered}) {
    const ElementTiles tiles = tile(*items, mesh.node_count());
    expect_valid_schedule(tiles, *items, mesh.node_count());
    EXPECT_GE(tiles.largest_colour(), 4u) << "a colour the threads can share";
  }
  // 64 tets are about 11 of the 1 cm cells, as 16 batches of 4 are (above).
  EXPECT_LT(mean_tile_diagonal(tile(scattered, mesh.node_count()), scattered), 0.06);
  EXPECT_TRUE(ElementTiles(in_order.nodes, 4, in_order.centres, mesh.node_count(), 0).empty())
      << "tiles of no items";
}

TEST(ElementTiles, SmallBodiesGetAValidSchedule) {
  for (const uint32_t cells : {1u, 2u, 3u, 5u}) {  // 1 to 187 items
    const TestMesh mesh = box_tet_mesh({cells, cells, cells}, {0.1, 0.1, 0.1}, 1000.0);
    const Items items(mesh.tets, mesh.positions);
    expect_valid_schedule(tile(items, mesh.node_count()), items, mesh.node_count());
    expect_valid_schedule(tile(items.shuffled(3), mesh.node_count()), items.shuffled(3),
                          mesh.node_count());
  }
}

// Centres the Morton grid cannot place (never from a mesh the models accept: they refuse
// non-finite positions) still give a valid schedule, on the Morton path (shuffled, 250 items).
TEST(ElementTiles, NonFiniteCentresStillGetAValidSchedule) {
  const TestMesh mesh = box_tet_mesh({10, 10, 10}, {0.1, 0.1, 0.1}, 1000.0);
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Items items = Items(mesh.tets, mesh.positions).shuffled(5);
    items.centres[3 * 17 + 1] = bad;
    const ElementTiles tiles = tile(items, mesh.node_count());
    expect_valid_schedule(tiles, items, mesh.node_count());
  }
}

TEST(ElementTiles, AnInputThatIsNotAListOfItemsGivesNoSchedule) {
  const TestMesh mesh = box_tet_mesh({3, 3, 3}, {0.1, 0.1, 0.1}, 1000.0);
  Items items(mesh.tets, mesh.positions);
  EXPECT_TRUE(ElementTiles({}, kNodesPerItem, {}, 10).empty());
  EXPECT_TRUE(ElementTiles(std::span(items.nodes).first(items.nodes.size() - 1), kNodesPerItem,
                           items.centres, mesh.node_count())
                  .empty())
      << "a node list shorter than the items";
  items.nodes[5] = mesh.node_count();
  EXPECT_TRUE(tile(items, mesh.node_count()).empty()) << "a node past the body's";
  EXPECT_EQ(ElementTiles().colours(), 0u);
}

}  // namespace
}  // namespace tacta::models::sparse
