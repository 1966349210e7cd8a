// Vertex Block Descent (Chen, Macklin et al., "Vertex Block Descent", ACM TOG 43(4), SIGGRAPH
// 2024): backward Euler as the minimisation of the incremental potential
//   G(x) = 1/(2 h^2) |x - y|_M^2 + E(x) + D(x),   y = x_t + h v_t + h^2 M^-1 f_ext,
// one 3x3 Newton step per vertex at a time, Gauss-Seidel over a graph colouring (vertices of
// one colour share no tet, so each colour's updates are independent and run in parallel), with
// no global matrix. D is the damping potential: alpha m/(2h) |x - x_t|^2 (Rayleigh mass) plus
// beta/h times E's Bregman distance from x_t (Rayleigh stiffness: its gradient
// beta/h (grad E(x) - grad E(x_t)) is exactly beta K v_{t+1} for a quadratic E).
// Energies per linear tet: `corotational`, corotational_fem's V (mu eps:eps + lambda/2 tr^2 eps),
// eps = sym(R^T F) - I with R the polar rotation taken once per step at x_t (so the converged
// step is corotational_fem's linearised step); `neo_hookean`, hyperelastic's
// mu/2 (I1 - 3) - mu ln J + lambda/2 ln^2 J, its volume term continued below kMinVolumeRatio by
// its Taylor expansion (finite for crushed or inverted tets). Units: SI (m, s, kg, N, Pa, J).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <span>
#include <vector>

#include "tacta/model_api.h"
#include "tacta/models/divergence_guard.hpp"
#include "tacta/models/state_blob.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::vbd {

using tacta::models::StateIo;

enum class Energy { kCorotational = 0, kNeoHookean = 1 };                // scene choice order
enum class InitialGuess { kAdaptive = 0, kInertia = 1, kPrevious = 2 };  // scene choice order

struct Options {
  Energy energy = Energy::kCorotational;
  int iterations = 10;  // VBD iterations (sweeps over every colour) per step
  // Chebyshev acceleration's spectral radius estimate; 0: off. 0.85: the most accurate of
  // 0.7-0.95 at 10 iterations on a soft swinging beam with no energy gained in any step; 0.9 and
  // above gained energy there (VALIDATION.md, vbd).
  double chebyshev_rho = 0.85;
  InitialGuess initial_guess = InitialGuess::kAdaptive;
  const tacta_host_services* host = nullptr;  // parallel_for per colour; null: serial
};

class VbdModel {
 public:
  // Throws std::invalid_argument naming the tet or node at fault.
  VbdModel(const tacta_mesh_view& mesh, const tacta_material& material,
           std::span<const double> masses, std::span<const uint8_t> fixed, const Options& options);
  VbdModel(const VbdModel&) = delete;
  VbdModel& operator=(const VbdModel&) = delete;

  uint32_t step(tacta_body_state& state, double dt) noexcept;
  void begin(const tacta_body_state& state, double dt) noexcept;
  double elastic_energy(const double* positions) noexcept;
  void internal_forces(const double* positions, double* forces) noexcept;

  uint32_t node_count() const { return node_count_; }
  uint32_t colour_count() const { return static_cast<uint32_t>(colour_start_.size() - 1); }
  // Free vertices of colour c (fixed vertices are never updated and have no colour).
  std::span<const uint32_t> colour(uint32_t c) const {
    return {colour_vertices_.data() + colour_start_[c], colour_start_[c + 1] - colour_start_[c]};
  }
  const Options& options() const { return options_; }
  void set_iterations(int iterations) { options_.iterations = iterations; }
  void set_chebyshev_rho(double rho) { options_.chebyshev_rho = rho; }
  // Vertex updates skipped because their 3x3 block was singular, since create().
  uint64_t skipped_updates() const;
  uint32_t element_count() const { return static_cast<uint32_t>(tets_.size()); }
  // Checkpoints (state_blob.hpp): the warm-start rotations, the adaptive guess's v_{t-1} and
  // whether it is set, and the skipped-update count (loaded onto the first worker's tally: the
  // restored instance may have another number of workers).
  void state_fields(StateIo& io);

  // Below this fraction of the rest volume the Neo-Hookean volume term continues as its
  // quadratic Taylor expansion: the log barrier's local Newton steps overshoot there (a vertex
  // step moves J linearly), and an inverted tet (J <= 0) keeps a finite, restoring energy.
  static constexpr double kMinVolumeRatio = 0.1;

 private:
  // One incident tet of a vertex, with what the vertex's step needs of it at rest: laid out in
  // the vertex's CSR row, so a step reads its tets' rest data in one stream.
  struct Incidence {
    double gradient[3];  // grad N of the vertex's corner, 1/m
    double volume;       // m^3
    uint32_t tet;
    uint32_t corner;  // 0..3
  };
  // A tet's state over a step: R at x_t and F where the sweep evaluates forces (corotational:
  // R^T F, the strain's frame), together so a corner's evaluation touches one place.
  struct TetFrame {
    Eigen::Matrix3d deformation = Eigen::Matrix3d::Identity();
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  };
  struct VertexBlock {  // what one vertex's incident tets add to its force and Hessian
    Eigen::Vector3d force = Eigen::Vector3d::Zero();    // N, -dE/dx_i
    Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();  // N/m, d2E/dx_i^2 (PSD)
  };
  // Sums vertex i's elastic force (and, when with_hessian, its Hessian block) at the cached
  // deformation gradients of its tets.
  VertexBlock vertex_block(uint32_t i, bool with_hessian) const noexcept;
  // Every tet's F at positions + blend (positions - x_t) into the cache (blend 0: at positions);
  // refresh_deformation: tet e's.
  void refresh_deformations(const double* positions, double blend) noexcept;
  void refresh_deformation(uint32_t e, const double* positions, double blend) noexcept;
  // The Newton step of vertex i on G, applied to positions; skipped (and counted on the
  // worker's tally) when its block is singular.
  void update_vertex(uint32_t i, double* positions, uint32_t worker, bool first_iteration) noexcept;
  // Rotations of every tet at positions (corotational; warm-started from the last ones).
  void update_rotations(const double* positions) noexcept;
  // Runs body(i) for every index in [0, count) on the host's workers, or serially.
  template <class Body>
  void for_each(uint32_t count, uint32_t grain, Body&& body) noexcept;
  void build_incidence_and_colours(std::span<const uint8_t> fixed);
  Eigen::Matrix3d deformation(uint32_t tet, const double* positions) const noexcept;

  uint32_t node_count_;
  double lambda_, mu_;   // Pa
  double alpha_, beta_;  // Rayleigh: 1/s, s
  Options options_;
  std::vector<TetRest> tets_;
  std::vector<double> masses_;
  std::vector<uint8_t> fixed_;
  std::vector<uint32_t> incidence_start_;  // node_count + 1
  std::vector<Incidence> incidence_;
  std::vector<uint32_t> colour_start_, colour_vertices_;
  DivergenceGuard guard_;

  // Per step (sized at create; step() only writes into them).
  double h_ = 0.0;                                  // s
  std::vector<Eigen::Quaterniond> step_rotation_;   // per tet, warm start across steps
  std::vector<Eigen::Quaterniond> query_rotation_;  // per tet, for energy/force queries
  // Per tet: R at x_t, and F kept up to date by rank-one changes as the tet's corners move, so
  // a vertex step reads its tets' F instead of gathering four nodes.
  std::vector<TetFrame> frames_;
  std::vector<double> start_, inertia_target_;  // x_t, y: 3 per node, m
  std::vector<double> start_force_;             // Neo-Hookean: f_el(x_t), N

  std::vector<Eigen::Matrix3d> elastic_hessian_;          // corotational: per node, N/m
  std::vector<double> previous_velocity_;                 // v_{t-1}, m/s (adaptive guess)
  std::vector<double> chebyshev_prev_, chebyshev_prev2_;  // x^(k-1), x^(k-2), m
  struct alignas(64) WorkerTally {                        // one cache line per worker
    uint64_t skipped = 0;
  };
  std::vector<WorkerTally> tallies_;
  bool history_ = false;  // previous_velocity_ holds a real v_{t-1}
};

}  // namespace tacta::models::vbd
