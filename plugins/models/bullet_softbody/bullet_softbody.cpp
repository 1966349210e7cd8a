#include "bullet_softbody.hpp"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::bullet {

namespace {
double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}
}  // namespace

struct BulletSoftBody::World {
  btSoftBodyRigidBodyCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  btSoftBodyWorldInfo info;
  std::unique_ptr<btSoftBody> body;
  ~World() {
    if (body) world.removeSoftBody(body.get());
  }
};

namespace {
// k_e dt^2 / m_reduced of each mesh edge's spring (N/m from the rule), -1 where both ends are held.
std::vector<double> stiffness_dt2(const tacta_mesh_view& mesh, std::span<const double> masses,
                                  const tacta_material& material, StiffnessRule rule, double dt) {
  const std::vector<double> spring =
      edge_stiffness("bullet_softbody", mesh, material, rule);  // N/m
  std::vector<double> out(mesh.edge_count);
  for (uint32_t e = 0; e < mesh.edge_count; ++e) {
    const double inverse_mass_sum =
        (masses[mesh.edges[2 * e]] > 0 ? 1 / masses[mesh.edges[2 * e]] : 0) +
        (masses[mesh.edges[2 * e + 1]] > 0 ? 1 / masses[mesh.edges[2 * e + 1]] : 0);
    out[e] = inverse_mass_sum > 0 ? spring[e] * dt * dt * inverse_mass_sum : -1.0;
  }
  return out;
}
}  // namespace

std::vector<double> link_stiffness_from_material(const tacta_mesh_view& mesh,
                                                 std::span<const double> masses,
                                                 const tacta_material& material, StiffnessRule rule,
                                                 double dt, int position_iterations) {
  const std::vector<double> k_dt2 = stiffness_dt2(mesh, masses, material, rule, dt);
  std::vector<double> fraction(mesh.edge_count);
  for (uint32_t e = 0; e < mesh.edge_count; ++e) {
    if (k_dt2[e] < 0) {  // both ends held: Bullet never moves it
      fraction[e] = 1.0;
      continue;
    }
    const double closed_per_step = k_dt2[e] / (1.0 + k_dt2[e]);
    const double per_iteration = 1.0 - std::pow(1.0 - closed_per_step, 1.0 / position_iterations);
    fraction[e] = std::clamp(per_iteration, 1e-6, 1.0);  // Bullet divides by kLST
  }
  return fraction;
}

int substeps_for(const tacta_mesh_view& mesh, std::span<const double> masses,
                 const tacta_material& material, StiffnessRule rule, double dt) {
  const std::vector<double> k_dt2 = stiffness_dt2(mesh, masses, material, rule, dt);
  const double stiffest = k_dt2.empty() ? 0.0 : *std::max_element(k_dt2.begin(), k_dt2.end());
  // (dt / n)^2 k / m <= kStiffnessDt2: n >= sqrt(k dt^2 / m / kStiffnessDt2).
  return std::clamp(static_cast<int>(std::ceil(std::sqrt(std::max(stiffest, 0.0) / kStiffnessDt2))),
                    1, kMaxSubsteps);
}

BulletSoftBody::BulletSoftBody(const tacta_mesh_view& mesh, const tacta_material& material,
                               std::span<const double> masses, std::span<const uint8_t> fixed,
                               double dt, const Options& options)
    : world_(std::make_unique<World>()),
      fixed_(fixed.begin(), fixed.end()),
      rest_(mesh.rest_positions, mesh.rest_positions + 3 * size_t{mesh.node_count}),
      alpha_(material.rayleigh_mass),
      guard_(mesh) {
  if (mesh.node_count == 0 || mesh.edge_count == 0)
    throw std::invalid_argument("bullet_softbody needs a mesh with nodes and edges");
  if (masses.size() != mesh.node_count)
    throw std::invalid_argument("bullet_softbody: expected one mass per node");
  if (!(dt > 0.0)) throw std::invalid_argument("bullet_softbody: dt must be positive");
  World& w = *world_;
  w.info.m_gravity.setZero();  // the engine's external forces already hold m g
  w.info.m_broadphase = &w.broadphase;
  w.info.m_dispatcher = &w.dispatcher;
  w.info.m_sparsesdf.Initialize();
  w.world.setGravity(btVector3(0, 0, 0));
  std::vector<btVector3> x(mesh.node_count);
  std::vector<btScalar> m(mesh.node_count);
  for (uint32_t i = 0; i < mesh.node_count; ++i) {
    x[i] = btVector3(rest_[3 * i], rest_[3 * i + 1], rest_[3 * i + 2]);
    const bool held = !fixed_.empty() && fixed_[i];
    if (!held && !(masses[i] > 0.0))
      throw std::invalid_argument("bullet_softbody: node " + std::to_string(i) +
                                  " is free but has mass " + std::to_string(masses[i]) + " kg");
    m[i] = held ? 0.0 : masses[i];
  }
  w.body =
      std::make_unique<btSoftBody>(&w.info, static_cast<int>(mesh.node_count), x.data(), m.data());
  body_ = w.body.get();
  // A held node is an infinite mass to Bullet (inverse mass 0), so the rule must see it so: with
  // its lumped mass instead, a link to the clamp closed its error as if shared with a node that
  // never moves, about twice too stiff (a 2x2x6-cell cantilever settled 0.80x mass_spring's).
  std::vector<double> moving_masses(masses.begin(), masses.end());
  for (uint32_t i = 0; i < mesh.node_count; ++i)
    if (!fixed_.empty() && fixed_[i]) moving_masses[i] = 0.0;
  substeps_ = options.stiffness_override > 0.0
                  ? 1
                  : substeps_for(mesh, moving_masses, material, options.stiffness_rule, dt);
  const double substep = dt / substeps_;
  link_stiffness_ =
      options.stiffness_override > 0.0
          ? std::vector<double>(mesh.edge_count, options.stiffness_override)
          : link_stiffness_from_material(mesh, moving_masses, material, options.stiffness_rule,
                                         substep, options.position_iterations);
  for (uint32_t e = 0; e < mesh.edge_count; ++e) {
    const uint32_t i = mesh.edges[2 * e], j = mesh.edges[2 * e + 1];
    if (i >= mesh.node_count || j >= mesh.node_count)
      throw std::invalid_argument("bullet_softbody: edge " + std::to_string(e) +
                                  " names a node past " + std::to_string(mesh.node_count));
    btSoftBody::Material* link_material = body_->appendMaterial();  // kLST is per material
    link_material->m_kLST = link_material->m_kAST = link_material->m_kVST = link_stiffness_[e];
    body_->appendLink(static_cast<int>(i), static_cast<int>(j), link_material);
  }
  for (uint32_t t = 0; t < mesh.tet_count; ++t) {
    const uint32_t* n = mesh.tets + 4 * t;
    body_->appendTetra(static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2]),
                       static_cast<int>(n[3]));
  }
  btSoftBody::Material* bullet_material = body_->m_materials[0];  // bending links' material
  bullet_material->m_kLST = bullet_material->m_kAST = bullet_material->m_kVST =
      median(link_stiffness_);
  if (options.bending) body_->generateBendingConstraints(2, bullet_material);
  body_->m_cfg.piterations = options.position_iterations;
  body_->m_cfg.kDP = std::clamp(1.0 - std::exp(-alpha_ * substep), 0.0, 1.0);
  body_->m_cfg.collisions = 0;  // no colliders here: contact reaches us as external forces
  // Bullet computes its runtime constants, the links' rest lengths among them, at the first
  // predictMotion from the nodes' positions *then*, which step() has just overwritten with the
  // state's: a body whose first step started deformed took that shape as its rest (a 1 % stretch
  // gave 0 N, `tacta check-plugin`). Computed here, from the rest positions, and not again.
  body_->updateConstants();
  body_->m_bUpdateRtCst = false;
  w.world.addSoftBody(body_);
}

BulletSoftBody::~BulletSoftBody() = default;

uint32_t BulletSoftBody::step(tacta_body_state& state, double dt) noexcept {
  const int count = body_->m_nodes.size();
  for (int i = 0; i < count; ++i) {
    btSoftBody::Node& node = body_->m_nodes[i];
    const double* x = state.positions + 3 * i;
    const double* v = state.velocities + 3 * i;
    node.m_x = btVector3(x[0], x[1], x[2]);
    node.m_q = node.m_x;
    node.m_v = btVector3(v[0], v[1], v[2]);
  }
  const double substep = dt / substeps_;
  for (int k = 0; k < substeps_; ++k) {
    for (int i = 0; i < count; ++i) {  // Bullet clears the forces after each of its steps
      btSoftBody::Node& node = body_->m_nodes[i];
      const double* f = state.external_forces + 3 * i;
      node.m_f = node.m_im > 0.0 ? btVector3(f[0], f[1], f[2]) : btVector3(0, 0, 0);
    }
    world_->world.stepSimulation(substep, 0, substep);
  }
  for (int i = 0; i < count; ++i) {
    const btSoftBody::Node& node = body_->m_nodes[i];
    const bool held = !fixed_.empty() && fixed_[i];
    for (int c = 0; c < 3; ++c) {
      if (!held) state.positions[3 * i + c] = node.m_x[c];
      state.velocities[3 * i + c] = held ? 0.0 : node.m_v[c];
    }
  }
  return guard_.check(state.positions, state.velocities);
}

}  // namespace tacta::models::bullet
