// The threaded paths of the solvers and models: the host's parallel_for (model_api.h) over a
// fixed split of a body's nodes (rows) into chunks. The split depends on the row count only,
// never on the thread count, and every sum is kept per chunk and added up in chunk order, so a
// threaded solve gives the same bits run after run and on any number of threads (2, 4, 16):
// which worker ran a chunk never matters. Equal to the serial code to rounding (sums in another
// order). A few parallel_for calls per CG iteration: the job pool's workers spin between them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models::sparse {

// Partial sums of one chunk, one cache line each (no false sharing between workers).
struct alignas(64) ChunkSums {
  double s[4];
};

class RowTeam {
 public:
  static constexpr uint32_t kRowsPerChunk = 96;  // a chunk is ~10-30 us of a product's work
  static constexpr uint32_t kMaxChunks = 64;     // enough to balance 16 threads

  RowTeam() = default;
  // Threaded when host offers parallel_for on two or more workers and rows >= min_rows;
  // otherwise threaded() is false and the caller keeps its serial code.
  RowTeam(const tacta_host_services* host, uint32_t rows, uint32_t min_rows)
      : sums_(kMaxChunks) {
    if (host == nullptr || host->worker_count < 2 || host->parallel_for == nullptr ||
        rows < min_rows)
      return;
    host_ = host;
    const uint32_t chunks =
        std::clamp<uint32_t>((rows + kRowsPerChunk - 1) / kRowsPerChunk, 1, kMaxChunks);
    bounds_.resize(chunks + 1);
    for (uint32_t c = 0; c <= chunks; ++c)
      bounds_[c] = static_cast<uint32_t>(uint64_t{rows} * c / chunks);
  }

  bool threaded() const { return host_ != nullptr; }
  uint32_t chunks() const { return bounds_.empty() ? 0 : static_cast<uint32_t>(bounds_.size() - 1); }

  // f(chunk, first_row, end_row) for every chunk, on the host's workers and the caller;
  // returns when every chunk has run. f writes its sums to sums(chunk).
  template <class F>
  void run(F&& f) const {
    struct Call {
      const RowTeam* team;
      F* f;
    } call{this, &f};
    const auto body = [](void* user, uint32_t begin, uint32_t end, uint32_t /*worker*/) {
      const Call& c = *static_cast<const Call*>(user);
      for (uint32_t k = begin; k < end; ++k) (*c.f)(k, c.team->bounds_[k], c.team->bounds_[k + 1]);
    };
    // About four pickups per thread: each is an atomic on a shared line (~0.1 us between
    // cores). Which chunks a pickup holds never changes a result (sums stay per chunk).
    const uint32_t grain = std::max<uint32_t>(1, chunks() / (4 * host_->worker_count));
    host_->parallel_for(host_->jobs, chunks(), grain, body, &call);
  }
  ChunkSums& sums(uint32_t chunk) const { return sums_[chunk]; }
  // Sum number `which` of every chunk, in chunk order.
  double total(int which) const {
    double sum = 0.0;
    for (uint32_t c = 0; c < chunks(); ++c) sum += sums_[c].s[which];
    return sum;
  }

 private:
  const tacta_host_services* host_ = nullptr;
  std::vector<uint32_t> bounds_;
  mutable std::vector<ChunkSums> sums_;
};

}  // namespace tacta::models::sparse
