// Per-tick and per-frame records, kept in memory during the run in buffers reserved before it
// starts (push_back within capacity never allocates), and written to CSV after it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace tacta {

struct TraceRow {  // one per tick per device (trace.csv)
  double time_s;
  uint32_t device;
  double position[3];  // m, device
  double proxy[3];     // m
  double force[3];     // N, sent to the device
  uint32_t contact;    // 1 when the tool touches a body
  double tick_ms;      // duration of the previous tick
};

struct TrajectoryRow {  // one per recorded node per record interval (trajectory.csv)
  double time_s;
  uint32_t body, node;
  double x[3], v[3];
};

struct ProbeRow {  // one per probe per record interval (probes.csv)
  double time_s;
  uint32_t body, probe;
  double x[3];  // m
};

struct EnergyRow {  // one per body per frame (energy.csv)
  double time_s;
  uint32_t body;
  double kinetic_J, elastic_J, max_displacement_m;
};

template <class Row>
class Recorder {
 public:
  void reserve(size_t rows) { rows_.reserve(rows); }
  // Room for `more` rows past those kept (a persistent clock stepping on), `limit` rows in all
  // (a session that plays for hours keeps its first rows and counts the rest); allocates.
  void grow(size_t more, size_t limit) {
    rows_.reserve(std::min(rows_.size() + more, std::max(limit, rows_.capacity())));
  }
  // Drops the row (and counts it) once the reserved capacity is full: never allocates.
  void push(const Row& row) noexcept {
    if (rows_.size() < rows_.capacity())
      rows_.push_back(row);
    else
      ++dropped_;
  }
  const std::vector<Row>& rows() const noexcept { return rows_; }
  // A checkpoint's rows and drop count (allocates; the next run grows the room past them).
  void restore(std::vector<Row> rows, uint64_t dropped) {
    rows_ = std::move(rows);
    dropped_ = dropped;
  }
  uint64_t dropped() const noexcept { return dropped_; }

 private:
  std::vector<Row> rows_;
  uint64_t dropped_ = 0;
};

}  // namespace tacta
