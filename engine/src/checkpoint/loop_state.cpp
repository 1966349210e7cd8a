// The clock's, the haptic loop's and the haptic channels' part of a checkpoint: what the next
// ticks read or the report adds to (records so far, status counters, the record cadence, the
// proxies and couplings). Tick durations are wall time, not state: a resumed run times its own.
#include <type_traits>

#include "checkpoint/checkpoint_format.hpp"
#include "haptic_interaction/haptic_interaction.hpp"
#include "systems/haptic_loop.hpp"
#include "timing/clock_session.hpp"

namespace tacta {

namespace {

enum : uint32_t {
  kClockSection = 0x434c4f4b,
  kLoopSection = 0x4c4f4f50,
  kHapticSection = 0x48415054
};

// Rows a record may bring back: what a single run keeps at most.
constexpr uint64_t kMaxRows = 1ull << 32;

template <class Row>
void save_rows(CheckpointWriter& out, const Recorder<Row>& r) {
  out.array(r.rows());
  out.pod(r.dropped());
}

template <class Row>
void load_rows(CheckpointReader& in, Recorder<Row>& r, const char* what) {
  std::vector<Row> rows = in.array<Row>(what, kMaxRows);
  r.restore(std::move(rows), in.pod<uint64_t>(what));
}

}  // namespace

void HapticLoop::save_state(CheckpointWriter& out) const {
  const size_t at = out.begin_section(kLoopSection);
  save_rows(out, trace_);
  save_rows(out, trajectory_);
  save_rows(out, probes_);
  save_rows(out, energy_);
  save_rows(out, faults_);
  out.pod(next_record_s_);
  out.pod(tick_index_);
  out.pod(tick_time_);
  out.array(body_status_);
  out.array(device_status_);
  out.pod(collision_status_);
  out.end_section(at);
}

void HapticLoop::load_state(CheckpointReader& outer) {
  CheckpointReader in = outer.section(kLoopSection, "records");
  load_rows(in, trace_, "trace rows");
  load_rows(in, trajectory_, "trajectory rows");
  load_rows(in, probes_, "probe rows");
  load_rows(in, energy_, "energy rows");
  load_rows(in, faults_, "fault records");
  in.pod_into(next_record_s_, "the next record time");
  in.pod_into(tick_index_, "the tick index");
  in.pod_into(tick_time_, "the tick time");
  in.array_exact(body_status_, "body status counters");
  in.array_exact(device_status_, "device status counters");
  in.pod_into(collision_status_, "the collision status counter");
  in.expect_end();
}

void ClockSession::save_state(CheckpointWriter& out) const {
  const size_t at = out.begin_section(kClockSection);
  out.pod(tick_);
  out.pod(frames_);
  out.pod(frame_clock_.next_frame);
  out.end_section(at);
  loop_.save_state(out);
}

void ClockSession::load_state(CheckpointReader& outer) {
  CheckpointReader in = outer.section(kClockSection, "clock");
  in.pod_into(tick_, "the tick");
  in.pod_into(frames_, "the frame count");
  in.pod_into(frame_clock_.next_frame, "the next frame");
  in.expect_end();
  loop_.load_state(outer);
}

void HapticInteraction::save_state(CheckpointWriter& out) const {
  static_assert(std::is_trivially_copyable_v<Channel>, "a channel is saved as plain bytes");
  const size_t at = out.begin_section(kHapticSection);
  out.array(channels_);
  out.end_section(at);
}

void HapticInteraction::load_state(CheckpointReader& outer) {
  CheckpointReader in = outer.section(kHapticSection, "haptic channels");
  in.array_exact(channels_, "haptic channels (devices)");
  in.expect_end();
}

}  // namespace tacta
