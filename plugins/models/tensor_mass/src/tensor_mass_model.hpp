// Delingette et al.'s tensor-mass model (paper section 4): linear elasticity on tetrahedra with
// the stiffness stored along the mesh topology, K_ii per vertex and K_ij per edge:
//
//   K_jk(T) = V(T) [ lambda g_j g_k^T + mu g_k g_j^T + mu (g_j . g_k) I3 ]
//           = [ lambda m_j m_k^T + mu m_k m_j^T + mu (m_j . m_k) I3 ] / (36 V(T))
//   F_i = -( K_ii d_i + sum_{j in N(i)} K_ij d_j ),   d = x - x_rest                 (22)
//
// g_j are the shape-function gradients and m_j = -6 V g_j the paper's doubled face area
// vectors. (The summary prints lambda m_k m_j^T + mu m_j m_k^T: the transpose, i.e. K_kj; with
// F_i = -sum K_ij d_j the form above is the derivative of W = lambda/2 tr(e)^2 + mu tr(e^2).)
// Linear strain: a rigid rotation produces spurious forces growing with the angle (measured in
// the tests); valid for displacements up to about 10% of a cell.
//
// Integrators: central differences with damping gamma_i = alpha m_i + c (SEED_SUMMARY's
// corrected eq. 23), or implicit Euler with Rayleigh damping C = alpha M + beta K + c I, whose
// matrix M + dt C + dt^2 K is assembled from the same blocks and factorised once at create.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tacta/model_api.h"
#include "tacta/models/divergence_guard.hpp"
#include "tacta/models/state_blob.hpp"

namespace tacta::models {

struct TensorMassOptions {
  // kAuto: central differences when they are stable at the setup dt, implicit Euler otherwise.
  enum class Integrator { kCentralDifference = 0, kImplicitEuler = 1, kAuto = 2 };
  Integrator integrator = Integrator::kCentralDifference;
  double damping = 0.0;  // N s/m per node, added to the material's alpha * m
  double divergence_stretch = DivergenceGuard::kDefaultStretchLimit;
};

class ImplicitEulerSolver;  // tensor_mass_implicit.cpp

class TensorMassModel {
 public:
  TensorMassModel(const tacta_model_setup& setup, const TensorMassOptions& options);
  ~TensorMassModel();
  TensorMassModel(const TensorMassModel&) = delete;
  TensorMassModel& operator=(const TensorMassModel&) = delete;

  void begin(const tacta_body_state& state, double dt) noexcept;
  uint32_t step(tacta_body_state& state, double dt) noexcept;
  double elastic_energy(const double* positions) noexcept;
  void internal_forces(const double* positions, double* forces) const noexcept;

  // y = K u for a flat vector u (3 per node): the stiffness applied through the blocks.
  void apply_stiffness(const double* u, double* y) const noexcept;

  uint32_t node_count() const { return node_count_; }
  bool implicit() const { return implicit_ != nullptr; }
  // Central differences' stability limit, s: 2 / omega_max, omega_max^2 bounded by Gershgorin
  // (the largest row sum of |K| over free nodes divided by their mass); 0 when nothing is free.
  double central_difference_limit() const;
  // What the model chose for this body, for report.json (empty when the parameters said it).
  const std::string& note() const { return note_; }
  const std::vector<Eigen::Matrix3d>& vertex_blocks() const { return vertex_block_; }
  const std::vector<Eigen::Matrix3d>& edge_blocks() const { return edge_block_; }
  const std::vector<uint32_t>& edges() const { return edges_; }
  // Checkpoints (state_blob.hpp): central differences' x(t - dt) and whether it is set; the
  // implicit solver's factor is fixed at creation.
  void state_fields(StateIo& io) {
    io.vector(previous_, "previous_positions");
    io.value(has_history_, "has_history");
  }

 private:
  uint32_t step_central(tacta_body_state& state, double dt) noexcept;

  TensorMassOptions options_;
  uint32_t node_count_ = 0;
  std::vector<double> rest_, mass_, gamma_;  // m; kg; N s/m
  std::vector<uint8_t> fixed_;
  std::vector<uint32_t> edges_;                // 2 per edge (a < b)
  std::vector<Eigen::Matrix3d> vertex_block_;  // K_ii, N/m
  std::vector<Eigen::Matrix3d> edge_block_;    // K_ab for edge (a, b); K_ba = K_ab^T
  std::vector<double> previous_;               // central differences: x(t - dt)
  mutable std::vector<double> scratch_;        // displacement buffer for internal_forces()
  std::vector<double> force_;                  // 3 per node, N
  bool has_history_ = false;
  std::unique_ptr<ImplicitEulerSolver> implicit_;
  DivergenceGuard guard_;
  std::string note_;
};

}  // namespace tacta::models
