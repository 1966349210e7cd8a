// The Z-width stability criterion: is a haptic contact stable, judged from the per-tick trace of
// one pressing-and-holding run (trace.csv, docs/REPORT.md)?
//
// Stable, for a run whose hand presses and then holds still over [hold_start, hold_end]:
//   1. no body fault (no frozen body, no non-finite force);
//   2. the tool stays in contact on every tick of the hold (no bouncing, no chatter);
//   3. the force oscillation does not persist: with "ringing" the RMS of |F| about its
//      least-squares line over a window of `settle_window` s, the ringing over the last window of
//      the hold is either at most max(abs_tolerance, rel_tolerance * mean |F|) (settled), or at
//      most decay_ratio times the ringing over the first window of the hold (decaying).
// A limit cycle (same ringing early and late) or a growing oscillation fails 3; a lightly damped
// hand whose oscillation dies away slowly passes. The port energy (work done on the
// environment by the held device force, E(n) = E(n-1) - F(n-1).(x(n) - x(n-1)), Hannaford-Ryu)
// is reported beside the verdict: its most negative value is the energy the coupling gave back
// beyond what it took (J).
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

namespace tacta::bench {

struct TraceSample {
  double time = 0.0;               // s, end of the tick
  std::array<double, 3> device{};  // m, device position
  std::array<double, 3> proxy{};   // m, proxy position (on the surface)
  std::array<double, 3> force{};   // N, force sent to the device
  bool contact = false;
};

struct StabilityCriterion {
  double hold_start = 0.4;      // s: from here the hand holds still and contact is required
  double hold_end = 1.1;        // s: the hold ends (the hand starts to release)
  double settle_window = 0.2;   // s: the last part of the hold where the force must be steady
  double abs_tolerance = 1e-3;  // N, RMS of |F| about its trend below which it is steady
  double rel_tolerance = 0.01;  // of the mean |F| over the settle window
  double decay_ratio = 0.5;     // late ringing at most this times the early ringing: decaying
};

struct StabilityVerdict {
  bool stable = false;
  std::string reason;            // why not, in a few words ("ok" when stable)
  double mean_force = 0.0;       // N, mean |F| over the settle window
  double oscillation_rms = 0.0;  // N, RMS of |F| about its linear trend over the settle window
  double early_oscillation_rms = 0.0;  // N, the same over the first settle_window s of the hold
  double peak_force = 0.0;             // N, largest |F| of the run
  double rendered_stiffness = 0.0;  // N/m, mean |F| / mean |proxy - device| over the settle window
  double min_port_energy = 0.0;     // J, most negative port energy (0 when passive throughout)
  unsigned long contact_lost = 0;   // ticks without contact during the hold
};

// body_fault: the run reported a body fault (frozen body) or a non-finite force.
StabilityVerdict judge_stability(std::span<const TraceSample> trace,
                                 const StabilityCriterion& criterion, bool body_fault);

// Reads device 0's rows of a trace.csv (columns by name, docs/REPORT.md); throws
// std::runtime_error naming the file and line on a malformed file.
std::vector<TraceSample> read_trace_csv(const std::string& path);

}  // namespace tacta::bench
