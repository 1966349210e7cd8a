// The threaded hyperelastic step (issue: every core used): with two or more workers the element
// pass runs in coloured tiles and the passes over the system matrix on row chunks, beside the
// threaded CG. The step equals the serial one to rounding, repeats bit for bit at a fixed thread
// count and gives the same bits on 2 and 3 threads; the lagged-system decision (a force pass that
// stops once an element has moved too far) is the serial one; a body stepped in a group runs the
// serial step bit for bit, and so does a body with nodal volumes; a threaded step allocates
// nothing. The host services are the engine's JobPool, as the engine hands them to a plugin.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <memory>
#include <numeric>
#include <random>
#include <span>
#include <vector>

#include "allocation_counter.hpp"  // the shared malloc interposer; off under the sanitizers
#include "hyperelastic_test_support.hpp"
#include "services/job_pool.hpp"

namespace tacta::models::hyperelastic {
namespace {

using testing::Body;
using testing::make_model;

struct Host {  // the engine's host services over a pool of `threads`
  explicit Host(uint32_t threads) : pool(threads) {}
  JobPool pool;
  tacta_host_services services = host_services(&pool, nullptr);
};

// A soft box of 7 x 7 x 7 cubes (2,058 tets, 512 nodes) clamped at z = 0, under gravity, its
// top kicked sideways: above the threaded thresholds, and it swings far enough that some steps
// reuse the lagged system and others rule it out.
struct KickedBox {
  TestMesh mesh = box_tet_mesh({7, 7, 7}, {0.07, 0.07, 0.07}, 1000.0);
  Volumetric volumetric = Volumetric::kElement;
  KickedBox() { mesh.fix_plane(2, 0.0); }

  struct Run {
    std::vector<double> positions;
    NewtonCounters counters;
  };
  Run run(const tacta_host_services* host, int steps = 30) const {
    Options options;
    options.host = host;
    options.volumetric = volumetric;
    auto model = make_model(mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, options);
    Body body(mesh);
    for (uint32_t i = 0; i < mesh.node_count(); ++i) {
      body.f[3 * i + 1] = -9.81 * mesh.masses[i];
      body.v[3 * i] = 3.0 * mesh.positions[3 * i + 2];  // m/s, growing with height
    }
    model->begin(body.state, 1e-3);
    for (int i = 0; i < steps; ++i)
      EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u) << i;
    return {body.x, model->counters()};
  }
};

// The largest |a - b| against the largest displacement of the reference run from rest.
struct Gap {
  double difference = 0.0, displacement = 0.0;
  Gap(const std::vector<double>& a, const std::vector<double>& b, const TestMesh& mesh) {
    for (size_t k = 0; k < a.size(); ++k) {
      difference = std::max(difference, std::abs(a[k] - b[k]));
      displacement = std::max(displacement, std::abs(b[k] - mesh.positions[k]));
    }
  }
};

void expect_threaded_matches_serial(const KickedBox& box) {
  const KickedBox::Run serial = box.run(nullptr);
  Host one(1), two(2), three(3);
  EXPECT_EQ(box.run(&one.services).positions, serial.positions) << "one thread is the serial code";
  const KickedBox::Run on_two = box.run(&two.services);
  EXPECT_NE(on_two.positions, serial.positions) << "the threaded step sums in another order";
  const Gap gap(on_two.positions, serial.positions, box.mesh);
  EXPECT_GT(gap.displacement, 1e-3);
  // Newton stops at 1e-3 of its first residual and CG at 1e-4 either way: the runs differ by
  // rounding carried through 30 steps, many orders below what the solvers leave.
  EXPECT_LT(gap.difference, 1e-8 * gap.displacement)
      << gap.difference << " of " << gap.displacement;
  // The same decisions: lagged systems reused, fresh ones assembled, backtracks.
  EXPECT_EQ(on_two.counters.newton_iterations, serial.counters.newton_iterations);
  EXPECT_EQ(on_two.counters.lagged_tangents, serial.counters.lagged_tangents);
  EXPECT_EQ(on_two.counters.line_search_backtracks, serial.counters.line_search_backtracks);
  EXPECT_EQ(box.run(&two.services).positions, on_two.positions) << "two threads, twice";
  EXPECT_EQ(box.run(&three.services).positions, on_two.positions) << "two and three threads";
}

TEST(ThreadedHyperelastic, EqualsSerialToRoundingAndRepeatsBitForBit) {
  const KickedBox box;
  const KickedBox::Run serial = box.run(nullptr);
  // The run exercises both sides of the lagged-system test. Every step converges on one
  // correction, so only that test (an element moved further than tangent_reuse_change since the
  // lagged assembly) can refuse a lagged system within its age limit (4): without refusals, 4
  // of every 5 steps would reuse it. Refused passes are the ones the threaded pass stops early.
  EXPECT_EQ(serial.counters.unconverged_steps, 0u);
  EXPECT_EQ(serial.counters.newton_iterations, serial.counters.steps);
  EXPECT_GT(serial.counters.lagged_tangents, 0u);
  EXPECT_LT(serial.counters.lagged_tangents, 4 * serial.counters.steps / 5 - 1);
  expect_threaded_matches_serial(box);
}

TEST(ThreadedHyperelastic, AMeshersOrderGetsMortonTilesAndTheSameResults) {
  KickedBox box;  // the tets in a random order, as a mesher may write them
  std::vector<uint32_t> order(box.mesh.tets.size() / 4);
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  const std::vector<uint32_t> tets = box.mesh.tets;
  for (size_t e = 0; e < order.size(); ++e)
    std::copy_n(&tets[4 * size_t{order[e]}], 4, &box.mesh.tets[4 * e]);
  Host two(2);
  Options options;
  options.host = &two.services;
  ASSERT_TRUE(make_model(box.mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, options)->tiled());
  expect_threaded_matches_serial(box);
}

TEST(ThreadedHyperelastic, NodalVolumesKeepTheSerialStep) {
  KickedBox box;
  box.volumetric = Volumetric::kNodalAverage;
  Host two(2);
  EXPECT_EQ(box.run(&two.services).positions, box.run(nullptr).positions);
}

TEST(ThreadedHyperelastic, TheTiledPassGivesTheSerialEnergyForcesAndTangent) {
  const KickedBox box;
  Host two(2);
  Options options;
  options.host = &two.services;
  options.tile_queries = true;  // queries stay in mesh order otherwise
  auto serial = make_model(box.mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true);
  auto tiled = make_model(box.mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, options);
  EXPECT_FALSE(serial->tiled());
  ASSERT_TRUE(tiled->tiled());
  const std::vector<double> x = testing::deformed_cube(box.mesh, 7, 0.002);
  const double energy = serial->elastic_energy(x.data());
  const double tiled_energy = tiled->elastic_energy(x.data());
  EXPECT_NEAR(tiled_energy, energy, 1e-13 * energy);
  // Summed per tile and then in tile order: the same bits every time and on any thread count.
  Host three(3);
  Options on_three = options;
  on_three.host = &three.services;
  EXPECT_EQ(tiled->elastic_energy(x.data()), tiled_energy);
  EXPECT_EQ(make_model(box.mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, on_three)
                ->elastic_energy(x.data()),
            tiled_energy);
  std::vector<double> forces(x.size()), tiled_forces(x.size());
  serial->internal_forces(x.data(), forces.data());
  tiled->internal_forces(x.data(), tiled_forces.data());
  double largest = 0.0;
  for (const double f : forces) largest = std::max(largest, std::abs(f));
  for (size_t k = 0; k < x.size(); ++k) ASSERT_NEAR(tiled_forces[k], forces[k], 1e-13 * largest);
  const std::span<const double> k_serial = serial->assemble_stiffness(x.data()).values();
  const std::span<const double> k_tiled = tiled->assemble_stiffness(x.data()).values();
  largest = 0.0;
  for (const double v : k_serial) largest = std::max(largest, std::abs(v));
  ASSERT_EQ(k_tiled.size(), k_serial.size());
  for (size_t k = 0; k < k_serial.size(); ++k)
    ASSERT_NEAR(k_tiled[k], k_serial[k], 1e-13 * largest);
}

TEST(ThreadedHyperelastic, AnInvertedElementIsReportedFromTheTiles) {
  const KickedBox box;
  Host two(2);
  // One free node on the top face pushed down through the layer below: its tets invert.
  uint32_t node = 0;
  for (uint32_t i = 0; i < box.mesh.node_count(); ++i)
    if (box.mesh.positions[3 * i + 2] > 0.069 && box.mesh.positions[3 * i] > 0.03 &&
        box.mesh.positions[3 * i + 1] > 0.03) {
      node = i;
      break;
    }
  ASSERT_GT(node, 0u);
  for (const tacta_host_services* host : {static_cast<const tacta_host_services*>(nullptr),
                                          static_cast<const tacta_host_services*>(&two.services)}) {
    Options options;
    options.host = host;
    auto model = make_model(box.mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, options);
    EXPECT_EQ(model->tiled(), host != nullptr);
    Body body(box.mesh);
    body.x[3 * node + 2] -= 0.025;  // m: past the node 1 cm below
    model->begin(body.state, 1e-3);
    EXPECT_NE(model->step(body.state, 1e-3) & TACTA_STEP_INVERTED_ELEMENT, 0u);
    EXPECT_EQ(model->counters().inverted_element_steps, 1u);
  }
}

// Two boxes stepped as the engine steps a group: one body per part of one parallel_for, so each
// model's own parallel_for runs serially inside its part.
struct GroupedBoxes {
  const KickedBox& box;
  const tacta_host_services* host;
  std::vector<double> positions[2];
  static void step_one(void* user, uint32_t begin, uint32_t end, uint32_t) {
    auto& g = *static_cast<GroupedBoxes*>(user);
    for (uint32_t b = begin; b < end; ++b) g.positions[b] = g.box.run(g.host).positions;
  }
};

TEST(ThreadedHyperelastic, ABodySteppedInAGroupRunsTheSerialStepBitForBit) {
  const KickedBox box;
  Host two(2);
  const std::vector<double> serial = box.run(nullptr).positions;
  GroupedBoxes group{box, &two.services, {}};
  two.pool.parallel_for(2, 1, &GroupedBoxes::step_one, &group);
  for (int b = 0; b < 2; ++b) EXPECT_EQ(group.positions[b], serial) << b;
  GroupedBoxes alone{box, &two.services, {}};  // a group of one: the workers are its own
  two.pool.parallel_for(1, 1, &GroupedBoxes::step_one, &alone);
  EXPECT_EQ(alone.positions[0], box.run(&two.services).positions);
  EXPECT_NE(alone.positions[0], serial);
}

TEST(ThreadedHyperelastic, SmallBodiesStepInMeshOrder) {
  // 3 x 3 x 3 cubes: 162 tets, 64 nodes: each colour of tiles would hold one, and the row
  // chunks start from 384 nodes.
  TestMesh mesh = box_tet_mesh({3, 3, 3}, {0.03, 0.03, 0.03}, 1000.0);
  mesh.fix_plane(2, 0.0);
  Host two(2);
  const auto run = [&](const tacta_host_services* host) {
    Options options;
    options.host = host;
    auto model = make_model(mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, options);
    Body body(mesh);
    for (uint32_t i = 0; i < mesh.node_count(); ++i) body.f[3 * i + 1] = -9.81 * mesh.masses[i];
    model->begin(body.state, 1e-3);
    for (int i = 0; i < 20; ++i) model->step(body.state, 1e-3);
    return body.x;
  };
  Options options;
  options.host = &two.services;
  EXPECT_FALSE(make_model(mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, options)->tiled());
  EXPECT_EQ(run(&two.services), run(nullptr));
}

TEST(ThreadedHyperelastic, StepsWithoutAllocating) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "malloc belongs to the sanitizer here";
  const KickedBox box;
  Host two(2);
  Options options;
  options.host = &two.services;
  auto model = make_model(box.mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, options);
  Body body(box.mesh);
  for (uint32_t i = 0; i < box.mesh.node_count(); ++i) {
    body.f[3 * i + 1] = -9.81 * box.mesh.masses[i];
    body.v[3 * i] = 3.0 * box.mesh.positions[3 * i + 2];
  }
  model->begin(body.state, 1e-3);
  model->step(body.state, 1e-3);  // the first step may size what it needs
  uint32_t bits = 0;
  EXPECT_EQ(allocations_in([&] {
              for (int i = 0; i < 20; ++i) bits |= model->step(body.state, 1e-3);
            }),
            0);
  EXPECT_EQ(bits & TACTA_STEP_FAULT_MASK, 0u);
  EXPECT_GT(allocations_in(
                [&] { make_model(box.mesh, MaterialLaw::kNeoHookean, 1e4, 0.4, true, options); }),
            0)
      << "the counter counts";
}

}  // namespace
}  // namespace tacta::models::hyperelastic
