// The Z-width stability criterion can pass and fail: on synthetic traces with a known answer, and
// on real runs of scenes/bench/zwidth.yaml (corotational FEM block, sim_stylus hand, passivity
// controller and first-contact limit off).
#include "zwidth_criterion.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

#include "zwidth_run.hpp"

namespace tacta::bench {
namespace {

constexpr double kTick = 1e-3;  // s

// 1.2 s of a hold at `force` N along +y with the device 2 mm inside a surface at y = 0, plus a
// 40 Hz oscillation of amplitude a0 * exp(growth * t) N.
std::vector<TraceSample> hold_trace(double force, double a0, double growth) {
  std::vector<TraceSample> trace;
  for (int i = 1; i <= 1200; ++i) {
    TraceSample s;
    s.time = i * kTick;
    s.contact = true;
    s.device = {0.0, -0.002, 0.0};
    s.proxy = {0.0, 0.0, 0.0};
    s.force = {
        0.0, force + a0 * std::exp(growth * s.time) * std::sin(2 * std::numbers::pi * 40 * s.time),
        0.0};
    trace.push_back(s);
  }
  return trace;
}

TEST(ZwidthCriterion, SteadyHoldIsStableAndMeasuresTheRenderedStiffness) {
  const std::vector<TraceSample> trace = hold_trace(1.0, 0.0, 0.0);
  const StabilityVerdict v = judge_stability(trace, StabilityCriterion{}, false);
  EXPECT_TRUE(v.stable) << v.reason;
  EXPECT_NEAR(v.mean_force, 1.0, 1e-12);
  EXPECT_NEAR(v.rendered_stiffness, 500.0, 1e-9);  // 1 N over 2 mm
  EXPECT_NEAR(v.oscillation_rms, 0.0, 1e-12);
}

TEST(ZwidthCriterion, DecayedRingingIsStableGrowingOscillationIsNot) {
  // Decays by e^-30 before the settle window: stable.
  EXPECT_TRUE(judge_stability(hold_trace(1.0, 0.5, -30.0), StabilityCriterion{}, false).stable);
  // Decays slowly (amplitude 0.2 N, time constant 0.5 s): not settled, but decaying: stable.
  EXPECT_TRUE(judge_stability(hold_trace(1.0, 0.2, -2.0), StabilityCriterion{}, false).stable);
  // Grows from 5 mN: an RMS of about 0.7 * 5e-3 * e^2 N in the settle window, over the 10 mN bound.
  const StabilityVerdict v =
      judge_stability(hold_trace(1.0, 5e-3, 2.0), StabilityCriterion{}, false);
  EXPECT_FALSE(v.stable);
  EXPECT_GT(v.oscillation_rms, 0.01);
  EXPECT_GT(v.oscillation_rms, v.early_oscillation_rms);
  // A limit cycle: a constant 0.1 N ringing never decays.
  EXPECT_FALSE(judge_stability(hold_trace(1.0, 0.1, 0.0), StabilityCriterion{}, false).stable);
  // A slow linear drift (a body still creeping) is not an oscillation.
  std::vector<TraceSample> drift = hold_trace(1.0, 0.0, 0.0);
  for (TraceSample& s : drift) s.force[1] += 0.2 * s.time;
  EXPECT_TRUE(judge_stability(drift, StabilityCriterion{}, false).stable);
}

TEST(ZwidthCriterion, LostContactOrFaultIsUnstable) {
  std::vector<TraceSample> bounce = hold_trace(1.0, 0.0, 0.0);
  bounce[600].contact = false;  // t = 0.601 s, inside the hold
  const StabilityVerdict v = judge_stability(bounce, StabilityCriterion{}, false);
  EXPECT_FALSE(v.stable);
  EXPECT_EQ(v.contact_lost, 1u);
  EXPECT_FALSE(judge_stability(hold_trace(1.0, 0.0, 0.0), StabilityCriterion{}, true).stable);
}

TEST(ZwidthCriterion, PortEnergyIsTheWorkOfTheHeldForce) {
  // A 1 N push along +y while the device moves 1 mm per tick along +y for 10 ticks: the
  // environment gives the device 1 N * 10 mm = 10 mJ (port energy -0.01 J).
  std::vector<TraceSample> trace = hold_trace(1.0, 0.0, 0.0);
  for (int i = 0; i <= 10; ++i) trace[static_cast<size_t>(i)].device[1] = -0.002 + 1e-3 * i;
  for (size_t i = 11; i < trace.size(); ++i) trace[i].device[1] = 0.008;
  EXPECT_NEAR(judge_stability(trace, StabilityCriterion{}, false).min_port_energy, -0.01, 1e-12);
}

// The real chain: coupling stiffness is what tips it. An undamped hand (hand_damping 0) with the
// controller off: 40000 N/m must ring or bounce, 300 N/m must settle.
class ZwidthScene : public ::testing::Test {
 protected:
  // A folder per test: ctest runs the two cases as parallel processes, and each run rewrites
  // its trace.csv there.
  ZwidthRunner runner{std::string(TACTA_SOURCE_DIR) + "/scenes/bench/zwidth.yaml",
                      std::string(TACTA_BINARY_DIR) + "/test_zwidth_runs/" +
                          ::testing::UnitTest::GetInstance()->current_test_info()->name(),
                      TACTA_PLUGIN_DIR};
  ZwidthCase undamped{"corotational_fem", 0.0, false, {"devices.*.params.hand_damping=0"}};
};

TEST_F(ZwidthScene, StiffCouplingOnAnUndampedHandIsFlagged) {
  const StabilityVerdict stiff = runner.run(undamped, 40000.0);
  EXPECT_FALSE(stiff.stable) << "rms " << stiff.oscillation_rms << " N, mean " << stiff.mean_force
                             << " N";
}

TEST_F(ZwidthScene, SoftCouplingOnAnUndampedHandPasses) {
  const StabilityVerdict soft = runner.run(undamped, 300.0);
  EXPECT_TRUE(soft.stable) << soft.reason << ", rms " << soft.oscillation_rms << " N";
  EXPECT_GT(soft.mean_force, 0.2);                    // N: it really presses
  EXPECT_NEAR(soft.rendered_stiffness, 300.0, 30.0);  // N/m: the coupling is rendered as set
}

}  // namespace
}  // namespace tacta::bench
