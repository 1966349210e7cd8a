// Cutting as the hand feels it (issue 22, "Haptics"): a probe pressed beside a separation moves
// nothing on the far side and one lowered into a carved slot touches nothing until the slot's
// floor; a cut made while the stylus dwells gives no force spike. Energy and replay are in
// test_cut_energy_replay.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

#include "cut_haptics_support.hpp"

namespace tacta::simtest {
namespace {

// ---- A probe across a cut line meets no stiffness on the far side ---------------------------

struct PressOutcome {
  double near_displacement = 0, far_displacement = 0;  // m, largest node displacement per side
  double peak_force = 0;                               // N
};

// The stylus presses 8 mm into the top face at x = -12.5 mm (left of the plane x = 0), with or
// without the cube first separated along x = 0. "Far" is the right piece (or, uncut, the nodes
// at x >= 12.5 mm, as far from the plane as the probe is).
PressOutcome press_beside_the_plane(bool separated) {
  Simulation sim(
      scene_from_text(cube_scene("corotational_fem", press_waypoints(-0.0125, 0.092)), "cut_cube"),
      plugins());
  const BodyHandle cube = sim.body("cube");
  std::vector<int> piece;
  if (separated) {
    const CutSummary split = sim.cut(cube, plane_x(0.0), CutMode::kSeparate);
    EXPECT_EQ(split.nodes_added, 5u * 5);  // the 5 x 5 nodes of the plane, copied once
    piece = pieces(sim.body_mesh(cube));
  }
  PressOutcome out;
  const DeviceHandle stylus = sim.device("stylus");
  while (sim.time() < 0.4 - 1e-9) {
    sim.step();
    out.peak_force = std::max(out.peak_force, norm(sim.device_reading(stylus).force));
  }
  const BodyArrays a = sim.body_arrays(cube);
  const VolumeMesh& mesh = sim.body_mesh(cube);
  const int right = separated ? piece[node_with_largest_x(mesh)] : -1;
  for (uint32_t n = 0; n < a.nodes; ++n) {
    const double d = std::hypot(a.positions[3 * n] - a.rest_positions[3 * n],
                                a.positions[3 * n + 1] - a.rest_positions[3 * n + 1],
                                a.positions[3 * n + 2] - a.rest_positions[3 * n + 2]);
    const bool far = separated ? piece[n] == right : a.rest_positions[3 * n] >= 0.0125 - 1e-9;
    double& side = far ? out.far_displacement : out.near_displacement;
    side = std::max(side, d);
  }
  return out;
}

// Gravity is off, so the far piece has no load at all once cut: its nodes stay where they are to
// round-off (1e-12 m, a billionth of the near side's millimetres). Uncut, the same press moves
// the far nodes by a sizeable fraction of the near side's motion (so the check can fail).
TEST(CutHaptics, PressBesideASeparationMovesNothingOnTheFarSide) {
  const PressOutcome intact = press_beside_the_plane(false);
  const PressOutcome cut = press_beside_the_plane(true);
  std::printf(
      "intact: near %.3g m, far %.3g m, peak %.4f N; separated: near %.3g m, far %.3g m, "
      "peak %.4f N\n",
      intact.near_displacement, intact.far_displacement, intact.peak_force, cut.near_displacement,
      cut.far_displacement, cut.peak_force);
  ASSERT_GT(intact.near_displacement, 1e-3) << "the press must deform the cube";
  EXPECT_GT(intact.far_displacement, 0.05 * intact.near_displacement)
      << "uncut, the press reaches across the plane";
  EXPECT_GT(cut.near_displacement, 1e-3);
  EXPECT_LT(cut.far_displacement, 1e-12) << "the far piece moved: coupled across the cut";
  EXPECT_LT(cut.peak_force, intact.peak_force) << "the half cube is softer than the whole";
}

// A removal carves a slot 25 mm wide from the top face down to y = 50 mm (the cells x in
// [-25, 0] mm, y in [50, 100] mm, all z). The stylus (a 4 mm sphere) is lowered along the slot's
// middle: above the floor it touches nothing (zero force, to the bit); it meets the floor when
// its centre reaches 54 mm. Uncut, the same descent is in contact from 104 mm.
struct Descent {
  double lowest_free_y = 1.0;  // m, the lowest stylus height with zero force and no contact
  double highest_contact_y = -1.0;
  double nonzero_above_floor = 0;  // N, the largest force while the centre is 1 mm above 54 mm
  double final_force = 0;          // N
};

Descent lower_into(bool slotted) {
  // Down from 115 mm to 40 mm over 0.6 s, then held.
  const std::string waypoints = "[0, -0.0125, 0.115, 0,   0.6, -0.0125, 0.040, 0]";
  Simulation sim(scene_from_text(cube_scene("corotational_fem", waypoints), "cut_cube"), plugins());
  const BodyHandle cube = sim.body("cube");
  if (slotted) {
    const std::vector<double> blade = quad_x(-0.0125, 0.051, 0.2);
    const CutSummary slot = sim.cut(cube, blade, CutMode::kRemove);
    EXPECT_EQ(slot.tets_removed, 2u * 4 * 6);  // 2 cells high, 4 deep, 6 tets each
  }
  Descent out;
  const DeviceHandle stylus = sim.device("stylus");
  while (sim.time() < 0.8 - 1e-9) {
    sim.step();
    const DeviceReading r = sim.device_reading(stylus);
    const double force = norm(r.force), y = r.position[1];
    if (force == 0.0 && !r.in_contact) out.lowest_free_y = std::min(out.lowest_free_y, y);
    if (r.in_contact) out.highest_contact_y = std::max(out.highest_contact_y, y);
    if (y > 0.054 + 0.001) out.nonzero_above_floor = std::max(out.nonzero_above_floor, force);
    out.final_force = force;
  }
  return out;
}

TEST(CutHaptics, ProbeLoweredIntoACarvedSlotTouchesNothingUntilItsFloor) {
  const Descent intact = lower_into(false);
  const Descent slotted = lower_into(true);
  std::printf(
      "intact: first contact at %.4f m; slotted: free down to %.4f m, first contact at "
      "%.4f m, largest force above the floor %.3g N, held %.3f N\n",
      intact.highest_contact_y, slotted.lowest_free_y, slotted.highest_contact_y,
      slotted.nonzero_above_floor, slotted.final_force);
  EXPECT_GT(intact.highest_contact_y, 0.1) << "uncut, the descent meets the top face";
  EXPECT_EQ(slotted.nonzero_above_floor, 0.0) << "a force inside the slot, above its floor";
  EXPECT_LT(slotted.highest_contact_y, 0.054 + 1e-4) << "contact above the slot's floor";
  EXPECT_LT(slotted.lowest_free_y, 0.0545) << "free all the way down to the floor";
  EXPECT_GT(slotted.final_force, 0.5) << "the floor pushes back";
}

// ---- No force spike at a topology change ----------------------------------------------------

// The stylus presses 8 mm into the top face at x = -12.5 mm and dwells; at 0.8 s (the press
// settled) the cube is cut. Over the 50 ticks after the cut the force stays within 1.1 x the
// force of the tick before (issue 22: peak over steady at most 1.1, as for first contact).
struct DwellCut {
  double steady = 0, peak_after = 0, lowest_after = 1e9;  // N
};

DwellCut cut_while_dwelling(const std::vector<double>& blade, CutMode mode, bool cut) {
  Simulation sim(
      scene_from_text(cube_scene("corotational_fem", press_waypoints(-0.0125, 0.092)), "cut_cube"),
      plugins());
  const DeviceHandle stylus = sim.device("stylus");
  sim.advance_to(0.8);
  DwellCut out;
  out.steady = norm(sim.device_reading(stylus).force);
  if (cut) {
    EXPECT_TRUE(sim.cut(sim.body("cube"), blade, mode).changed);
  }
  for (int k = 0; k < 50; ++k) {
    sim.step();
    const double f = norm(sim.device_reading(stylus).force);
    out.peak_after = std::max(out.peak_after, f);
    out.lowest_after = std::min(out.lowest_after, f);
  }
  return out;
}

TEST(CutHaptics, NoForceSpikeWhenTheBodyIsCutDuringADwell) {
  const DwellCut uncut = cut_while_dwelling({}, CutMode::kSeparate, false);
  std::printf("no cut: steady %.4f N, next 50 ticks %.4f..%.4f N\n", uncut.steady,
              uncut.lowest_after, uncut.peak_after);
  ASSERT_GT(uncut.steady, 0.5) << "the stylus must be pressing";
  struct Case {
    const char* name;
    std::vector<double> blade;
    CutMode mode;
  };
  const Case cases[] = {
      {"separation 37.5 mm away (x = 25 mm)", plane_x(0.025), CutMode::kSeparate},
      {"separation beside the probe (x = 0)", plane_x(0.0), CutMode::kSeparate},
      {"removal of the far column (x = 37.5 mm)", plane_x(0.0375), CutMode::kRemove},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const DwellCut r = cut_while_dwelling(c.blade, c.mode, true);
    std::printf("%s: steady %.4f N, next 50 ticks %.4f..%.4f N, peak/steady %.4f\n", c.name,
                r.steady, r.lowest_after, r.peak_after, r.peak_after / r.steady);
    EXPECT_LE(r.peak_after, 1.1 * r.steady);
    EXPECT_GT(r.lowest_after, 0.0) << "the stylus lost the surface at the cut";
  }
}

}  // namespace
}  // namespace tacta::simtest
