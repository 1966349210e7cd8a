// The block incomplete Cholesky preconditioner and the CG that uses it: exact where IC(0) has no
// fill to drop (one tet), the same solution as sparse Cholesky on a bent beam's system in fewer
// iterations than block Jacobi, and the same trajectory as Cholesky when stepping. The LDL^T
// symbolic analysis gives Eigen's elimination tree and column counts. The batched element pass,
// a tet's node order, CG's adaptive guess and its force-scaled tolerance leave the motion as it
// was.
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>

#include "corotational_test_support.hpp"
#include "incomplete_cholesky.hpp"
#include "ldlt_symbolic.hpp"
#include "linear_solvers.hpp"
#include "padded_blocks.hpp"

namespace tacta::models::corotational {
namespace {

using sparse::BlockIncompleteCholesky;
using sparse::PaddedBlocks;
using testing::BodyState;
using testing::make_model;

// Writes the upper blocks of a dense symmetric matrix into a, whose pattern must hold them.
void fill_from_dense(BlockSparseMatrix& a, const Eigen::MatrixXd& dense) {
  const auto starts = a.row_starts();
  const auto columns = a.columns();
  for (uint32_t i = 0; i < a.node_count(); ++i)
    for (uint32_t k = starts[i]; k < starts[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) a.block(k)[3 * r + c] = dense(3 * i + r, 3 * columns[k] + c);
}

double relative_residual(const BlockSparseMatrix& a, const std::vector<double>& x,
                         const std::vector<double>& b) {
  std::vector<double> ax(b.size());
  a.multiply(x.data(), ax.data());
  double r2 = 0.0, b2 = 0.0;
  for (size_t i = 0; i < b.size(); ++i) {
    r2 += (b[i] - ax[i]) * (b[i] - ax[i]);
    b2 += b[i] * b[i];
  }
  return std::sqrt(r2 / b2);
}

TEST(BlockIncompleteCholesky, ExactWhenNothingIsDropped) {
  // One tet couples all four nodes: the pattern is full, IC(0) is the complete factorisation
  // and M^-1 r solves A z = r to rounding.
  const std::vector<uint32_t> tet = {0, 1, 2, 3};
  BlockSparseMatrix a(4, tet);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd g(12, 12);
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) g(i, j) = uniform(random);
  const Eigen::MatrixXd spd = g.transpose() * g + 0.5 * Eigen::MatrixXd::Identity(12, 12);
  fill_from_dense(a, spd);
  BlockIncompleteCholesky ic(a);
  EXPECT_EQ(ic.factorize(a), 0);
  // apply() works on 4 values per node, the fourth 0.
  std::vector<double> r4(16, 0.0), z4(16, 0.0), r(12), z(12);
  for (int i = 0; i < 12; ++i) r4[4 * (i / 3) + i % 3] = r[i] = uniform(random);
  ic.apply(r4.data(), z4.data());
  for (int i = 0; i < 12; ++i) z[i] = z4[4 * (i / 3) + i % 3];
  for (int node = 0; node < 4; ++node) EXPECT_EQ(z4[4 * node + 3], 0.0);
  EXPECT_LT(relative_residual(a, z, r), 1e-12);
}

// On the one-diagonal lattice: IC(0) there has no pivot breakdown and halves the iterations; on
// the symmetric split (issue 11) it replaced 7 pivots and took 88 iterations to block Jacobi's 167.
struct BeamSystem {
  TestMesh mesh = box_tet_mesh({3, 3, 12}, {0.03, 0.03, 0.3}, 1000.0, GridSplit::kOneDiagonal);
  BlockSparseMatrix matrix{0, {}};
  std::vector<double> rhs;
  BeamSystem() {
    mesh.fix_plane(2, 0.0);
    matrix = BlockSparseMatrix(mesh.node_count(), mesh.tets);
    // Bend the beam (u_y = 0.5 z^2, up to 4.5 cm at the tip) and take the implicit-Euler
    // matrix there: (1 + h alpha) M + (h beta + h^2) K, h = 1 ms, fixed nodes identity.
    std::vector<double> x = mesh.positions;
    for (uint32_t i = 0; i < mesh.node_count(); ++i)
      x[3 * i + 1] += 0.5 * x[3 * i + 2] * x[3 * i + 2];
    auto model = make_model(mesh, make_material(1e5, 0.45, 1000.0));
    const BlockSparseMatrix& k = model->assemble_stiffness(x.data());
    const double h = 1e-3, scale = h * 0.01 + h * h;
    for (size_t v = 0; v < k.values().size(); ++v) matrix.values()[v] = scale * k.values()[v];
    for (uint32_t i = 0; i < mesh.node_count(); ++i)
      for (int c = 0; c < 3; ++c) matrix.block(matrix.diagonal_block(i))[4 * c] += mesh.masses[i];
    matrix.apply_fixed(mesh.fixed);
    rhs.resize(3 * mesh.node_count());
    for (uint32_t i = 0; i < mesh.node_count(); ++i)
      for (int c = 0; c < 3; ++c)
        rhs[3 * i + c] = mesh.fixed[i] ? 0.0 : std::sin(0.7 * i + c) * mesh.masses[i];
  }
};

// Eigen's own analysis, with its elimination tree and column counts in view.
struct EigenAnalysis : Eigen::SimplicialLDLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>,
                                             Eigen::Upper, Eigen::NaturalOrdering<int>> {
  const VectorI& parent() const { return m_parent; }
  const VectorI& below() const { return m_nonZerosPerCol; }
};

TEST(LdltSymbolic, SameTreeAndColumnCountsAsEigen) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 60; ++trial) {
    // Random upper triangles, from a forest of a few entries to dense, with the diagonal.
    const int n = 1 + static_cast<int>(random() % 80);
    const double density = (trial % 6 + 1) / 12.0;
    std::bernoulli_distribution entry(density * density);
    std::vector<Eigen::Triplet<double, int>> upper;
    for (int c = 0; c < n; ++c)
      for (int r = 0; r <= c; ++r)
        if (r == c || entry(random)) upper.emplace_back(r, c, 1.0);
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> a(n, n);
    a.setFromTriplets(upper.begin(), upper.end());
    EigenAnalysis eigen;
    eigen.analyzePattern(a);
    std::vector<int> parent(n), below(n);
    sparse::ldlt_symbolic(n, a.outerIndexPtr(), a.innerIndexPtr(), parent, below);
    for (int j = 0; j < n; ++j) {
      ASSERT_EQ(parent[j], eigen.parent()[j]) << "trial " << trial << ", column " << j;
      ASSERT_EQ(below[j], eigen.below()[j]) << "trial " << trial << ", column " << j;
    }
  }
}

TEST(PaddedBlocks, ProductMatchesTheBlockMatrix) {
  BeamSystem system;
  const uint32_t nodes = system.mesh.node_count();
  PaddedBlocks padded(system.matrix);
  padded.assign(system.matrix.values());
  std::vector<double> x(3 * nodes), y(3 * nodes), x4(4 * nodes, 0.0), y4(4 * nodes, -1.0);
  for (uint32_t k = 0; k < 3 * nodes; ++k) x4[4 * (k / 3) + k % 3] = x[k] = std::cos(0.3 * k);
  const double dot = system.matrix.multiply(x.data(), y.data());
  const double dot4 = padded.multiply_symmetric(x4.data(), y4.data());
  double scale = 0.0;
  for (double v : y) scale = std::max(scale, std::abs(v));
  for (uint32_t k = 0; k < 3 * nodes; ++k)
    EXPECT_NEAR(y4[4 * (k / 3) + k % 3], y[k], 1e-13 * scale);
  for (uint32_t i = 0; i < nodes; ++i) EXPECT_EQ(y4[4 * i + 3], 0.0);
  EXPECT_NEAR(dot4, dot, 1e-12 * std::abs(dot));
}

TEST(ConjugateGradient, IncompleteCholeskyMatchesSparseCholeskyInFewerIterations) {
  BeamSystem system;
  const size_t n = system.rhs.size();
  std::vector<double> exact(n, 0.0), with_ic(n, 0.0), with_block_jacobi(n, 0.0);
  CholeskySolver cholesky(system.matrix);
  ASSERT_TRUE(cholesky.solve(system.matrix, system.rhs.data(), exact.data()));
  ConjugateGradientSolver ic(system.matrix, Preconditioner::kIncompleteCholesky, 1000, 1e-10);
  ConjugateGradientSolver block_jacobi(system.matrix, Preconditioner::kBlockJacobi, 1000, 1e-10);
  const SolveReport ic_report = ic.solve(system.matrix, system.rhs.data(), with_ic.data());
  const SolveReport bj_report =
      block_jacobi.solve(system.matrix, system.rhs.data(), with_block_jacobi.data());
  ASSERT_TRUE(ic_report.converged);
  ASSERT_TRUE(bj_report.converged);
  EXPECT_EQ(ic_report.replaced_pivots, 0);
  EXPECT_LE(ic_report.relative_residual, 1e-10);
  EXPECT_LT(relative_residual(system.matrix, with_ic, system.rhs), 1e-9);  // the true residual
  double difference2 = 0.0, norm2 = 0.0;
  for (size_t i = 0; i < n; ++i) {
    difference2 += (with_ic[i] - exact[i]) * (with_ic[i] - exact[i]);
    norm2 += exact[i] * exact[i];
  }
  EXPECT_LT(std::sqrt(difference2 / norm2), 1e-6);
  EXPECT_LT(2 * ic_report.iterations, bj_report.iterations)
      << "IC(0) " << ic_report.iterations << ", block Jacobi " << bj_report.iterations;
}

// A CG pass stopped by its cap goes on from where it got to: on the bent beam's system to 1e-10,
// a pass capped at a third of what CG needs from zero, then the restart, take about what one
// uncapped pass does (from zero again they would take a third more).
TEST(SafeSolver, RestartGoesOnFromWhereTheCappedPassStopped) {
  BeamSystem system;
  const size_t n = system.rhs.size();
  const auto solve = [&](int max_iterations, int restart_factor) {
    sparse::SolverOptions options;
    options.max_iterations = max_iterations;
    options.restart_factor = restart_factor;
    options.tolerance = 1e-10;
    options.fallback = SolverFallback::kRestartOnly;
    sparse::SafeSolver solver(system.matrix, options);
    std::vector<double> x(n, 0.0);
    const SolveReport report = solver.solve(system.matrix, system.rhs.data(), x.data());
    EXPECT_TRUE(report.converged);
    EXPECT_LT(relative_residual(system.matrix, x, system.rhs), 1e-9);
    return std::pair<SolveReport, uint64_t>{report, solver.counters().restarts};
  };
  const auto [whole, no_restarts] = solve(1000, 1);
  ASSERT_EQ(no_restarts, 0u);
  const int cap = whole.iterations / 3;
  const auto [capped, restarts] = solve(cap, 1000 / cap);
  ASSERT_EQ(restarts, 1u);
  EXPECT_LE(capped.iterations, whole.iterations + cap / 2)
      << "uncapped " << whole.iterations << ", capped at " << cap;
}

// The solver tests' beam: 2 x 2 x 8 cells, 0.02 x 0.02 x 0.2 m, rho 1000, held at z = 0.
TestMesh clamped_beam() {
  TestMesh mesh = box_tet_mesh({2, 2, 8}, {0.02, 0.02, 0.2}, 1000.0);
  mesh.fix_plane(2, 0.0);
  return mesh;
}

// Its material: E 1e5 Pa, nu 0.4, Rayleigh rayleigh_mass (1/s) and 0.01 s.
tacta_material beam_material(double rayleigh_mass) {
  tacta_material material = make_material(1e5, 0.4, 1000.0);
  material.rayleigh_mass = rayleigh_mass;
  material.rayleigh_stiffness = 0.01;
  return material;
}

// Tip displacement after 30 steps under gravity, with the given solver settings.
double tip_after_steps(const Options& options) {
  const TestMesh mesh = clamped_beam();
  const tacta_material material = beam_material(0.1);
  auto model = make_model(mesh, material, options);
  BodyState body(mesh);
  body.add_gravity(mesh, {0.0, -9.81, 0.0});
  model->begin(body.state, 1e-3);
  for (int i = 0; i < 30; ++i) EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
  const uint32_t tip = mesh.node_count() - 1;
  return body.positions[3 * tip + 1] - mesh.positions[3 * tip + 1];
}

TEST(CorotationalSolvers, IncompleteCholeskyStepsLikeSparseCholesky) {
  Options exact;
  exact.solver = LinearSolver::kCholesky;
  const double reference = tip_after_steps(exact);
  ASSERT_LT(reference, -1e-4);  // the tip has fallen
  for (int interval : {1, 5}) {
    Options ic;
    ic.preconditioner = Preconditioner::kIncompleteCholesky;
    ic.tolerance = 1e-10;
    ic.max_iterations = 500;
    ic.refactor_interval = interval;  // a stale factor still preconditions: same answer
    EXPECT_NEAR(tip_after_steps(ic), reference, 1e-6 * std::abs(reference)) << interval;
  }
}

// A clamped beam swinging under gravity after a sideways kick, 40 steps of 1 ms: where its
// nodes end, and the last step's polar iterations when asked.
std::vector<double> kicked_beam_positions(const TestMesh& mesh, const tacta_material& material,
                                          const Options& options,
                                          long* polar_iterations = nullptr) {
  auto model = make_model(mesh, material, options);
  BodyState body(mesh);
  body.add_gravity(mesh, {0.0, -9.81, 0.0});
  body.kick_sideways(mesh, 5.0);
  model->begin(body.state, 1e-3);
  for (int i = 0; i < 40; ++i) EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
  if (polar_iterations != nullptr) *polar_iterations = model->last_polar_iterations();
  return body.positions;
}

// step()'s element pass four tets at a time gives the trajectory of the one-at-a-time pass: a
// beam swinging under gravity with a sideways kick, 54 tets so that two go through the
// one-at-a-time path after the batches. With rotation svd the batch's Newton step finds U V^T
// of every tet with det F > 0 (the polar factor) to ~1e-12 rad, and the SVD does the others.
TEST(CorotationalSolvers, BatchedElementPassMatchesOneAtATime) {
  TestMesh mesh = box_tet_mesh({1, 1, 9}, {0.02, 0.02, 0.18}, 1000.0);
  mesh.fix_plane(2, 0.0);
  tacta_material material = make_material(2e4, 0.4, 1000.0);
  material.rayleigh_mass = 0.1;
  material.rayleigh_stiffness = 0.01;
  ASSERT_EQ(mesh.tets.size() / 4 % CorotationalFem::kBatchLanes, 2u);
  for (const RotationMethod rotation : {RotationMethod::kPolar, RotationMethod::kSvd}) {
    long polar_iterations = 0;
    auto run = [&](bool batched) {
      Options options;
      options.batch_elements = batched;
      options.rotation = rotation;
      options.solver = LinearSolver::kCholesky;
      return kicked_beam_positions(mesh, material, options, batched ? &polar_iterations : nullptr);
    };
    const std::vector<double> batched = run(true), single = run(false);
    double difference = 0.0, displacement = 0.0;
    for (size_t k = 0; k < batched.size(); ++k) {
      difference = std::max(difference, std::abs(batched[k] - single[k]));
      displacement = std::max(displacement, std::abs(single[k] - mesh.positions[k]));
    }
    const char* name = rotation == RotationMethod::kPolar ? "polar" : "svd";
    EXPECT_GT(displacement, 1e-3) << name;
    EXPECT_LT(difference, 1e-10 * displacement) << name;
    EXPECT_GT(polar_iterations, 0) << name;  // the batch ran its Newton step
  }
}

// An inverted tet under `svd` takes the SVD in the batched pass too: a beam whose free half is
// pushed through itself steps the same with the batch as one tet at a time, with the inverted
// flag raised by both.
TEST(CorotationalSolvers, BatchedSvdTakesTheSvdForInvertedTets) {
  TestMesh mesh = box_tet_mesh({1, 1, 9}, {0.02, 0.02, 0.18}, 1000.0);
  mesh.fix_plane(2, 0.0);
  const tacta_material material = make_material(2e4, 0.4, 1000.0);
  auto run = [&](bool batched, uint32_t& bits) {
    Options options;
    options.batch_elements = batched;
    options.rotation = RotationMethod::kSvd;
    options.solver = LinearSolver::kCholesky;
    auto model = make_model(mesh, material, options);
    BodyState body(mesh);
    // Every node past z = 0.09 m mirrored through that plane: the tets there turn inside out.
    for (uint32_t i = 0; i < mesh.node_count(); ++i)
      if (mesh.positions[3 * i + 2] > 0.09)
        body.positions[3 * i + 2] = 0.18 - mesh.positions[3 * i + 2];
    model->begin(body.state, 1e-3);
    bits = 0;
    for (int i = 0; i < 5; ++i) bits |= model->step(body.state, 1e-3);
    return body.positions;
  };
  uint32_t batched_bits = 0, single_bits = 0;
  const std::vector<double> batched = run(true, batched_bits), single = run(false, single_bits);
  EXPECT_NE(batched_bits & TACTA_STEP_INVERTED_ELEMENT, 0u);
  EXPECT_NE(single_bits & TACTA_STEP_INVERTED_ELEMENT, 0u);
  double difference = 0.0, motion = 0.0;
  for (size_t k = 0; k < batched.size(); ++k) {
    difference = std::max(difference, std::abs(batched[k] - single[k]));
    motion = std::max(motion, std::abs(single[k] - mesh.positions[k]));
  }
  EXPECT_GT(motion, 1e-3);
  EXPECT_LT(difference, 1e-9 * motion);
}

// The model keeps each tet's nodes in ascending order (so a pair's stored block is never
// transposed): the order a mesh file gives them in must not change the motion. The beam of the
// batched test, kicked, with every tet's last three nodes turned (an even permutation, so still
// positively oriented), steps as the mesh as built does, to rounding (the sums run in another
// order).
TEST(CorotationalSolvers, TetNodeOrderDoesNotChangeTheMotion) {
  TestMesh mesh = box_tet_mesh({1, 1, 9}, {0.02, 0.02, 0.18}, 1000.0);
  mesh.fix_plane(2, 0.0);
  TestMesh turned = mesh;
  size_t ascending = 0;
  for (size_t e = 0; e < turned.tets.size(); e += 4) {
    std::rotate(turned.tets.begin() + static_cast<std::ptrdiff_t>(e + 1),
                turned.tets.begin() + static_cast<std::ptrdiff_t>(e + 2),
                turned.tets.begin() + static_cast<std::ptrdiff_t>(e + 4));
    ascending += std::is_sorted(turned.tets.begin() + static_cast<std::ptrdiff_t>(e),
                                turned.tets.begin() + static_cast<std::ptrdiff_t>(e + 4));
  }
  ASSERT_LT(ascending, turned.tets.size() / 4);  // most turned tets' nodes do not ascend
  tacta_material material = make_material(2e4, 0.4, 1000.0);
  material.rayleigh_mass = 0.1;
  material.rayleigh_stiffness = 0.01;
  const auto run = [&](const TestMesh& m, bool batched) {
    Options options;
    options.batch_elements = batched;
    options.solver = LinearSolver::kCholesky;
    return kicked_beam_positions(m, material, options);
  };
  for (const bool batched : {true, false}) {
    const std::vector<double> built = run(mesh, batched), other = run(turned, batched);
    double difference = 0.0, displacement = 0.0;
    for (size_t k = 0; k < built.size(); ++k) {
      difference = std::max(difference, std::abs(built[k] - other[k]));
      displacement = std::max(displacement, std::abs(built[k] - mesh.positions[k]));
    }
    EXPECT_GT(displacement, 1e-3) << batched;
    EXPECT_LT(difference, 1e-10 * displacement) << batched;
  }
}

// The largest coordinate difference between two sets of node positions, m.
double largest_gap(const std::vector<double>& a, const std::vector<double>& b) {
  double gap = 0.0;
  for (size_t k = 0; k < a.size(); ++k) gap = std::max(gap, std::abs(a[k] - b[k]));
  return gap;
}

// Two CG settings against the direct solve on the same run: how far each ends from the direct
// solve's nodes (m), the direct run's displacement (m), and the CG iterations each counted.
struct AgainstDirect {
  double first_off = 0.0, second_off = 0.0, displacement = 0.0;
  uint64_t first_iterations = 0, second_iterations = 0;
};
// run(options, iterations) steps a model made with options and returns its node positions.
template <class Run>
AgainstDirect against_direct(const TestMesh& mesh, Run run, const Options& first,
                             const Options& second) {
  Options direct;
  direct.solver = LinearSolver::kCholesky;
  AgainstDirect r;
  uint64_t unused = 0;
  const std::vector<double> reference = run(direct, unused);
  r.first_off = largest_gap(run(first, r.first_iterations), reference);
  r.second_off = largest_gap(run(second, r.second_iterations), reference);
  r.displacement = largest_gap(reference, mesh.positions);
  return r;
}

// CG's adaptive guess (quadratic over three steps after a step where that missed by less)
// changes where CG starts, not what it converges to: a beam sagging and swinging under gravity
// follows the direct solve's path as closely as with the linear guess, in fewer iterations.
TEST(CorotationalSolvers, AdaptiveGuessFollowsTheDirectSolveInFewerIterations) {
  const TestMesh mesh = clamped_beam();
  const tacta_material material = beam_material(0.1);
  const auto run = [&](Options options, uint64_t& iterations) {
    auto model = make_model(mesh, material, options);
    BodyState body(mesh);
    body.add_gravity(mesh, {0.0, -9.81, 0.0});
    body.kick_sideways(mesh, 0.5);
    model->begin(body.state, 1e-3);
    for (int i = 0; i < 300; ++i)
      EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
    iterations = model->counters().cg_iterations;
    return body.positions;
  };
  Options adaptive, linear;
  linear.adaptive_guess = false;
  const AgainstDirect r = against_direct(mesh, run, adaptive, linear);
  EXPECT_GT(r.displacement, 1e-3);
  // 300 steps: linear 9,478 iterations, adaptive 3,916; both within 2e-6 of the motion.
  EXPECT_LT(r.first_iterations, r.second_iterations);
  // Each step's dv is solved to a relative residual of 1e-5 (the default tolerance): the path
  // may differ from the direct solve's by about that fraction of the motion.
  EXPECT_LT(r.first_off, 1e-5 * r.displacement) << "linear guess: " << r.second_off;
  EXPECT_LT(r.second_off, 1e-5 * r.displacement);
}

// Near equilibrium the step's rhs is what is left of forces that cancel. CG's tolerance taken
// relative to the larger of ||rhs|| and the step's force impulse (tolerance_scale: forces, the
// default) leaves an unbalanced force of at most 1e-5 of the forces in play; relative to ||rhs||
// alone it asks for ever more digits as the body comes to rest. A beam sagging under gravity and
// a tip load until it rests: both rest where the direct solve rests, the force scale in fewer
// iterations over the resting half.
TEST(CorotationalSolvers, ForceScaledToleranceRestsWhereTheDirectSolveRests) {
  const TestMesh mesh = clamped_beam();
  const tacta_material material = beam_material(5.0);  // damped to rest within the run
  const uint32_t tip = mesh.node_count() - 1;
  const auto run = [&](Options options, uint64_t& resting_iterations) {
    auto model = make_model(mesh, material, options);
    BodyState body(mesh);
    body.add_gravity(mesh, {0.0, -9.81, 0.0});
    body.external_forces[3 * tip] += 0.01;  // N, sideways at one tip node
    model->begin(body.state, 1e-3);
    for (int i = 0; i < 2000; ++i) {
      if (i == 1000) resting_iterations = model->counters().cg_iterations;
      EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
    }
    resting_iterations = model->counters().cg_iterations - resting_iterations;
    EXPECT_EQ(model->counters().unconverged, 0u);
    return body.positions;
  };
  Options forces, rhs;
  rhs.force_scaled_tolerance = false;
  const AgainstDirect r = against_direct(mesh, run, forces, rhs);
  std::printf(
      "at rest: displacement %.3e m; off the direct solve: forces %.3e m, rhs %.3e m; "
      "CG iterations over the last 1000 steps: forces %llu, rhs %llu\n",
      r.displacement, r.first_off, r.second_off,
      static_cast<unsigned long long>(r.first_iterations),
      static_cast<unsigned long long>(r.second_iterations));
  EXPECT_GT(r.displacement, 1e-3);
  EXPECT_LT(r.first_iterations, r.second_iterations);
  // An unbalanced force of 1e-5 of those in play moves the rest shape by about that fraction.
  EXPECT_LT(r.first_off, 1e-5 * r.displacement) << "rhs scale: " << r.second_off;
  EXPECT_LT(r.second_off, 1e-5 * r.displacement);
}

}  // namespace
}  // namespace tacta::models::corotational
