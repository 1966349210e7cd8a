// step()'s batched element pass on the engine's workers. Batches scatter into the forces and
// the matrix blocks of their nodes, so batches that share a node must not run at once: they are
// coloured greedily, and each colour is one parallel_for. With one worker (or no host) the pass
// runs in batch order, as it always has: results then match earlier builds bit for bit.
#include <algorithm>

#include "corotational_fem.hpp"

namespace tacta::models::corotational {

namespace {
// A colour with fewer batches than this runs serially: waking workers costs more (~10 us).
constexpr uint32_t kMinParallelBatches = 64;
constexpr uint32_t kGrain = 16;  // batches per chunk a worker takes

struct PassJob {
  CorotationalFem* model;
  const uint32_t* batches;
  const double* positions;
  double scale;
};
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
    PassJob job{this, colour_batches_.data() + colour_start_[c], positions, scale};
    const auto body = [](void* user, uint32_t begin, uint32_t end, uint32_t worker) {
      const PassJob& j = *static_cast<const PassJob*>(user);
      WorkerTally& tally = j.model->tallies_[worker];
      for (uint32_t i = begin; i < end; ++i)
        tally.bits |=
            j.model->step_batch(j.batches[i], j.positions, j.scale, tally.polar_iterations);
    };
    if (count < kMinParallelBatches)
      body(&job, 0, count, 0);
    else
      host.parallel_for(host.jobs, count, kGrain, body, &job);
  }
  for (const WorkerTally& t : tallies_) {
    result |= t.bits;
    polar_iterations_ += t.polar_iterations;
  }
  return result;
}

}  // namespace tacta::models::corotational
