// Bullet's btSoftBody on a Tacta tet mesh: a reference peer to compare the other models with,
// not a haptic model (Bullet's step allocates and its stiffness is not a physical modulus).
//
// Mesh: one Bullet node per mesh node (mass from the engine's lumped masses; fixed nodes get
// mass 0, which Bullet treats as immovable), one link per mesh edge, one tetra per tet.
// Gravity and contact come from the engine's external forces (Bullet's own gravity is zero).
//
// Material rule (Bullet's kLST is a per-iteration position-correction fraction in [0, 1], not
// a modulus): each link has its own Bullet material. Its spring constant k_e comes from E and nu
// by the stiffness rule mass_spring uses (tacta/models/spring_stiffness.hpp). An implicit spring
// of stiffness k between masses of reduced mass m closes the fraction s = k dt^2 / (m + k dt^2)
// of its error in one step; n position iterations of fraction f close 1 - (1 - f)^n; so
// kLST_e = 1 - (1 - s_e)^(1/n). Damping: kDP = 1 - exp(-alpha dt) with alpha the Rayleigh mass
// coefficient (Bullet's kDP removes that fraction of velocity per step).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "tacta/model_api.h"
#include "tacta/models/divergence_guard.hpp"
#include "tacta/models/spring_stiffness.hpp"

class btSoftBody;

namespace tacta::models::bullet {

struct Options {
  int position_iterations = 10;     // Bullet's m_cfg.piterations
  double stiffness_override = 0.0;  // kLST in (0, 1]; 0: derive it from E by the rule above
  bool bending = false;             // add Bullet's distance-2 bending links
  StiffnessRule stiffness_rule = StiffnessRule::kVanGelder;  // spring constant per edge
};

// The kLST of every mesh edge's link (same order as mesh.edges) by the rule above.
std::vector<double> link_stiffness_from_material(const tacta_mesh_view& mesh,
                                                 std::span<const double> masses,
                                                 const tacta_material& material, StiffnessRule rule,
                                                 double dt, int position_iterations);

// Substeps per step so that every link's k (dt / n)^2 / m_reduced is at most kStiffnessDt2. A
// position projection behaves as a spring only as k h^2 / m -> 0: it cannot close more than all
// of a link's error per step, so links stiffer than m / h^2 saturate (a 2x2x6-cell beam of E 2 MPa
// at 1 ms settled 1.86x lower than mass_spring's whatever the iterations), and at k h^2 / m = x
// the per-link calibration x / (1 + x) leaves the network up to ln(1 + x) / x as stiff (the
// 8x1x1 beam_under_gravity at x < 1: 14 % softer than mass_spring; at 8 kHz 0.4 %).
inline constexpr double kStiffnessDt2 = 1.0 / 16.0;
inline constexpr int kMaxSubsteps = 64;
int substeps_for(const tacta_mesh_view& mesh, std::span<const double> masses,
                 const tacta_material& material, StiffnessRule rule, double dt);

class BulletSoftBody {
 public:
  BulletSoftBody(const tacta_mesh_view& mesh, const tacta_material& material,
                 std::span<const double> masses, std::span<const uint8_t> fixed, double dt,
                 const Options& options);
  ~BulletSoftBody();
  BulletSoftBody(const BulletSoftBody&) = delete;
  BulletSoftBody& operator=(const BulletSoftBody&) = delete;

  // Copies positions and velocities into Bullet, applies external forces, steps, copies back.
  uint32_t step(tacta_body_state& state, double dt) noexcept;
  // kLST of each link, in mesh.edges order.
  const std::vector<double>& link_stiffness() const { return link_stiffness_; }
  int substeps() const { return substeps_; }

 private:
  struct World;
  std::unique_ptr<World> world_;
  btSoftBody* body_ = nullptr;  // owned by world_
  std::vector<uint8_t> fixed_;
  std::vector<double> rest_;
  std::vector<double> link_stiffness_;
  double alpha_ = 0.0;     // Rayleigh mass damping, 1/s
  int substeps_ = 1;       // Bullet steps per step (substeps_for)
  DivergenceGuard guard_;  // NaN and runaway edge stretch
};

}  // namespace tacta::models::bullet
