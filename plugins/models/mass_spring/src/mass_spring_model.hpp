// Mass-spring model (paper section 5). One spring per mesh edge: for tetrahedral meshes these
// are the structural edges plus the tets' face and body diagonals, which resist shear; no
// separate bending springs. Spring constants from E and nu by the options' stiffness rule
// (tacta/models/spring_stiffness.hpp): Van Gelder's E sum V / L^2 (default; nu ignored) or each
// tet's linear-FEM edge block projected on the spring. Springs have Poisson's ratio 1/4 whatever
// nu says (docs/VALIDATION.md, models that agree).
//
// Integrators: symplectic Euler (eqs. 26-27); Baraff-Witkin implicit Euler, one Newton step
// (eqs. 32-36) solved by preconditioned CG; Desbrun et al. (1999): the constant linear part
// M + dt^2 L_k (L_k the k-weighted graph Laplacian, the Jacobian of zero-rest-length springs)
// factorised once, the full non-linear force on the right-hand side, and an angular-momentum
// correction (a rigid rotation that removes the spin the linear filter adds).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "tacta/model_api.h"
#include "tacta/models/divergence_guard.hpp"
#include "tacta/models/spring_stiffness.hpp"

namespace tacta::models {

struct MassSpringOptions {
  enum class Integrator { kSymplecticEuler = 0, kImplicitEuler = 1, kDesbrun = 2 };
  Integrator integrator = Integrator::kSymplecticEuler;
  double damping = 0.0;            // N s/m per node, added to the material's alpha * m
  int cg_max_iterations = 200;     // Baraff-Witkin CG
  double cg_tolerance = 1e-8;      // relative residual
  bool desbrun_correction = true;  // Desbrun: remove the angular momentum the linear filter adds
  double divergence_stretch = DivergenceGuard::kDefaultStretchLimit;
  StiffnessRule stiffness_rule = StiffnessRule::kVanGelder;
};

// The springs and their forces; shared by the integrators.
struct SpringSet {
  std::vector<uint32_t> ends;       // 2 per spring
  std::vector<double> stiffness;    // N/m
  std::vector<double> rest_length;  // m
  size_t size() const { return stiffness.size(); }
  void forces(const double* positions, uint32_t node_count, double* out) const noexcept;
  double energy(const double* positions) const noexcept;
};

class BaraffWitkinSolver;
class DesbrunSolver;

class MassSpringModel {
 public:
  MassSpringModel(const tacta_model_setup& setup, const MassSpringOptions& options);
  ~MassSpringModel();
  MassSpringModel(const MassSpringModel&) = delete;
  MassSpringModel& operator=(const MassSpringModel&) = delete;

  uint32_t step(tacta_body_state& state, double dt) noexcept;
  double elastic_energy(const double* positions) const noexcept {
    return springs_.energy(positions);
  }
  void internal_forces(const double* positions, double* forces) const noexcept {
    springs_.forces(positions, node_count_, forces);
  }

  const SpringSet& springs() const { return springs_; }
  uint32_t node_count() const { return node_count_; }
  const std::vector<double>& masses() const { return mass_; }
  const std::vector<uint8_t>& fixed() const { return fixed_; }
  double damping_per_node(uint32_t i) const { return alpha_ * mass_[i] + options_.damping; }
  // s: the material's stiffness-proportional (Rayleigh) damping, C = alpha M + beta K. The
  // implicit integrators take it in their solve; symplectic Euler ignores it (an explicit
  // beta K v bounds the step by about 2 / (beta omega_max^2), far below the elastic limit).
  double stiffness_damping() const { return beta_; }
  const MassSpringOptions& options() const { return options_; }
  // Last Baraff-Witkin CG iteration count (0 for the other integrators).
  int last_cg_iterations() const;

 private:
  uint32_t step_symplectic(tacta_body_state& state, double dt) noexcept;

  MassSpringOptions options_;
  uint32_t node_count_ = 0;
  double alpha_ = 0;  // 1/s, material's mass-proportional damping
  double beta_ = 0;   // s, material's stiffness-proportional damping
  std::vector<double> mass_;
  std::vector<uint8_t> fixed_;
  SpringSet springs_;
  std::vector<double> force_;
  std::unique_ptr<BaraffWitkinSolver> baraff_witkin_;
  std::unique_ptr<DesbrunSolver> desbrun_;
  DivergenceGuard guard_;
};

}  // namespace tacta::models
