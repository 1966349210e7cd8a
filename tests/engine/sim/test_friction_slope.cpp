// Coulomb friction through a whole run (scene -> collision pipeline -> the ccd plugin's response):
// a soft block on an inclined plane. Reference: the rigid block on a slope, analytic. Along the
// slope a sliding block accelerates at a = g (sin theta - mu cos theta) (negative: it
// decelerates), and a block at rest stays at rest when tan theta < mu. The slope is the floor
// y = 0 with gravity tilted by theta towards +x (the same physics as a tilted plane under
// vertical gravity, with the block's mesh axis-aligned on the floor).
//
// Also the one rule for the coefficient (docs/SCENES.md, collision.friction): written as
// collision.friction or as the ccd plugin's own `friction` parameter; both written with
// different values is refused at load.
#include <cmath>
#include <cstdio>
#include <string>

#include "sim_test_support.hpp"
#include "tacta/error.hpp"
#include "validation_row.hpp"

namespace tacta::simtest {
namespace {

constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

// A 4 cm corotational cube (2x2x2 cells, E 100 kPa) resting on the floor; the collision section
// is COLLISION, the gravity tilted by THETA degrees, initial slide velocity V0 (m/s, along +x).
std::string slope_scene(double theta_deg, const std::string& collision, double v0) {
  const double t = theta_deg * kPi / 180.0;
  char gravity[96];
  std::snprintf(gravity, sizeof gravity, "[%.17g, %.17g, 0]", kG * std::sin(t), -kG * std::cos(t));
  std::string text = R"(
name: friction_slope
gravity: GRAVITY
clock: {mode: lockstep, duration_s: 10}
output: {trace: false}
bodies:
  - name: block
    mesh: {box_grid: {size: [0.04, 0.04, 0.04], cells: [2, 2, 2], origin: [-0.02, 0.0001, -0.02]}}
    material: {youngs_modulus: 1.0e5, poisson_ratio: 0.3, density: 1000, rayleigh_stiffness: 0.002}
    model: {name: corotational_fem, solver: cholesky}
    initial: {uniform_velocity: [V0, 0, 0]}
obstacles:
  - {name: slope, shape: {plane: {normal: [0, 1, 0], offset: 0}}}
collision: COLLISION
)";
  const auto put = [&](const std::string& key, const std::string& value) {
    text.replace(text.find(key), key.size(), value);
  };
  put("GRAVITY", gravity);
  put("COLLISION", collision);
  put("V0", std::to_string(v0));
  return text;
}

struct Slide {
  double acceleration = 0;    // m/s^2 along +x (down the slope), least squares over the window
  double displacement = 0;    // m along x of the centre of mass at the end
  double end_velocity = 0;    // m/s along x of the centre of mass at the end
  std::vector<double> x_com;  // m, per tick (bitwise comparisons of two runs)
};

// Runs `ticks` ms; the acceleration is the least-squares slope of the centre of mass's x
// velocity over ticks [from, to].
Slide slide(const std::string& text, int ticks, int from, int to) {
  Simulation sim(scene_from_text(text, "friction_slope"), plugins());
  const BodyArrays a = sim.body_arrays(sim.body("block"));
  double mass = 0, x0 = 0;
  for (size_t n = 0; n < a.nodes; ++n) mass += a.masses[n];
  for (size_t n = 0; n < a.nodes; ++n) x0 += a.masses[n] * a.positions[3 * n] / mass;
  double st = 0, sv = 0, stt = 0, stv = 0;
  int count = 0;
  Slide s;
  for (int tick = 1; tick <= ticks; ++tick) {
    sim.step(1);
    const BodyArrays b = sim.body_arrays(sim.body("block"));
    double v = 0, x = 0;
    for (size_t n = 0; n < b.nodes; ++n) {
      v += b.masses[n] * b.velocities[3 * n] / mass;
      x += b.masses[n] * b.positions[3 * n] / mass;
    }
    s.x_com.push_back(x);
    s.displacement = x - x0;
    s.end_velocity = v;
    if (tick < from || tick > to) continue;
    const double t = tick * 1e-3;
    st += t, sv += v, stt += t * t, stv += t * v, ++count;
  }
  s.acceleration = (count * stv - st * sv) / (count * stt - st * st);
  return s;
}

double coulomb(double theta_deg, double mu) {
  const double t = theta_deg * kPi / 180.0;
  return kG * (std::sin(t) - mu * std::cos(t));
}

// One row per check for scripts/validate (docs/VALIDATION.md, "Rows").
bool row(const char* name, const char* reference, const char* tolerance, double measured,
         double expected, bool pass) {
  return test::validation_row(
      name, reference, tolerance,
      test::validation_number(measured) + " (expected " + test::validation_number(expected) + ")",
      pass);
}

// tan 30 deg = 0.577 > 0.3: slides down from rest at g (sin - mu cos) = 2.356 m/s^2. 5 %: the
// block is elastic, so its contact vertices carry an oscillating share of the load; the slope
// of the centre of mass's velocity over 250 ms averages it out (measured within 1 %).
TEST(FrictionSlope, SlidingBlockAcceleratesAtGSinMinusMuCos) {
  const Slide s = slide(slope_scene(30, "{friction: 0.3}", 0.0), 300, 50, 300);
  const double expected = coulomb(30, 0.3);
  const bool pass = std::abs(s.acceleration - expected) <= 0.05 * expected;
  row("friction.slope_30deg_mu0.3", "rigid block on a slope: g (sin theta - mu cos theta)",
      "5 % (elastic block: contact load oscillates)", s.acceleration, expected, pass);
  EXPECT_NEAR(s.acceleration, expected, 0.05 * expected);
  // Friction did act: frictionless the same block goes at g sin theta.
  const Slide free = slide(slope_scene(30, "{friction: 0}", 0.0), 300, 50, 300);
  EXPECT_NEAR(free.acceleration, coulomb(30, 0.0), 0.05 * coulomb(30, 0.0));
}

// tan 10 deg = 0.176 < 0.5, launched down the slope at 1 m/s: decelerates at
// g (mu cos - sin) = 3.127 m/s^2, stops after 0.32 s and stays.
TEST(FrictionSlope, LaunchedBlockDeceleratesAndStops) {
  const Slide s = slide(slope_scene(10, "{friction: 0.5}", 1.0), 600, 30, 250);
  const double expected = coulomb(10, 0.5);  // negative
  const bool pass = std::abs(s.acceleration - expected) <= 0.05 * std::abs(expected);
  row("friction.slope_10deg_mu0.5_decelerates",
      "rigid block on a slope: g (sin theta - mu cos theta)", "5 % (as above)", s.acceleration,
      expected, pass);
  EXPECT_NEAR(s.acceleration, expected, 0.05 * std::abs(expected));
  // Stopping distance v0^2 / (2 |a|) = 0.160 m; stopped at the end.
  EXPECT_NEAR(s.displacement, 1.0 / (2 * std::abs(expected)), 0.05 / (2 * std::abs(expected)));
  EXPECT_LT(std::abs(s.end_velocity), 1e-3);
}

// tan 20 deg = 0.364 < mu 0.5: a block set down at rest stays put. Reference: 0 (a rigid block
// does not move). The elastic block first settles into the slope (it lands from the contact
// margin and shears under the slope's load: its bottom slips 0.1 mm and its top leans 0.27 mm
// within 50 ms, then holds); from 0.1 s on the centre of mass may move 10 um at most (ringing of
// that settling decays, measured 2 um), against 0.40 m sliding frictionless over the same 0.4 s.
TEST(FrictionSlope, BlockOnAShallowerSlopeThanItsFrictionAngleStaysPut) {
  const Slide s = slide(slope_scene(20, "{friction: 0.5}", 0.0), 500, 100, 500);
  const double moved = s.x_com[499] - s.x_com[99];
  const bool pass = std::abs(moved) < 1e-5;
  row("friction.slope_20deg_mu0.5_stays", "rigid block, tan theta < mu: no motion",
      "10 um from 0.1 to 0.5 s (the elastic settling's ringing)", moved, 0.0, pass);
  EXPECT_LT(std::abs(moved), 1e-5);
  EXPECT_LT(std::abs(s.end_velocity), 1e-4);
  // Frictionless, the same block slides away: the check above can fail.
  const Slide free = slide(slope_scene(20, "{friction: 0}", 0.0), 500, 100, 500);
  EXPECT_GT(free.x_com[499] - free.x_com[99], 0.1);
}

// The ccd plugin's own parameter is the same coefficient: written there instead of in
// collision.friction it gives bitwise the same run.
TEST(FrictionSlope, PluginParameterAndCollisionFrictionAreOneCoefficient) {
  const Slide scene_key = slide(slope_scene(30, "{friction: 0.3}", 0.0), 100, 1, 100);
  const Slide plugin_key =
      slide(slope_scene(30, "{narrow_phase: {name: ccd, friction: 0.3}}", 0.0), 100, 1, 100);
  EXPECT_EQ(scene_key.x_com, plugin_key.x_com);
  // And it is not the default 0.3 by accident: 0.1 written on the plugin slides faster.
  const Slide plugin_low =
      slide(slope_scene(30, "{narrow_phase: {name: ccd, friction: 0.1}}", 0.0), 300, 50, 300);
  EXPECT_NEAR(plugin_low.acceleration, coulomb(30, 0.1), 0.05 * coulomb(30, 0.1));
}

TEST(FrictionSlope, TwoDifferentCoefficientsAreRefused) {
  try {
    scene_from_text(slope_scene(30, "{friction: 0.3, narrow_phase: {name: ccd, friction: 0.4}}", 0),
                    "friction_slope");
    ADD_FAILURE() << "a scene with two different frictions loaded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("friction is given twice"), std::string::npos) << what;
    EXPECT_NE(what.find("collision.friction"), std::string::npos) << what;
  }
  // The same value in both places is one coefficient: accepted.
  EXPECT_NO_THROW(scene_from_text(
      slope_scene(30, "{friction: 0.4, narrow_phase: {name: ccd, friction: 0.4}}", 0),
      "friction_slope"));
}

}  // namespace
}  // namespace tacta::simtest
