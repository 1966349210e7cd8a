#include "element_tiles.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <utility>

#include "tacta/models/greedy_colouring.hpp"

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
                           std::span<const double> centres, uint32_t node_count,
                           uint32_t items_per_tile)
    : items_per_tile_(items_per_tile) {
  const size_t count = centres.size() / 3;
  if (count == 0 || nodes_per_item == 0 || items_per_tile == 0 ||
      nodes.size() < count * nodes_per_item ||
      count > std::numeric_limits<uint32_t>::max() / nodes_per_item ||  // 32-bit node counts
      count > std::numeric_limits<uint32_t>::max() - items_per_tile)
    return;  // nothing to schedule, or not a list of items: no schedule (the pass stays serial)
  for (size_t k = 0; k < count * nodes_per_item; ++k)
    if (nodes[k] >= node_count) return;
  items_.resize(count);
  std::iota(items_.begin(), items_.end(), 0u);
  colour_tiles(nodes, nodes_per_item, node_count);
  if (count <= size_t{kMinTilesPerColour} * items_per_tile ||
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
  const auto tiles = static_cast<uint32_t>((count + items_per_tile_ - 1) / items_per_tile_);
  // Within a tile, items go in index order: their rest data and history then stream from memory.
  for (size_t first = 0; first < count; first += items_per_tile_)
    std::sort(
        items_.begin() + static_cast<std::ptrdiff_t>(first),
        items_.begin() + static_cast<std::ptrdiff_t>(std::min(count, first + items_per_tile_)));
  const auto for_each_node = [&](uint32_t t, auto&& f) {
    for (uint32_t item : items_of(t))
      for (uint32_t m = 0; m < nodes_per_item; ++m) f(nodes[size_t{item} * nodes_per_item + m]);
  };
  // The tiles touching each node (CSR), each listed once per node.
  std::vector<uint32_t> node_start(node_count + 1, 0), last_tile(node_count, tiles);
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
  // Tiles that share a node clash.
  ColourGroups groups = greedy_colouring(
      tiles,
      [&](uint32_t t, auto&& visit) {
        for_each_node(t, [&](uint32_t n) {
          for (uint32_t k = node_start[n]; k < node_start[n + 1]; ++k) visit(node_tiles[k]);
        });
      },
      [](uint32_t) { return false; });
  colour_start_ = std::move(groups.starts);
  tiles_ = std::move(groups.members);
}

}  // namespace tacta::models::sparse
