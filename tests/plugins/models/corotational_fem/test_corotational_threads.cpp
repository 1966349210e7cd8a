// The threaded paths (issue: every core used): the row-range products equal the serial ones to
// rounding; the threaded CG and a threaded corotational step equal the serial ones to rounding,
// repeat bit for bit at a fixed thread count and give the same bits on 2 and 3 threads (the row
// chunks and the colouring do not depend on the count); a threaded step allocates nothing; a body
// stepped in a group (one body per job) runs the serial step, bit for bit as without workers.
// The host services are the engine's JobPool, as the engine hands them to a plugin.
#include <algorithm>
#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <memory>
#include <vector>

#include "allocation_counter.hpp"  // the shared malloc interposer; off under the sanitizers
#include "corotational_test_support.hpp"
#include "linear_solvers.hpp"
#include "padded_blocks.hpp"
#include "services/job_pool.hpp"

namespace tacta::models::corotational {
namespace {

using sparse::PaddedBlocks;
using testing::BodyState;
using testing::make_model;

// The engine's host services over a pool of `threads`.
struct Host {
  explicit Host(uint32_t threads) : pool(threads) {}
  JobPool pool;
  tacta_host_services services = host_services(&pool, nullptr);
};

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// A clamped box of 7 x 7 x 7 cubes (2,058 tets, 512 nodes), soft, under gravity, kicked
// sideways: above the threaded thresholds, and its CG iterates.
struct KickedBox {
  TestMesh mesh = box_tet_mesh({7, 7, 7}, {0.07, 0.07, 0.07}, 1000.0);
  tacta_material material = make_material(1e4, 0.4, 1000.0);
  KickedBox() {
    mesh.fix_plane(2, 0.0);
    material.rayleigh_mass = 0.1;
    material.rayleigh_stiffness = 0.01;
  }
  // Positions after `steps` steps with the given host (null: serial).
  std::vector<double> run(const tacta_host_services* host, int steps = 30, bool* threaded = nullptr,
                          bool threaded_solve = true) const {
    Options options;
    options.host = host;
    options.threaded_solve = threaded_solve;
    auto model = make_model(mesh, material, options);
    if (threaded) *threaded = model->threaded();
    BodyState body(mesh);
    body.add_gravity(mesh, {0.0, -9.81, 0.0});
    body.kick_sideways(mesh, 3.0);
    model->begin(body.state, 1e-3);
    for (int i = 0; i < steps; ++i)
      EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
    return body.positions;
  }
};

// Two boxes stepped as the engine steps a group: one body per part of one parallel_for on the
// pool, so each model's own parallel_for runs serially inside its part.
struct GroupedBoxes {
  const KickedBox& box;
  const tacta_host_services* host;
  std::vector<double> positions[2];
  bool threaded[2] = {true, true};
  static void step_one(void* user, uint32_t begin, uint32_t end, uint32_t) {
    auto& g = *static_cast<GroupedBoxes*>(user);
    for (uint32_t b = begin; b < end; ++b) g.positions[b] = g.box.run(g.host, 30, &g.threaded[b]);
  }
};

// The stiffness of the kicked box at rest, with its mass: a system like step()'s.
struct BoxSystem {
  KickedBox box;
  std::unique_ptr<CorotationalFem> model = make_model(box.mesh, box.material);
  BlockSparseMatrix matrix{box.mesh.node_count(),
                           std::span<const uint32_t>(box.mesh.tets.data(), box.mesh.tets.size())};
  std::vector<double> rhs;
  BoxSystem() {
    const BlockSparseMatrix& k = model->assemble_stiffness(box.mesh.positions.data());
    std::copy(k.values().begin(), k.values().end(), matrix.values().begin());
    for (double& v : matrix.values()) v *= 1e-3 * 1e-3;
    matrix.add_to_diagonal(box.mesh.masses, 1.0);
    matrix.apply_fixed(box.mesh.fixed);
    rhs.resize(3 * size_t{box.mesh.node_count()});
    for (size_t k2 = 0; k2 < rhs.size(); ++k2)
      rhs[k2] = box.mesh.fixed[k2 / 3] ? 0.0 : std::sin(0.37 * static_cast<double>(k2)) * 1e-4;
  }
};

TEST(RowProducts, BlockMatrixRowsMatchTheSymmetricProduct) {
  BoxSystem system;
  const BlockSparseMatrix& a = system.matrix;
  const uint32_t nodes = a.node_count();
  std::vector<double> x(3 * size_t{nodes}), y(x.size()), y_rows(x.size(), -1.0);
  for (size_t k = 0; k < x.size(); ++k) x[k] = std::cos(0.3 * static_cast<double>(k));
  const double dot = a.multiply(x.data(), y.data());
  double dot_rows = 0.0;
  for (uint32_t begin = 0; begin < nodes; begin += 37)  // uneven ranges
    dot_rows += a.multiply_rows(x.data(), y_rows.data(), begin, std::min(nodes, begin + 37));
  const double scale = max_abs(y);
  for (size_t k = 0; k < y.size(); ++k) ASSERT_NEAR(y_rows[k], y[k], 1e-13 * scale) << k;
  EXPECT_NEAR(dot_rows, dot, 1e-12 * std::abs(dot));
  // Every off-diagonal block is in exactly one lower list.
  EXPECT_EQ(a.lower_starts().back(), a.block_count() - nodes);
}

TEST(RowProducts, PaddedRowsMatchAndFuseTheDirectionUpdate) {
  BoxSystem system;
  const uint32_t nodes = system.matrix.node_count();
  PaddedBlocks padded(system.matrix), by_rows(system.matrix);
  padded.assign(system.matrix.values());
  for (uint32_t begin = 0; begin < nodes; begin += 100)
    by_rows.assign_rows(system.matrix.values(), begin, std::min(nodes, begin + 100));
  std::vector<double> p(4 * size_t{nodes}, 0.0), z(p.size(), 0.0), q(p.size(), 0.0);
  for (uint32_t i = 0; i < nodes; ++i)
    for (int c = 0; c < 3; ++c) {
      p[4 * i + c] = std::cos(0.3 * (3 * i + c));
      z[4 * i + c] = std::sin(0.7 * (3 * i + c));
    }
  const double beta = 0.37;
  for (size_t k = 0; k < q.size(); ++k) q[k] = z[k] + beta * p[k];
  std::vector<double> y(p.size()), y_rows(p.size(), -1.0), q_out(p.size(), -1.0);
  const double dot = padded.multiply_symmetric(q.data(), y.data());
  double dot_rows = 0.0;
  for (uint32_t begin = 0; begin < nodes; begin += 61)
    dot_rows += by_rows.multiply_rows(p.data(), y_rows.data(), begin, std::min(nodes, begin + 61),
                                      z.data(), beta, q_out.data());
  const double scale = max_abs(y);
  for (uint32_t i = 0; i < nodes; ++i) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_NEAR(y_rows[4 * i + c], y[4 * i + c], 1e-13 * scale) << i;
      ASSERT_NEAR(q_out[4 * i + c], q[4 * i + c], 1e-15) << i;
    }
    EXPECT_EQ(y_rows[4 * i + 3], 0.0);
  }
  EXPECT_NEAR(dot_rows, dot, 1e-12 * std::abs(dot));
}

TEST(RowProducts, FinishRowsEqualsMassThenFixedBitForBit) {
  KickedBox box;
  auto model = make_model(box.mesh, box.material);
  const BlockSparseMatrix& k = model->assemble_stiffness(box.mesh.positions.data());
  BlockSparseMatrix serial = k, by_rows = k;
  serial.apply_fixed(box.mesh.fixed);  // the first call lists the blocks (at creation in a model)
  std::copy(k.values().begin(), k.values().end(), serial.values().begin());
  serial.add_to_diagonal(box.mesh.masses, 1.01);
  serial.apply_fixed(box.mesh.fixed);
  for (uint32_t begin = 0; begin < k.node_count(); begin += 50) {
    const uint32_t end = std::min(k.node_count(), begin + 50);
    by_rows.finish_rows(begin, end, box.mesh.masses, 1.01, box.mesh.fixed);
  }
  ASSERT_EQ(serial.values().size(), by_rows.values().size());
  EXPECT_TRUE(std::equal(serial.values().begin(), serial.values().end(), by_rows.values().begin()));
  BlockSparseMatrix zeroed = k;
  zeroed.zero_rows(0, 10);
  zeroed.zero_rows(10, k.node_count());
  EXPECT_EQ(max_abs(std::vector<double>(zeroed.values().begin(), zeroed.values().end())), 0.0);
}

TEST(ThreadedConjugateGradient, EqualsSerialToRoundingAndRepeatsBitForBit) {
  BoxSystem system;
  const size_t n = system.rhs.size();
  for (const Preconditioner preconditioner :
       {Preconditioner::kBlockJacobi, Preconditioner::kJacobi}) {
    const auto solve = [&](const tacta_host_services* host, SolveReport* report) {
      ConjugateGradientSolver cg(system.matrix, preconditioner, 200, 1e-9, 1, host);
      EXPECT_EQ(cg.threaded(), host != nullptr);
      std::vector<double> x(n, 0.0);
      // Twice: the second starts from the first's answer (a warm start), as steps do.
      *report = cg.solve(system.matrix, system.rhs.data(), x.data());
      for (double& v : x) v *= 0.9;
      *report = cg.solve(system.matrix, system.rhs.data(), x.data());
      return x;
    };
    SolveReport serial_report, report2, again2, report3;
    const std::vector<double> serial = solve(nullptr, &serial_report);
    Host two(2), three(3);
    const std::vector<double> threaded = solve(&two.services, &report2);
    const std::vector<double> repeated = solve(&two.services, &again2);
    const std::vector<double> on_three = solve(&three.services, &report3);
    ASSERT_TRUE(serial_report.converged);
    ASSERT_TRUE(report2.converged);
    EXPECT_LE(report2.relative_residual, 1e-9);
    EXPECT_NEAR(report2.iterations, serial_report.iterations, 1);
    const double scale = max_abs(serial);
    for (size_t k = 0; k < n; ++k) ASSERT_NEAR(threaded[k], serial[k], 1e-7 * scale) << k;
    EXPECT_EQ(threaded, repeated) << "two threads, twice";
    EXPECT_EQ(threaded, on_three) << "two and three threads";
    EXPECT_EQ(report2.iterations, report3.iterations);
  }
}

TEST(ThreadedConjugateGradient, SmallSystemsAndIncompleteCholeskyStaySerial) {
  Host two(2);
  TestMesh small = box_tet_mesh({3, 3, 3}, {0.03, 0.03, 0.03}, 1000.0);  // 64 nodes
  BlockSparseMatrix a(small.node_count(),
                      std::span<const uint32_t>(small.tets.data(), small.tets.size()));
  EXPECT_FALSE(ConjugateGradientSolver(a, Preconditioner::kBlockJacobi, 25, 1e-5, 1, &two.services)
                   .threaded());
  BoxSystem system;
  EXPECT_FALSE(ConjugateGradientSolver(system.matrix, Preconditioner::kIncompleteCholesky, 25, 1e-5,
                                       1, &two.services)
                   .threaded());
  Host one(1);
  EXPECT_FALSE(ConjugateGradientSolver(system.matrix, Preconditioner::kBlockJacobi, 25, 1e-5, 1,
                                       &one.services)
                   .threaded());
}

TEST(ThreadedCorotational, EqualsSerialToRoundingAndRepeatsBitForBit) {
  KickedBox box;
  bool threaded = false;
  const std::vector<double> serial = box.run(nullptr, 30, &threaded);
  EXPECT_FALSE(threaded);
  Host one(1), two(2), three(3);
  EXPECT_EQ(box.run(&one.services), serial) << "one thread is the serial code";
  const std::vector<double> on_two = box.run(&two.services, 30, &threaded);
  EXPECT_TRUE(threaded);
  double difference = 0.0, displacement = 0.0;
  for (size_t k = 0; k < serial.size(); ++k) {
    difference = std::max(difference, std::abs(on_two[k] - serial[k]));
    displacement = std::max(displacement, std::abs(serial[k] - box.mesh.positions[k]));
  }
  EXPECT_GT(displacement, 1e-3);
  // CG stops at a relative residual of 1e-5 either way: the two solutions differ by a small
  // part of that, not by the solver's tolerance.
  EXPECT_LT(difference, 1e-8 * displacement) << difference << " of " << displacement;
  EXPECT_EQ(box.run(&two.services), on_two) << "two threads, twice";
  EXPECT_EQ(box.run(&three.services), on_two) << "two and three threads";
  // With threaded_solve off only the element pass goes to the workers (in tiles): its own bits,
  // the same on 2 and 3 threads, within rounding of the serial run.
  Options colours_only;
  colours_only.host = &two.services;
  colours_only.threaded_solve = false;
  EXPECT_FALSE(make_model(box.mesh, box.material, colours_only)->threaded());
  const std::vector<double> tiles_two = box.run(&two.services, 30, nullptr, false);
  EXPECT_NE(tiles_two, serial) << "the tiled pass adds in another order";
  EXPECT_EQ(box.run(&three.services, 30, nullptr, false), tiles_two) << "two and three threads";
  difference = 0.0;
  for (size_t k = 0; k < serial.size(); ++k)
    difference = std::max(difference, std::abs(tiles_two[k] - serial[k]));
  EXPECT_LT(difference, 1e-8 * displacement) << difference << " of " << displacement;
}

TEST(ThreadedCorotational, ABodySteppedInAGroupRunsTheSerialStepBitForBit) {
  KickedBox box;
  Host two(2);
  const std::vector<double> serial = box.run(nullptr);
  GroupedBoxes group{box, &two.services, {}};
  two.pool.parallel_for(2, 1, &GroupedBoxes::step_one, &group);
  for (int b = 0; b < 2; ++b) {
    EXPECT_FALSE(group.threaded[b]) << b;
    // Inside a part the workers cannot spread: the element pass in order and the serial solve,
    // the bits of a body without workers, whichever thread the part ran on.
    EXPECT_EQ(group.positions[b], serial) << b;
  }
  // Alone (a group of one), the body has the workers again.
  GroupedBoxes alone{box, &two.services, {}};
  two.pool.parallel_for(1, 1, &GroupedBoxes::step_one, &alone);
  EXPECT_TRUE(alone.threaded[0]);
  EXPECT_EQ(alone.positions[0], box.run(&two.services)) << "alone: the threaded solve's bits";
}

// One model stepped alone, then inside a part of a split job, then alone again: each step asks
// where it runs (the threaded step alone, the serial one in the part), and the mixed run
// repeats bit for bit and stays within rounding of the threaded one.
struct SwitchingRun {
  const KickedBox& box;
  Host& host;
  bool threaded_alone = false, threaded_in_part = true;
  std::vector<double> run() {
    Options options;
    options.host = &host.services;
    auto model = make_model(box.mesh, box.material, options);  // threaded_solve by default
    BodyState body(box.mesh);
    body.add_gravity(box.mesh, {0.0, -9.81, 0.0});
    body.kick_sideways(box.mesh, 3.0);
    model->begin(body.state, 1e-3);
    const auto steps = [&](int n) {
      for (int i = 0; i < n; ++i)
        EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
    };
    steps(10);
    threaded_alone = model->threaded();
    std::function<void()> in_part = [&] {
      threaded_in_part = model->threaded();
      steps(10);
    };
    host.pool.parallel_for(
        2, 1,
        [](void* user, uint32_t begin, uint32_t, uint32_t) {
          if (begin == 0) (*static_cast<std::function<void()>*>(user))();  // 1: another body's
        },
        &in_part);
    steps(10);
    return body.positions;
  }
};

TEST(ThreadedCorotational, EachStepTakesThePathOfWhereItRuns) {
  KickedBox box;
  Host two(2);
  SwitchingRun switching{box, two};
  const std::vector<double> mixed = switching.run();
  EXPECT_TRUE(switching.threaded_alone);
  EXPECT_FALSE(switching.threaded_in_part);
  SwitchingRun again{box, two};
  EXPECT_EQ(again.run(), mixed) << "repeats bit for bit";
  const std::vector<double> threaded = box.run(&two.services);
  EXPECT_NE(mixed, threaded) << "the middle steps ran the serial step";
  double difference = 0.0, displacement = 0.0;
  for (size_t k = 0; k < mixed.size(); ++k) {
    difference = std::max(difference, std::abs(mixed[k] - threaded[k]));
    displacement = std::max(displacement, std::abs(threaded[k] - box.mesh.positions[k]));
  }
  EXPECT_LT(difference, 1e-8 * displacement) << difference << " of " << displacement;
}

TEST(ThreadedCorotational, StepsWithoutAllocating) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "malloc belongs to the sanitizer here";
  KickedBox box;
  Host two(2);
  Options options;
  options.host = &two.services;
  options.threaded_solve = true;
  auto model = make_model(box.mesh, box.material, options);
  ASSERT_TRUE(model->threaded());
  BodyState body(box.mesh);
  body.add_gravity(box.mesh, {0.0, -9.81, 0.0});
  model->begin(body.state, 1e-3);
  model->step(body.state, 1e-3);
  g_allocations = 0;
  g_counting = true;
  uint32_t bits = 0;
  for (int i = 0; i < 20; ++i) bits |= model->step(body.state, 1e-3);
  const long in_steps = g_allocations;
  auto another = make_model(box.mesh, box.material, options);  // the counter works
  g_counting = false;
  EXPECT_EQ(bits & TACTA_STEP_FAULT_MASK, 0u);
  EXPECT_EQ(in_steps, 0);
  EXPECT_GT(g_allocations, in_steps);
}

}  // namespace
}  // namespace tacta::models::corotational
