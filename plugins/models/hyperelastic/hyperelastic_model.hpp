// Hyperelastic tetrahedral FEM (the physics of the hyperelastic plugin): linear tets of a
// compressible Neo-Hookean, St Venant-Kirchhoff or Mooney-Rivlin material (stretch_energy.hpp),
// with a projected tangent that stays positive semi-definite through inversion.
//
// Dynamic steps: backward Euler as the minimisation of the incremental potential
//   Phi(x) = 1/2 |x - x_n - h v_n|_M^2 + h alpha/2 |x - x_n|_M^2 + h beta/2 |x - x_n|_Kd^2
//            + h^2 (W(x) - f_ext . x)
// (Rayleigh damping with Kd, the tangent at the step's first iterate), by Newton iterations
// with a backtracking (Armijo) line search on Phi; one iteration is the usual linearised step.
// Static solves: the same Newton on W(x) - f_ext . x, the change of load since the last
// equilibrium applied in load_steps increments, an increment halved when Newton fails.
// The sparsity pattern and every buffer are fixed at creation: step() allocates nothing.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "block_sparse.hpp"
#include "element_tiles.hpp"
#include "nodal_volume.hpp"
#include "row_team.hpp"
#include "safe_solver.hpp"
#include "stretch_energy.hpp"
#include "tacta/model_api.h"
#include "tacta/models/divergence_guard.hpp"
#include "tacta/models/state_blob.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::hyperelastic {

using tacta::models::StateIo;

enum class SolveMode { kDynamic = 0, kStatic = 1 };
// Where the volumetric energy is evaluated: per element (locks near nu 0.5), or on nodally
// averaged volumes (nodal_volume.hpp; neo_hookean and mooney_rivlin).
enum class Volumetric { kElement = 0, kNodalAverage = 1 };

struct Options {
  MaterialConstants material;
  bool project_tangent = true;  // false: the exact tangent (may be indefinite; tests)
  Volumetric volumetric = Volumetric::kElement;
  SolveMode mode = SolveMode::kDynamic;
  int newton_iterations = 3;  // dynamic: per step, at most
  // dynamic: steps whose first Newton correction reuses an earlier step's system matrix (its
  // tangent, preconditioner and Kd) before a fresh one is assembled; 0: fresh every step.
  int tangent_reuse_steps = 4;
  // dynamic: ... and while no element's F has changed by more than this (Frobenius norm) since.
  double tangent_reuse_change = 0.01;
  double newton_tolerance = 1e-3;  // dynamic: stop when |r| <= this * |r_0| (residual in N s^2)
  int load_steps = 1;              // static: increments of the load change per solve
  int static_iterations = 25;      // static: Newton iterations per increment, at most
  double static_tolerance = 1e-6;  // static: |f_int + f_ext| <= this * the load scale (N)
  int max_load_cuts = 8;           // static: halvings of a failed increment, at most
  sparse::SolverOptions solver;
  // The engine's parallel_for (model_api.h). With two or more workers, in the steps the body
  // has them to itself (not in a group), and per-element volumes: the element pass colour by
  // colour of tiles of elements (sparse::ElementTiles), and from 384 nodes the passes over the
  // matrix and a (block) Jacobi CG on row chunks (solver.host is set from it). One result on
  // any thread count, equal to the serial one to rounding. Nodal volumes keep the serial step.
  const tacta_host_services* host = nullptr;
  // Tests: the queries (elastic_energy, internal_forces, assemble_stiffness) on the tiles too.
  // Off, they run in mesh order: they may come from a thread other than the stepping one.
  bool tile_queries = false;
};

struct NewtonCounters {
  uint64_t steps = 0, newton_iterations = 0, line_search_backtracks = 0;
  uint64_t unconverged_steps = 0;  // dynamic: iterations ran out; static: cuts ran out
  uint64_t static_solves = 0, load_increments = 0, load_cuts = 0;
  uint64_t inverted_element_steps = 0;  // steps that ended with an inverted element
  uint64_t lagged_tangents = 0;         // dynamic: first corrections solved with a reused system
  double last_static_residual = 0.0;    // N: |f_int + f_ext| on the free nodes at the end
};

class HyperelasticModel {
 public:
  // Throws std::invalid_argument naming the element or node at fault.
  HyperelasticModel(const tacta_mesh_view& mesh, const tacta_material& material,
                    std::span<const double> masses, std::span<const uint8_t> fixed,
                    const Options& options);
  ~HyperelasticModel();
  HyperelasticModel(const HyperelasticModel&) = delete;
  HyperelasticModel& operator=(const HyperelasticModel&) = delete;

  uint32_t step(tacta_body_state& state, double dt) noexcept;
  void begin(const tacta_body_state& state, double dt) noexcept;
  double elastic_energy(const double* positions) noexcept;
  void internal_forces(const double* positions, double* forces) noexcept;
  void node_stress(const double* positions, double* von_mises) noexcept;
  // The tangent stiffness dF/dx (no mass, no fixed-node projection) at these positions, for
  // tests; overwrites the matrix the next step refills.
  const sparse::BlockSparseMatrix& assemble_stiffness(const double* positions) noexcept;

  const NewtonCounters& counters() const { return counters_; }
  const sparse::SolverCounters& solver_counters() const { return solver_->counters(); }
  const Options& options() const { return options_; }
  uint32_t node_count() const { return node_count_; }
  uint32_t element_count() const { return static_cast<uint32_t>(elements_.size()); }
  // Whether the element pass runs in tiles on the host's workers (in the steps the body has
  // them to itself): two or more workers, per-element volumes, a body of a few hundred tets.
  bool tiled() const { return !tiles_.empty(); }
  // Checkpoints (state_blob.hpp): the counters, the next step's first guess, the static solve's
  // last loads, and the lagged system (A, Kd, the F it was assembled at, its age, the solver's
  // preconditioner) that a later step's first correction may reuse.
  void state_fields(StateIo& io);

 private:
  using Element = TetRest;  // nodes, rest gradients (1/m), volume (m^3)
  // One pass over the elements at x: returns W (J); adds internal forces into forces (if not
  // null) and scale * K into matrix_ (if scale != 0); sets inverted_ when an element is.
  double element_pass(const double* x, double* forces, double scale) noexcept;
  // What an element pass gathers besides forces and matrix blocks.
  struct PassTally {
    double energy = 0.0;  // J
    double change = 0.0;  // the largest |F - assembled F|^2 met (track_change_)
    bool inverted = false;
  };
  // Element e's share of element_pass into tally; false when track_change_ has just ruled the
  // lagged system out (the pass may stop there: its forces are then not needed).
  bool add_element(uint32_t e, const double* x, double* forces, double scale,
                   PassTally& tally) noexcept;
  // Threaded element pass (parallel_pass.cpp): the elements in coloured tiles of
  // kElementsPerTile (a few to tens of microseconds each); tile_elements() leaves tiles_ empty
  // where that would not pay.
  static constexpr uint32_t kElementsPerTile = 64;
  void tile_elements(const double* rest_positions);
  // element_pass's loop over the elements, colour by colour of tiles on the host's workers;
  // the energy is summed per tile and then in tile order (the same bits on any thread count).
  void tiled_elements(const double* x, double* forces, double scale, PassTally& tally) noexcept;
  // Newton on Phi with weights (inertia a, mass damping b, stiffness damping c, potential s);
  // x holds the first iterate and the result. Returns true when converged.
  struct Objective {
    double inertia, mass_damping, stiffness_damping, potential;
    const double* predicted;    // x_n + h v_n (inertia)
    const double* start;        // x_n (damping)
    const double* loads;        // N
    const double* first_guess;  // the first correction's CG guess, or null for zero
    int max_iterations;
    double relative_tolerance, absolute_tolerance;  // on |r|, in the residual's units
    bool reuse_system;  // dynamic: the first correction may use the lagged system matrix
  };
  bool newton(const Objective& objective, double* x) noexcept;
  // Phi at x, given the element energy and forces_ at x; writes -grad Phi (zero on fixed
  // nodes) to residual and its norm. Leaves scratch_ = x - x_n and product_ = Kd scratch_.
  double measure_at(const Objective& objective, const double* x, double energy, double* residual,
                    double& residual_norm) noexcept;
  // The passes over the whole system matrix, on row chunks (rows_) when the body has the
  // workers to itself, else in order; the first three give the serial code's bits, the product
  // equals it to rounding. matrix_ zeroed:
  void zero_system() noexcept;
  // damping_ = matrix_ / potential (Kd: the tangent at the step's first iterate).
  void store_damping(double potential) noexcept;
  // A = (a + b) M + c Kd + s K(x): matrix_ holds s K(x); held nodes' rows and columns identity.
  void finish_system(const Objective& objective) noexcept;
  // s . Kd s into product_ = Kd s, s = scratch_ (measure_at's one matrix product).
  double damping_product() noexcept;
  uint32_t step_dynamic(tacta_body_state& state, double h) noexcept;
  uint32_t solve_static(tacta_body_state& state) noexcept;

  uint32_t node_count_;
  std::vector<Element> elements_;
  std::vector<double> masses_;
  std::vector<uint8_t> fixed_;
  Options options_;
  MaterialConstants element_material_;      // the law, less its volumetric term when that is nodal
  std::unique_ptr<NodalVolumeTerm> nodal_;  // null: the volumetric term stays per element
  DivergenceGuard guard_;
  sparse::BlockSparseMatrix matrix_, damping_;
  std::unique_ptr<sparse::SafeSolver> solver_;
  // 3 per node: forces, residual, Newton correction, predicted and start positions, the trial
  // point of the line search and its residual, the loads applied, the last equilibrium's loads
  // and scratch.
  std::vector<double> forces_, residual_, correction_, predicted_, start_, trial_, loads_,
      equilibrium_loads_, scratch_, product_, last_correction_, trial_residual_;
  std::vector<double> weights_;  // node_stress: volume per node
  NewtonCounters counters_;
  double rayleigh_mass_, rayleigh_stiffness_;  // alpha (1/s), beta (s)
  bool inverted_ = false;
  // matrix_ holds a complete system A (with Kd, masses, fixed rows) for the step h
  // system_step_, reused by system_age_ steps since its assembly.
  bool system_valid_ = false;
  // F per element at the first iterate of the last fresh assembly (Kd's), and the largest
  // |F - that|^2 a force pass met while track_change_ is set (which stops the pass once it
  // exceeds tangent_reuse_change^2: its forces are then incomplete).
  std::vector<Eigen::Matrix3d> assembled_deformation_;
  bool record_deformation_ = false, track_change_ = false;
  double deformation_change_ = 0.0;
  int system_age_ = 0;
  double system_step_ = 0.0;          // s
  bool linear_solve_failed_ = false;  // in this step
  bool stepping_ = false;             // inside step(): the element pass may use the tiles
  // The threaded element pass: the tiles, each tile's energy, per worker what it met (one
  // cache line each), and a flag that stops the pass once track_change_ rules the system out.
  sparse::ElementTiles tiles_;
  std::vector<double> tile_energy_;
  struct alignas(64) WorkerTally {
    double change = 0.0;
    bool inverted = false;
  };
  std::vector<WorkerTally> tallies_;
  sparse::OwnedSplit tile_split_;
  std::atomic<bool> stop_pass_{false};
  sparse::RowTeam rows_;  // the matrix passes on row chunks (none below 384 nodes or 1 worker)
};

}  // namespace tacta::models::hyperelastic
