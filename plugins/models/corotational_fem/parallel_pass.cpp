// step() on the engine's workers. The batched element pass: batches scatter into the forces
// and the matrix blocks of their nodes, so batches that share a node must not run at once: they
// are cut into tiles of consecutive batches, the tiles coloured (sparse::ElementTiles), and each
// colour is one parallel_for over its tiles. The row passes around the solve (sparse::RowTeam):
// each chunk of nodes writes only its own rows. With one worker (or no host, or inside a part of
// a split job: a body stepped in a group) everything runs in order, as it always has: results
// then match earlier builds bit for bit. With two or more, one result on any thread count (the
// tiles, their colours and the row chunks do not depend on it), equal to the serial one to
// rounding.
#include <algorithm>
#include <span>

#include "corotational_fem.hpp"

namespace tacta::models::corotational {

namespace {
// Below this many batches the pass runs in order on the caller: handing a few tiles to the
// workers costs more (~1 us while they spin between jobs, ~10-50 us to wake a parked one).
constexpr uint32_t kMinParallelBatches = 32;

}  // namespace

void CorotationalFem::tile_batches() {
  const tacta_host_services* host = options_.host;
  if (host == nullptr || host->worker_count < 2 || host->parallel_for == nullptr ||
      batches_.size() < kMinParallelBatches)
    return;
  std::vector<uint32_t> nodes(batches_.size() * 4 * kBatchLanes);
  std::vector<double> centres(3 * batches_.size(), 0.0);
  for (size_t b = 0; b < batches_.size(); ++b)
    for (int a = 0; a < 4; ++a)
      for (int l = 0; l < kBatchLanes; ++l) {
        const uint32_t node = batches_[b].nodes[a][l];
        nodes[(4 * b + a) * kBatchLanes + l] = node;
        for (size_t c = 0; c < 3; ++c)
          centres[3 * b + c] += rest_[3 * size_t{node} + c] / (4.0 * kBatchLanes);
      }
  tiles_ = sparse::ElementTiles(nodes, 4 * kBatchLanes, centres, node_count_);
  if (!tiles_.shares_work()) {  // a small body, or scattered tiles: little to share
    tiles_ = sparse::ElementTiles();
    return;
  }
  tallies_.assign(host->worker_count, WorkerTally{});
  tile_split_ = sparse::OwnedSplit(host);
}

uint32_t CorotationalFem::batched_pass(const double* positions, double scale) noexcept {
  uint32_t result = TACTA_STEP_OK;
  // In order where the workers cannot spread (a body stepped in a group runs inside one part of
  // the engine's job): the serial pass, its bits and its locality (tile order costs more alone).
  if (tiles_.empty() || tacta_host_workers_here(options_.host) < 2) {
    for (uint32_t b = 0; b < batches_.size(); ++b)
      result |= step_batch(b, positions, scale, polar_iterations_);
    return result;
  }
  for (WorkerTally& t : tallies_) t = WorkerTally{};
  for (uint32_t c = 0; c < tiles_.colours(); ++c) {
    const std::span<const uint32_t> tiles = tiles_.tiles_of(c);
    const auto run = [&](uint32_t begin, uint32_t end, uint32_t worker) {
      WorkerTally& tally = tallies_[worker];
      for (uint32_t t = begin; t < end; ++t)
        for (uint32_t b : tiles_.items_of(tiles[t]))
          tally.bits |= step_batch(b, positions, scale, tally.polar_iterations);
    };
    tiles_.run_colour(c, tile_split_, run);
  }
  for (const WorkerTally& t : tallies_) {
    result |= t.bits;
    polar_iterations_ += t.polar_iterations;
  }
  return result;
}

double CorotationalFem::finish_system_threaded(const tacta_body_state& state, double h) noexcept {
  // The matrix holds h (beta + h) K now: its product with v is the rhs's stiffness and damping
  // term. Every row reads blocks of other rows, so the mass and the held nodes go in after.
  rows_.run([&](uint32_t, uint32_t begin, uint32_t end) {
    matrix_.multiply_rows(state.velocities, stiffness_velocity_.data(), begin, end);
  });
  const bool extrapolate = solver_->iterative();
  rows_.run([&](uint32_t chunk, uint32_t begin, uint32_t end) {
    matrix_.finish_rows(begin, end, masses_, 1.0 + h * alpha_, fixed_);
    rows_.sums(chunk).s[0] = rhs_rows(state, h, begin, end);
    if (extrapolate) extrapolate_guess(3 * size_t{begin}, 3 * size_t{end});
  });
  return rows_.total(0);
}

void CorotationalFem::advance_threaded(tacta_body_state& state, double h) noexcept {
  const bool score = solver_->iterative() && options_.adaptive_guess;
  rows_.run([&](uint32_t chunk, uint32_t begin, uint32_t end) {
    if (score) {  // the guesses' misses, summed per chunk and then in chunk order
      sparse::ChunkSums& sums = rows_.sums(chunk);
      sums.s[0] = sums.s[1] = 0.0;
      score_guess(3 * size_t{begin}, 3 * size_t{end}, sums.s[0], sums.s[1]);
    }
    for (uint32_t i = begin; i < end; ++i) {
      const bool held = !fixed_.empty() && fixed_[i];
      for (size_t k = 3 * size_t{i}; k < 3 * size_t{i} + 3; ++k) {
        double& v = state.velocities[k];
        v = held ? 0.0 : v + delta_v_[k];
        state.positions[k] += h * v;
      }
    }
  });
  if (score) quadratic_guess_ = rows_.total(1) < rows_.total(0);
}

}  // namespace tacta::models::corotational
