// Corotational linear tetrahedral FEM (the physics of the corotational_fem plugin).
//
// Each linear tet measures strain in its own rotated frame: eps = sym(R^T F - I) with R the
// element rotation (polar or SVD), stress sigma = lambda tr(eps) I + 2 mu eps, nodal force
// f_a = -V R sigma grad_a. Time integration: backward Euler linearised once per step,
//   ((1 + h alpha) M + (h beta + h^2) K) dv = h (f + f_ext - alpha M v) - h (beta + h) K v,
// with K = R K0 R^T per element, Rayleigh damping C = alpha M + beta K. The sparsity pattern is
// fixed at creation; step() refills values in place and allocates nothing.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "block_sparse.hpp"
#include "element_tiles.hpp"
#include "row_team.hpp"
#include "safe_solver.hpp"
#include "tacta/model_api.h"
#include "tacta/models/divergence_guard.hpp"
#include "tacta/models/state_blob.hpp"

namespace tacta::models::corotational {

using sparse::BlockSparseMatrix;
using sparse::CholeskySolver;
using sparse::ConjugateGradientSolver;
using sparse::LinearSolver;
using sparse::Preconditioner;
using sparse::SafeSolver;
using sparse::SolverCounters;
using sparse::SolveReport;
using sparse::SolverFallback;
using tacta::models::StateIo;

enum class RotationMethod { kPolar = 0, kSvd = 1 };
struct Options {
  RotationMethod rotation = RotationMethod::kPolar;
  LinearSolver solver = LinearSolver::kConjugateGradient;
  Preconditioner preconditioner = Preconditioner::kBlockJacobi;
  int max_iterations = 25;    // CG iterations per step
  double tolerance = 1e-5;    // CG: relative residual ||r|| / ||b||
  int refactor_interval = 1;  // incomplete Cholesky: steps between refactorisations
  // Unconverged CG: restart from zero with restart_factor x max_iterations, then (kDirect)
  // sparse LDL^T. A capped CG that is accepted unconverged lets errors pile up (SOFA's
  // cantilever collapsed at 0.44 s).
  SolverFallback fallback = SolverFallback::kDirect;
  int restart_factor = 8;
  // Static solve: each step finds equilibrium under the current loads and held nodes by Newton
  // iterations on the corotational forces (tangent: R K0 R^T), the load change since the last
  // equilibrium applied in load_steps increments, an increment halved when Newton fails.
  bool static_solve = false;
  int load_steps = 1;
  int static_iterations = 25;      // per increment, at most
  double static_tolerance = 1e-6;  // |f_int + f_ext| on free nodes <= this * the load scale
  // step()'s element pass four tets at a time (element_batch.cpp; either rotation); false:
  // one at a time, the reference the batched pass is tested against.
  bool batch_elements = true;
  // CG's guess (extrapolate_guess): adaptive, linear or quadratic as the last step scored; or
  // linear always (the guess of earlier releases).
  bool adaptive_guess = true;
  // CG's tolerance is relative to the larger of ||rhs|| and the step's force impulse
  // h (|f_int|^2 + |f_ext|^2)^1/2 over free nodes (forces), or to ||rhs|| alone (rhs: earlier
  // releases). Near equilibrium the rhs is what is left of forces that cancel, and a tolerance
  // on it alone asks for digits no force in the step has: the liver demo resting pressed ran
  // most solves to the iteration cap.
  bool force_scaled_tolerance = true;
  // The engine's parallel_for (model_api.h); with more than one worker the batched pass runs in
  // tiles of consecutive batches, colour by colour (no two tiles of a colour share a node), each
  // colour's tiles in parallel, and with threaded_solve, from kMinThreadedNodes nodes, the rest
  // of the step too: the matrix's zeroing, its product with v, the mass and the held nodes, the
  // rhs, the CG solve (block Jacobi or Jacobi) and the update of the state, on fixed row chunks
  // (sparse::RowTeam).
  const tacta_host_services* host = nullptr;
  // Taken only in the steps the body has the workers to itself (RowTeam::threaded); in a group
  // of bodies stepped one per thread the serial code runs, which is faster there.
  bool threaded_solve = true;
};

struct StaticCounters {
  uint64_t solves = 0, newton_iterations = 0, load_increments = 0, load_cuts = 0, unconverged = 0;
  double last_residual = 0.0;  // N
};

class CorotationalFem {
 public:
  static constexpr int kBatchLanes = 4;  // elements per batch in step()'s element pass
  // Nodes from which step()'s row passes and its solve run on the host's workers.
  static constexpr uint32_t kMinThreadedNodes = 384;

  // Throws std::invalid_argument naming the element or node at fault.
  CorotationalFem(const tacta_mesh_view& mesh, const tacta_material& material,
                  std::span<const double> masses, std::span<const uint8_t> fixed,
                  const Options& options);
  ~CorotationalFem();
  CorotationalFem(const CorotationalFem&) = delete;
  CorotationalFem& operator=(const CorotationalFem&) = delete;

  uint32_t step(tacta_body_state& state, double dt) noexcept;
  void begin(const tacta_body_state& state, double dt) noexcept;
  double elastic_energy(const double* positions) noexcept;
  void internal_forces(const double* positions, double* forces) noexcept;
  void node_stress(const double* positions, double* von_mises) noexcept;

  // K at these positions (no mass, no fixed-node projection), for tests; overwrites the matrix
  // the next step refills.
  const BlockSparseMatrix& assemble_stiffness(const double* positions) noexcept;
  SolveReport last_solve() const { return last_solve_; }
  const SolverCounters& counters() const { return solver_->counters(); }
  const StaticCounters& static_counters() const { return static_counters_; }
  // Polar iterations summed over elements in the last step (0 with the SVD).
  long last_polar_iterations() const { return polar_iterations_; }
  uint32_t node_count() const { return node_count_; }
  uint32_t element_count() const { return static_cast<uint32_t>(elements_.size()); }
  // Whether step()'s row passes and solve run on the host's workers.
  bool threaded() const { return rows_.threaded(); }
  // CG limits, and the incomplete Cholesky's steps between refactorisations.
  void set_solver_limits(int max_iterations, double tolerance, int refactor_interval);
  const Options& options() const { return options_; }
  // Checkpoints (state_blob.hpp): what step() reads that an earlier step wrote (warm-start
  // rotations, the CG guess's history, the static solve's last loads, the solver's state).
  void state_fields(StateIo& io);

 private:
  struct Element {
    uint32_t nodes[4];
    double gradients[4][3];    // grad N_a at rest, 1/m
    double volume;             // m^3
    double gradient_dots[10];  // grad N_a . grad N_b for a <= b, 1/m^2
  };
  struct ElementFrame {  // what one pass over an element computes
    Eigen::Matrix3d rotation;
    Eigen::Matrix3d stress;  // Pa, in the element's rotated frame
    Eigen::Vector3d rotated_gradients[4];
    bool inverted;
  };
  // guess: the polar iteration's warm start on entry, the element's rotation on exit.
  ElementFrame frame_of(uint32_t e, const double* positions, Eigen::Quaterniond& guess) noexcept;
  // Rest data and nodes of kBatchLanes consecutive elements, lane-minor (structure of arrays).
  struct ElementBatch {
    double gradients[4][3][kBatchLanes];  // 1/m
    double volume[kBatchLanes];           // m^3
    // The lanes' nodes, here rather than read from elements_: an Element is 200 bytes, so four
    // lanes' indices would cost four cache lines a batch (the pass's largest stall at 10k tets).
    uint32_t nodes[4][kBatchLanes];
  };
  void build_batches();
  // step()'s frame_of + accumulate for one batch, warm start and history included; returns
  // TACTA_STEP_INVERTED_ELEMENT if a lane is inverted.
  uint32_t step_batch(uint32_t batch, const double* positions, double scale,
                      long& polar_iterations) noexcept;
  // Cuts the batches into coloured tiles (parallel pass); leaves tiles_ empty when it would not
  // pay.
  void tile_batches();
  // The batched pass over every batch: in order, or colour by colour of tiles on the host's
  // workers.
  uint32_t batched_pass(const double* positions, double scale) noexcept;
  // step() between the element pass and the solve, on the host's workers (rows_): the rhs's
  // h (beta + h) K v, the mass and the held nodes into the matrix, the rhs, the CG guess.
  // Returns rhs_rows' sum over every node, in chunk order.
  double finish_system_threaded(const tacta_body_state& state, double h) noexcept;
  // The rhs of nodes [begin, end) (0 on held nodes) from forces_ and the stiffness-velocity
  // product; returns the sum of |f_int|^2 + |f_ext|^2 over those of them that are free, N^2.
  double rhs_rows(const tacta_body_state& state, double h, uint32_t begin, uint32_t end) noexcept;
  // step() after the solve, on the workers: v += dv (0 on held nodes), x += h v.
  void advance_threaded(tacta_body_state& state, double h) noexcept;
  // Static solve (corotational_static.cpp): Newton to equilibrium, load stepping.
  uint32_t solve_static(tacta_body_state& state) noexcept;
  // One increment's Newton iterations toward f_int(x) + loads_ = 0; true when converged.
  bool newton_to_equilibrium(double* positions, double tolerance) noexcept;
  // |f_int + loads_| over free nodes at positions; leaves the forces in forces_ and, when
  // with_matrix, K (fixed rows projected) in matrix_.
  double equilibrium_residual(const double* positions, bool with_matrix) noexcept;
  // CG's guess for entries [begin, end) of dv: extrapolated from the last steps' increments.
  void extrapolate_guess(size_t begin, size_t end) noexcept;
  // Adds to linear and quadratic the squared misses of the two guesses of this step, entries
  // [begin, end), once dv is solved, (m/s)^2.
  void score_guess(size_t begin, size_t end, double& linear, double& quadratic) const noexcept;
  // Adds K_e scaled by `scale` into matrix_, and f_e into forces.
  void accumulate(uint32_t e, const ElementFrame& frame, double scale, double* forces) noexcept;

  uint32_t node_count_;
  double lambda_, mu_;   // Pa
  double alpha_, beta_;  // Rayleigh: 1/s, s
  std::vector<Element> elements_;
  std::vector<ElementBatch> batches_;
  std::vector<double> rest_, masses_;
  std::vector<uint8_t> fixed_;
  Options options_;
  DivergenceGuard guard_;                        // NaN and runaway edge stretch
  std::vector<Eigen::Quaterniond> polar_guess_;  // warm start per element (queries)
  // step()'s own history, untouched by queries between steps: each element's last rotation
  // and the turn it made in the last step.
  std::vector<Eigen::Quaterniond> step_rotation_, step_turn_;
  BlockSparseMatrix matrix_;
  std::unique_ptr<SafeSolver> solver_;
  std::vector<double> forces_, stiffness_velocity_,  // stiffness_velocity_: h (beta + h) K v
      rhs_, delta_v_, previous_delta_v_, weights_;
  // CG's guess (extrapolate_guess): the increment two steps back, m/s, and this step's second
  // difference; the guess is quadratic while that scored better on the last step, else linear.
  std::vector<double> older_delta_v_, guess_curvature_;
  bool quadratic_guess_ = false;
  SolveReport last_solve_;
  StaticCounters static_counters_;
  std::vector<double> loads_, equilibrium_loads_, static_start_;  // static solve, 3 per node
  long polar_iterations_ = 0;
  sparse::ElementTiles tiles_;      // parallel pass: batches in tiles, tiles by colour
  struct alignas(64) WorkerTally {  // one cache line per worker: no false sharing
    uint32_t bits = 0;
    long polar_iterations = 0;
  };
  std::vector<WorkerTally> tallies_;
  sparse::OwnedSplit tile_split_;  // a colour's tiles, each worker its own share first
  sparse::RowTeam rows_;  // threaded row passes (none below kMinThreadedNodes or one worker)
};

}  // namespace tacta::models::corotational
