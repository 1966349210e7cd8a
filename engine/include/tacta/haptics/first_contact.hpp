// First-contact shaping. A contact can begin with the device already deep in the surface (the
// body moved onto the tool, a fast hand, a late detection); a coupling spring that engages at full
// stretch then kicks with k * depth, many times the steady contact force.
//
// The penetration the contact begins with (s0, proxy - device) is withheld as a gap that closes at
// most `stretch_rate` (m/s) * dt per tick: the onset force rate is bounded by k * stretch_rate and
// the hand's own damping absorbs it. Motion after the first tick reaches the spring one for one
// (a stretch that grew with time rather than with the device's motion would be an energy source),
// so steady contact and sliding feel the coupling's stiffness exactly. Closing the gap is paid
// from a budget: `max_stretch`, the stretch whose spring energy 1/2 k L^2 the coupling has
// received (the initial penetration counting as received); ContactRenderer keeps that ledger.
// Leaving contact re-arms the shaping. Figures (onset peak over steady, energy returned):
// docs/VALIDATION.md, tests test_haptics and DeformablePress.*.
#pragma once

#include <limits>

#include "tacta/vec3.hpp"

namespace tacta::haptics {

struct FirstContactParams {
  double stretch_rate = 0.01;  // m/s, rate at which the initial penetration reaches the spring
};

class FirstContactLimiter {
 public:
  explicit FirstContactLimiter(const FirstContactParams& params = {}) noexcept : params_(params) {}

  // stretch: proxy - device this tick (m); in_contact: the proxy is constrained by a surface.
  // max_stretch (m): the largest stretch the coupling's energy budget allows (see above).
  // Returns the stretch the coupling spring should use.
  Vec3 shape(const Vec3& stretch, bool in_contact, double dt,
             double max_stretch = std::numeric_limits<double>::infinity()) noexcept;
  bool in_onset() const noexcept { return onset_; }
  void reset() noexcept {
    onset_ = true;
    engaged_ = false;
    gap_ = 0.0;
  }

 private:
  FirstContactParams params_;
  bool onset_ = true;     // armed: the next contact starts limited
  bool engaged_ = false;  // the current contact's first tick has been seen
  double gap_ = 0.0;      // m, true stretch minus the stretch the spring sees
};

}  // namespace tacta::haptics
