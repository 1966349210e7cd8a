// HyperelasticModel's element pass on the engine's workers. Elements scatter into the forces and
// the matrix blocks of their nodes, so elements that share a node must not run at once: they are
// cut into tiles of kElementsPerTile (sparse::ElementTiles: runs of the mesh's order, or of the
// Morton order of their centres where a mesher's order scatters runs; the tiles coloured so that
// no two tiles of a colour share a node), and each colour is one parallel_for over its tiles.
// The schedule and the order of every sum are fixed by the mesh, so the threaded pass gives the
// same bits on any thread count, equal to the serial pass (mesh order) to rounding. The passes
// over the system matrix run on fixed row chunks (sparse::RowTeam): each chunk writes only its
// own rows' blocks, with the serial code's bits, except measure_at's product with Kd (summed per
// chunk, then in chunk order). With nodal volumes (nodal_volume.hpp) the whole step is serial.
#include <algorithm>
#include <span>

#include "hyperelastic_model.hpp"

namespace tacta::models::hyperelastic {

namespace {
// Below this many elements the pass runs in order on the caller: handing a few tiles to the
// workers costs more (~1 us while they spin between jobs, ~10-50 us to wake a parked one).
constexpr uint32_t kMinParallelElements = 128;
}  // namespace

void HyperelasticModel::tile_elements(const double* rest_positions) {
  const tacta_host_services* host = options_.host;
  const auto elements = static_cast<uint32_t>(elements_.size());
  if (host == nullptr || host->worker_count < 2 || host->parallel_for == nullptr ||
      elements < kMinParallelElements)
    return;
  std::vector<uint32_t> nodes(4 * size_t{elements});
  std::vector<double> centres(3 * size_t{elements}, 0.0);
  for (uint32_t e = 0; e < elements; ++e)
    for (uint32_t a = 0; a < 4; ++a) {
      const uint32_t node = elements_[e].nodes[a];
      nodes[4 * size_t{e} + a] = node;
      for (size_t c = 0; c < 3; ++c)
        centres[3 * size_t{e} + c] += 0.25 * rest_positions[3 * size_t{node} + c];
    }
  tiles_ = sparse::ElementTiles(nodes, 4, centres, node_count_, kElementsPerTile);
  if (!tiles_.shares_work()) {  // a small body, or scattered tiles: little to share
    tiles_ = sparse::ElementTiles();
    return;
  }
  tile_energy_.assign(tiles_.tiles(), 0.0);
  tallies_.assign(host->worker_count, WorkerTally{});
  tile_split_ = sparse::OwnedSplit(host);
}

void HyperelasticModel::tiled_elements(const double* x, double* forces, double scale,
                                       PassTally& tally) noexcept {
  for (WorkerTally& t : tallies_) t = WorkerTally{tally.change, false};
  stop_pass_.store(false, std::memory_order_relaxed);
  for (uint32_t c = 0; c < tiles_.colours(); ++c) {
    const std::span<const uint32_t> tiles = tiles_.tiles_of(c);
    const auto run = [&](uint32_t begin, uint32_t end, uint32_t worker) {
      WorkerTally& mine = tallies_[worker];
      for (uint32_t t = begin; t < end; ++t) {
        if (stop_pass_.load(std::memory_order_relaxed)) return;
        PassTally part{0.0, mine.change, false};
        bool go_on = true;
        for (const uint32_t e : tiles_.items_of(tiles[t]))
          if (!(go_on = add_element(e, x, forces, scale, part))) break;
        tile_energy_[tiles[t]] = part.energy;
        mine.change = part.change;
        mine.inverted = mine.inverted || part.inverted;
        if (!go_on) stop_pass_.store(true, std::memory_order_relaxed);
      }
    };
    tiles_.run_colour(c, tile_split_, run);
    // Some element ruled the lagged system out: the caller discards this pass.
    if (stop_pass_.load(std::memory_order_relaxed)) break;
  }
  for (const WorkerTally& t : tallies_) {
    tally.change = std::max(tally.change, t.change);
    tally.inverted = tally.inverted || t.inverted;
  }
  // A stopped pass's energy is left partial, as the serial pass leaves it (nothing reads it).
  if (stop_pass_.load(std::memory_order_relaxed)) return;
  for (const double energy : tile_energy_) tally.energy += energy;
}

namespace {
// The values of rows [begin, end)'s blocks (contiguous: a row's blocks follow each other).
std::span<double> row_values(sparse::BlockSparseMatrix& matrix, uint32_t begin, uint32_t end) {
  const std::span<const uint32_t> starts = matrix.row_starts();
  return matrix.values().subspan(9 * size_t{starts[begin]},
                                 9 * size_t{starts[end] - starts[begin]});
}
}  // namespace

void HyperelasticModel::zero_system() noexcept {
  if (!rows_.threaded()) {
    matrix_.set_zero();
    return;
  }
  rows_.run([&](uint32_t, uint32_t begin, uint32_t end) { matrix_.zero_rows(begin, end); });
}

void HyperelasticModel::store_damping(double potential) noexcept {
  const auto copy = [&](uint32_t begin, uint32_t end) {
    const std::span<const double> from = row_values(matrix_, begin, end);
    const std::span<double> to = row_values(damping_, begin, end);  // the same pattern
    for (size_t k = 0; k < from.size(); ++k) to[k] = from[k] / potential;
  };
  if (rows_.threaded())
    rows_.run([&](uint32_t, uint32_t begin, uint32_t end) { copy(begin, end); });
  else
    copy(0, node_count_);
}

void HyperelasticModel::finish_system(const Objective& o) noexcept {
  const double mass_weight = o.inertia + o.mass_damping;
  const auto add_damping = [&](uint32_t begin, uint32_t end) {
    if (o.stiffness_damping == 0.0) return;
    const std::span<const double> kd = row_values(damping_, begin, end);
    const std::span<double> a = row_values(matrix_, begin, end);
    for (size_t k = 0; k < a.size(); ++k) a[k] += o.stiffness_damping * kd[k];
  };
  if (rows_.threaded() && mass_weight != 0.0) {
    // finish_rows: add_to_diagonal then apply_fixed on the chunk's rows, the same bits.
    rows_.run([&](uint32_t, uint32_t begin, uint32_t end) {
      add_damping(begin, end);
      matrix_.finish_rows(begin, end, masses_, mass_weight, fixed_);
    });
    return;
  }
  add_damping(0, node_count_);
  if (mass_weight != 0.0) matrix_.add_to_diagonal(masses_, mass_weight);
  matrix_.apply_fixed(fixed_);
}

double HyperelasticModel::damping_product() noexcept {
  if (!rows_.threaded()) return damping_.multiply(scratch_.data(), product_.data());
  rows_.run([&](uint32_t chunk, uint32_t begin, uint32_t end) {
    rows_.sums(chunk).s[0] = damping_.multiply_rows(scratch_.data(), product_.data(), begin, end);
  });
  return rows_.total(0);
}

}  // namespace tacta::models::hyperelastic
