// The threaded paths of the solvers and models: the host's parallel_for (model_api.h) over a
// fixed split of a body's nodes (rows) into chunks. The split depends on the row count only,
// never on the thread count, and every sum is kept per chunk and added up in chunk order, so a
// threaded solve gives the same bits run after run and on any number of threads (2, 4, 16):
// which worker ran a chunk never matters. Equal to the serial code to rounding (sums in another
// order). A few parallel_for calls per CG iteration: the job pool's workers spin between them.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models::sparse {

// Partial sums of one chunk, one cache line each (no false sharing between workers).
struct alignas(64) ChunkSums {
  double s[4];
};

// parallel_for over [0, count) in which worker w first runs its own share [w count / T,
// (w + 1) count / T), `step` indices at a time, then helps with the others' shares (a worker
// that starts late, or is preempted, loses what it has not begun to the others). The same
// indices run on the same thread job after job, so their rows stay in that core's cache: with
// the indices handed out first come, first served, every pass moved most of its vectors from
// one core's L2 to the other's (the CG's update cost 2.4 times its serial time).
class OwnedSplit {
 public:
  OwnedSplit() = default;
  explicit OwnedSplit(const tacta_host_services* host)
      : host_(host), shares_(host != nullptr ? host->worker_count : 0) {}

  // f(begin, end, worker) over [0, count), returns when all have run.
  template <class F>
  void run(uint32_t count, uint32_t step, F&& f) const {
    const auto workers = static_cast<uint32_t>(shares_.size());
    for (uint32_t w = 0; w < workers; ++w) {  // published to the workers by the job's start
      shares_[w].next.store(static_cast<uint32_t>(uint64_t{count} * w / workers),
                            std::memory_order_relaxed);
      shares_[w].end = static_cast<uint32_t>(uint64_t{count} * (w + 1) / workers);
    }
    struct Call {
      const OwnedSplit* split;
      std::remove_reference_t<F>* f;
      uint32_t step;
    } call{this, &f, std::max<uint32_t>(step, 1)};
    const auto body = [](void* user, uint32_t, uint32_t, uint32_t worker) {
      const Call& c = *static_cast<const Call*>(user);
      const auto n = static_cast<uint32_t>(c.split->shares_.size());
      for (uint32_t k = 0; k < n; ++k) {
        Share& share = c.split->shares_[(worker + k) % n];
        for (;;) {
          const uint32_t begin = share.next.fetch_add(c.step, std::memory_order_relaxed);
          if (begin >= share.end) break;
          (*c.f)(begin, std::min(begin + c.step, share.end), worker);
        }
      }
    };
    // One index per worker: each that takes one runs its share, then what is left of others'.
    host_->parallel_for(host_->jobs, workers, 1, body, &call);
  }

 private:
  struct alignas(64) Share {
    std::atomic<uint32_t> next{0};
    uint32_t end = 0;
  };
  const tacta_host_services* host_ = nullptr;
  mutable std::vector<Share> shares_;  // one per worker, sized once
};

class RowTeam {
 public:
  static constexpr uint32_t kRowsPerChunk = 96;  // a chunk is ~10-30 us of a product's work
  static constexpr uint32_t kMaxChunks = 64;     // enough to balance 16 threads

  RowTeam() = default;
  // May thread when host offers parallel_for on two or more workers and rows >= min_rows;
  // otherwise threaded() is always false and the caller keeps its serial code.
  RowTeam(const tacta_host_services* host, uint32_t rows, uint32_t min_rows) : sums_(kMaxChunks) {
    if (host == nullptr || host->worker_count < 2 || host->parallel_for == nullptr ||
        rows < min_rows)
      return;
    host_ = host;
    split_ = OwnedSplit(host);
    const uint32_t chunks =
        std::clamp<uint32_t>((rows + kRowsPerChunk - 1) / kRowsPerChunk, 1, kMaxChunks);
    bounds_.resize(chunks + 1);
    for (uint32_t c = 0; c <= chunks; ++c)
      bounds_[c] = static_cast<uint32_t>(uint64_t{rows} * c / chunks);
  }

  // The threaded code is for this call: two or more workers are offered and can spread from
  // here. Inside one job of a split parallel_for (a body stepped in a group) the serial code
  // runs instead: the threaded code run serially reads each block twice and is slower. Stable
  // within a step, and fixed by the scene's structure, not by timing (workers_here).
  bool threaded() const { return host_ != nullptr && tacta_host_workers_here(host_) > 1; }
  // Whether threaded() can ever be true (buffers the threaded code needs are sized for it).
  bool may_thread() const { return host_ != nullptr; }
  uint32_t chunks() const {
    return bounds_.empty() ? 0 : static_cast<uint32_t>(bounds_.size() - 1);
  }

  // f(chunk, first_row, end_row) for every chunk, on the host's workers and the caller, each
  // worker its own run of chunks first (OwnedSplit); returns when every chunk has run. f writes
  // its sums to sums(chunk).
  template <class F>
  void run(F&& f) const {
    split_.run(chunks(), 1, [&](uint32_t begin, uint32_t end, uint32_t) {
      for (uint32_t k = begin; k < end; ++k) f(k, bounds_[k], bounds_[k + 1]);
    });
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
  OwnedSplit split_;
  std::vector<uint32_t> bounds_;
  mutable std::vector<ChunkSums> sums_;
};

}  // namespace tacta::models::sparse
