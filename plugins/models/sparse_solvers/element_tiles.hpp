// The schedule of a threaded element pass that scatters into its nodes' rows (forces, matrix
// blocks): the items (element batches, or elements) cut into tiles of consecutive items, and the
// tiles coloured so that no two tiles of a colour share a node. A colour's tiles run in parallel
// and a tile's items in order on one thread, so the blocks neighbouring items add into stay in
// that core's cache and the items' own data streams. (Colouring single items instead spreads every
// colour over the whole body: each colour re-reads the matrix.) Where that leaves fewer than
// kMinTilesPerColour tiles per colour on average (the items' order is not spatial, as a mesher's
// random order), tiles follow the Morton order of the items' centres if that needs fewer colours.
// Fixed by the mesh alone, never by the thread count, so a threaded pass gives the same bits on
// any number of threads.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "row_team.hpp"

namespace tacta::models::sparse {

class ElementTiles {
 public:
  // Items per tile by default (batches of 4 tets: 64 tets a tile): a tile is a few microseconds
  // of work, and a colour of a 10k-tet body has enough tiles to balance a few threads.
  static constexpr uint32_t kItemsPerTile = 16;
  // Tiles of consecutive items are kept while the colours average at least this many tiles.
  static constexpr uint32_t kMinTilesPerColour = 4;

  ElementTiles() = default;
  // Item i touches nodes[i * nodes_per_item, (i + 1) * nodes_per_item) (each < node_count) and
  // sits at centres[3 i, 3 i + 3) (m); otherwise (or with no items, or items_per_tile 0) the
  // schedule is empty. Tiles are runs of items_per_tile items (in index order, or in the Morton
  // order of their centres); colours are given greedily, tile by tile.
  ElementTiles(std::span<const uint32_t> nodes, uint32_t nodes_per_item,
               std::span<const double> centres, uint32_t node_count,
               uint32_t items_per_tile = kItemsPerTile);

  bool empty() const { return items_.empty(); }
  uint32_t colours() const {
    return colour_start_.empty() ? 0 : static_cast<uint32_t>(colour_start_.size() - 1);
  }
  // The most tiles any colour has: below 2, no colour can use a second thread.
  size_t largest_colour() const;
  // Whether the colours average at least two tiles: below that most colours run one tile, so a
  // threaded pass is a string of parallel_for calls with one thread busy (a 2,193-tet liver in a
  // mesher's order, as batches of 4 tets: 35 tiles in 34 colours, slower than the serial pass).
  bool shares_work() const { return !tiles_.empty() && tiles_.size() >= 2 * size_t{colours()}; }
  // The tiles of colour c, in order.
  std::span<const uint32_t> tiles_of(uint32_t colour) const {
    return std::span(tiles_).subspan(colour_start_[colour],
                                     colour_start_[colour + 1] - colour_start_[colour]);
  }
  uint32_t tiles() const { return static_cast<uint32_t>(tiles_.size()); }
  // run(begin, end, worker) over colour c's tiles, [begin, end) indexing tiles_of(c): on split's
  // workers, each its own share first (the same tiles step after step), or on the caller
  // (worker 0) when the colour has one tile.
  template <class Run>
  void run_colour(uint32_t colour, const OwnedSplit& split, Run&& run) const {
    const auto count = static_cast<uint32_t>(tiles_of(colour).size());
    if (count < 2)
      run(0u, count, 0u);
    else
      split.run(count, 1, run);
  }
  // The items of tile t (items_per_tile of them, fewer in the last), in index order.
  std::span<const uint32_t> items_of(uint32_t tile) const {
    const size_t first = size_t{tile} * items_per_tile_;
    return std::span(items_).subspan(first,
                                     std::min<size_t>(items_per_tile_, items_.size() - first));
  }

 private:
  // Cuts items_ (in the order given) into tiles and colours them.
  void colour_tiles(std::span<const uint32_t> nodes, uint32_t nodes_per_item, uint32_t node_count);

  uint32_t items_per_tile_ = kItemsPerTile;
  std::vector<uint32_t> items_;                 // in tile order, items_per_tile_ a tile
  std::vector<uint32_t> tiles_, colour_start_;  // colour c: tiles_[colour_start_[c], [c + 1])
};

}  // namespace tacta::models::sparse
