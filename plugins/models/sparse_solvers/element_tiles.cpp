#include "element_tiles.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <utility>

namespace tacta::models::sparse {

namespace {

// The 10 bits of v spread to every third bit (bit k to bit 3k).
uint32_t spread_bits(uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

// Morton codes of the centres on a grid of 1024 cells along the bounding box's longest side
// (cubic cells: a run of codes is a compact piece of space, whatever the body's proportions).
std::vector<uint32_t> morton_codes(std::span<const double> centres, size_t count) {
  std::array<double, 3> low, high;
  low.fill(std::numeric_limits<double>::max());
  high.fill(std::numeric_limits<double>::lowest());
  for (size_t i = 0; i < count; ++i)
    for (size_t c = 0; c < 3; ++c) {
      low[c] = std::min(low[c], centres[3 * i + c]);
      high[c] = std::max(high[c], centres[3 * i + c]);
    }
  double extent = 0.0;
  for (size_t c = 0; c < 3; ++c) extent = std::max(extent, high[c] - low[c]);
  const double cells_per_metre = extent > 0.0 ? 1023.0 / extent : 0.0;
  std::vector<uint32_t> codes(count);
  for (size_t i = 0; i < count; ++i) {
    uint32_t code = 0;
    for (size_t c = 0; c < 3; ++c) {
      const double cell = (centres[3 * i + c] - low[c]) * cells_per_metre;
      // Non-finite centres (never from a mesh the models accept) go to cell 0; an infinite one
      // makes the extent infinite and every code 0 (the order is then kept).
      const uint32_t index = cell >= 0.0 ? static_cast<uint32_t>(std::min(cell, 1023.0)) : 0u;
      code |= spread_bits(index) << c;
    }
    codes[i] = code;
  }
  return codes;
}

}  // namespace

ElementTiles::ElementTiles(std::span<const uint32_t> nodes, uint32_t nodes_per_item,
                           std::span<const double> centres, uint32_t node_count) {
  const size_t count = centres.size() / 3;
  if (count == 0 || nodes_per_item == 0 || nodes.size() < count * nodes_per_item ||
      count > std::numeric_limits<uint32_t>::max() / kItemsPerTile)
    return;  // nothing to schedule, or not a list of items: no schedule (the pass stays serial)
  for (size_t k = 0; k < count * nodes_per_item; ++k)
    if (nodes[k] >= node_count) return;
  items_.resize(count);
  std::iota(items_.begin(), items_.end(), 0u);
  colour_tiles(nodes, nodes_per_item, node_count);
  if (count <= kMinTilesPerColour * kItemsPerTile ||
      tiles_.size() >= kMinTilesPerColour * colours())
    return;
  // Too few tiles per colour: perhaps the items' order is not spatial (a mesher's random order),
  // so tiles of consecutive items are scattered and clash. Tiles in Morton order, where they
  // need fewer colours.
  ElementTiles in_order = *this;
  const std::vector<uint32_t> codes = morton_codes(centres, count);
  std::stable_sort(items_.begin(), items_.end(),
                   [&](uint32_t a, uint32_t b) { return codes[a] < codes[b]; });
  colour_tiles(nodes, nodes_per_item, node_count);
  if (colours() >= in_order.colours()) *this = std::move(in_order);
}

size_t ElementTiles::largest_colour() const {
  size_t largest = 0;
  for (uint32_t c = 0; c < colours(); ++c) largest = std::max(largest, tiles_of(c).size());
  return largest;
}

void ElementTiles::colour_tiles(std::span<const uint32_t> nodes, uint32_t nodes_per_item,
                                uint32_t node_count) {
  const size_t count = items_.size();
  const auto tiles = static_cast<uint32_t>((count + kItemsPerTile - 1) / kItemsPerTile);
  tile_start_.clear();
  for (uint32_t t = 0; t <= tiles; ++t)
    tile_start_.push_back(
        static_cast<uint32_t>(std::min<size_t>(count, size_t{t} * kItemsPerTile)));
  // Within a tile, items go in index order: their rest data and history then stream from memory.
  for (uint32_t t = 0; t < tiles; ++t)
    std::sort(items_.begin() + tile_start_[t], items_.begin() + tile_start_[t + 1]);
  // The tiles touching each node (CSR), each listed once per node.
  std::vector<uint32_t> node_start(node_count + 1, 0), last_tile(node_count, tiles);
  const auto for_each_node = [&](uint32_t t, auto&& f) {
    for (uint32_t k = tile_start_[t]; k < tile_start_[t + 1]; ++k)
      for (uint32_t m = 0; m < nodes_per_item; ++m)
        f(nodes[size_t{items_[k]} * nodes_per_item + m]);
  };
  for (uint32_t t = 0; t < tiles; ++t)
    for_each_node(t, [&](uint32_t n) {
      if (last_tile[n] != t) ++node_start[n + 1];
      last_tile[n] = t;
    });
  std::partial_sum(node_start.begin(), node_start.end(), node_start.begin());
  std::vector<uint32_t> node_tiles(node_start.back()),
      fill(node_start.begin(), node_start.end() - 1);
  std::fill(last_tile.begin(), last_tile.end(), tiles);
  for (uint32_t t = 0; t < tiles; ++t)
    for_each_node(t, [&](uint32_t n) {
      if (last_tile[n] != t) node_tiles[fill[n]++] = t;
      last_tile[n] = t;
    });

  // Greedy: each tile takes the lowest colour no earlier tile it shares a node with has.
  std::vector<uint32_t> colour(tiles, 0), taken_by;  // taken_by[c]: last tile that saw c taken
  uint32_t colour_count = 0;
  for (uint32_t t = 0; t < tiles; ++t) {
    for_each_node(t, [&](uint32_t n) {
      for (uint32_t k = node_start[n]; k < node_start[n + 1] && node_tiles[k] < t; ++k)
        taken_by[colour[node_tiles[k]]] = t;
    });
    uint32_t c = 0;
    while (c < colour_count && taken_by[c] == t) ++c;
    if (c == colour_count) {
      ++colour_count;
      taken_by.push_back(tiles);
    }
    colour[t] = c;
  }
  colour_start_.assign(colour_count + 1, 0);
  for (uint32_t t = 0; t < tiles; ++t) ++colour_start_[colour[t] + 1];
  std::partial_sum(colour_start_.begin(), colour_start_.end(), colour_start_.begin());
  tiles_.resize(tiles);
  std::vector<uint32_t> next(colour_start_.begin(), colour_start_.end() - 1);
  for (uint32_t t = 0; t < tiles; ++t) tiles_[next[colour[t]]++] = t;
}

}  // namespace tacta::models::sparse
