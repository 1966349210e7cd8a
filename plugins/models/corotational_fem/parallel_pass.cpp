// step() on the engine's workers. The batched element pass: batches scatter into the forces
// and the matrix blocks of their nodes, so batches that share a node must not run at once: they
// are coloured greedily, and each colour is one parallel_for. The row passes around the solve
// (sparse::RowTeam): each chunk of nodes writes only its own rows. With one worker (or no host)
// everything runs in order, as it always has: results then match earlier builds bit for bit.
// With two or more, one result on any thread count (the colouring and the row chunks do not
// depend on it), equal to the serial one to rounding.
#include <algorithm>

#include "corotational_fem.hpp"

namespace tacta::models::corotational {

namespace {
// A colour with fewer batches than this runs serially: handing it to the workers costs more
// (~1 us while they spin between jobs, ~10-50 us to wake a parked one).
constexpr uint32_t kMinParallelBatches = 16;
// Batches per chunk a worker takes: at least kGrain, at most about four chunks per thread (a
// chunk taken is an atomic on a shared cache line).
constexpr uint32_t kGrain = 8;

}  // namespace

void CorotationalFem::colour_batches() {
  colour_batches_.clear();
  colour_start_.clear();
  const tacta_host_services* host = options_.host;
  if (host == nullptr || host->worker_count < 2 || host->parallel_for == nullptr ||
      batches_.size() < 2 * kMinParallelBatches)
    return;
  // colour_of_node[c][n]: node n already written by a batch of colour c.
  std::vector<std::vector<uint8_t>> used;
  std::vector<std::vector<uint32_t>> by_colour;
  for (uint32_t b = 0; b < batches_.size(); ++b) {
    size_t c = 0;
    const auto clashes = [&](size_t colour) {
      for (int l = 0; l < kBatchLanes; ++l)
        for (uint32_t n : elements_[kBatchLanes * b + l].nodes)
          if (used[colour][n]) return true;
      return false;
    };
    while (c < used.size() && clashes(c)) ++c;
    if (c == used.size()) {
      used.emplace_back(node_count_, 0);
      by_colour.emplace_back();
    }
    for (int l = 0; l < kBatchLanes; ++l)
      for (uint32_t n : elements_[kBatchLanes * b + l].nodes) used[c][n] = 1;
    by_colour[c].push_back(b);
  }
  for (const std::vector<uint32_t>& batches : by_colour) {
    colour_start_.push_back(static_cast<uint32_t>(colour_batches_.size()));
    colour_batches_.insert(colour_batches_.end(), batches.begin(), batches.end());
  }
  colour_start_.push_back(static_cast<uint32_t>(colour_batches_.size()));
  tallies_.assign(host->worker_count, WorkerTally{});
  colour_split_ = sparse::OwnedSplit(host);
}

uint32_t CorotationalFem::batched_pass(const double* positions, double scale) noexcept {
  uint32_t result = TACTA_STEP_OK;
  if (colour_start_.empty()) {
    for (uint32_t b = 0; b < batches_.size(); ++b)
      result |= step_batch(b, positions, scale, polar_iterations_);
    return result;
  }
  for (WorkerTally& t : tallies_) t = WorkerTally{};
  const tacta_host_services& host = *options_.host;
  for (size_t c = 0; c + 1 < colour_start_.size(); ++c) {
    const uint32_t count = colour_start_[c + 1] - colour_start_[c];
    const uint32_t* batches = colour_batches_.data() + colour_start_[c];
    const auto run = [&](uint32_t begin, uint32_t end, uint32_t worker) {
      WorkerTally& tally = tallies_[worker];
      for (uint32_t i = begin; i < end; ++i)
        tally.bits |= step_batch(batches[i], positions, scale, tally.polar_iterations);
    };
    if (count < kMinParallelBatches)
      run(0, count, 0);
    else  // each worker its own share of the colour first: the same batches step after step
      colour_split_.run(count, std::max(kGrain, count / (4 * host.worker_count)), run);
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
