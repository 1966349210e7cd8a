// The local contact model the haptic loop renders against when the touched body steps slower,
// on its own thread (scene: step_thread: own). Between two refreshes of the body's state the
// haptic loop sees a frozen surface; left like that the tool would feel a rigid wall that jumps
// at every refresh. Instead, around the contact the surface is a spring of the body's local
// point stiffness k_l (N/m) in series with the virtual coupling k_c: the refreshed surface already
// carries the normal force f_ref (N) the body felt in its last step, and only the force beyond
// it pushes the surface further in.
//
// With d (m) the device's depth below the refreshed surface along the outward normal, the
// surface sits at depth u = (k_c d - f_ref) / (k_l + k_c) and the coupling stretch along the
// normal becomes s = d - u = (f_ref + k_l d) / (k_l + k_c). Checks: k_l -> infinity gives the
// rigid snapshot (s = d); a device that has not moved since the refresh of a body at rest
// under f_ref (d = f_ref / k_c) gets exactly f_ref back. This is the multirate "local linear
// model" idea (a low-rate simulation hands the high-rate loop a local stiffness around the
// contact; e.g. Cavusoglu and Tendick, ICRA 2000), here reduced to the normal direction.
#pragma once

#include "tacta/vec3.hpp"

namespace tacta::haptics {

struct LocalCompliance {
  bool active = false;
  double stiffness = 0.0;        // N/m, k_l: the body's point stiffness at the contact, as measured
                                 // from its refreshed states (HapticInteraction)
  double reference_force = 0.0;  // N, f_ref: the normal force the refreshed surface has felt
  Vec3 normal{0.0, 0.0, 1.0};    // unit outward direction the surface yields along: the press
                                 // direction (the normal where the contact began), not the
                                 // normal of each tick, which flips on faceted surfaces
};

// The coupling stretch (proxy - device, m) seen through the local model (along local.normal),
// coupling_stiffness k_c in N/m. The other directions are unchanged.
inline Vec3 yield_stretch(const Vec3& stretch, double coupling_stiffness,
                          const LocalCompliance& local) noexcept {
  if (!local.active || !(local.stiffness > 0.0) || !(coupling_stiffness > 0.0)) return stretch;
  const Vec3& normal = local.normal;
  const double d = dot(stretch, normal);
  if (d <= 0.0) return stretch;  // not pressing: nothing to yield
  const double s =
      (local.reference_force + local.stiffness * d) / (local.stiffness + coupling_stiffness);
  return add_scaled(stretch, normal, s - d);
}

}  // namespace tacta::haptics
