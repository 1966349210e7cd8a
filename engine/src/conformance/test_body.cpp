#include "conformance/test_body.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"
#include "tacta/param_defaults.hpp"
#include "tacta/sdk/elastic_constants.hpp"

namespace tacta::conformance {

tacta_model_setup TestBody::setup() const {
  return {sizeof(tacta_model_setup),
          &view,
          &material,
          masses.data(),
          fixed.data(),
          params.data(),
          params.size(),
          dt,
          nullptr};
}

namespace {

// The plugin's view of body.mesh (pointers into it: set again whenever the mesh changes).
void point_view_at_mesh(TestBody& body) {
  const VolumeMesh& m = body.mesh;
  body.view = {static_cast<uint32_t>(m.node_count()),
               m.positions.data(),
               static_cast<uint32_t>(m.tet_count()),
               m.tets.data(),
               static_cast<uint32_t>(m.triangles.size() / 3),
               m.triangles.data(),
               static_cast<uint32_t>(m.quads.size() / 4),
               m.quads.data(),
               static_cast<uint32_t>(m.edges.size() / 2),
               m.edges.data(),
               m.dimension};
}

}  // namespace

std::unique_ptr<TestBody> make_test_body(const tacta_descriptor& model, bool clamped) {
  auto body = std::make_unique<TestBody>();
  body->mesh = make_box_grid({0.1, 0.1, 0.1}, {2, 2, 2}, {0.0, 0.0, 0.0});
  // Liver-like stiffness and water's density: the explicit models' stable step at this cell is
  // a few ms, above the 1 ms tick.
  const double E = 1e5, nu = 0.3, rho = 1000.0;
  const sdk::Lame lame = sdk::lame_from_young(E, nu);
  body->material = {E, nu, rho, lame.lambda, lame.mu, 0.0, 0.0};
  body->masses = lumped_masses(body->mesh, rho);
  body->fixed.assign(body->mesh.node_count(), 0);
  if (clamped)
    for (size_t n = 0; n < body->fixed.size(); ++n)
      body->fixed[n] = body->mesh.positions[3 * n + 2] == 0.0;
  point_view_at_mesh(*body);
  body->params = defaults_of(model);
  return body;
}

std::unique_ptr<TestBody> edited_test_body(const TestBody& body, VolumeMesh mesh,
                                           const std::vector<uint32_t>& node_source) {
  auto edited = std::make_unique<TestBody>();
  edited->mesh = std::move(mesh);
  edited->material = body.material;
  edited->params = body.params;
  edited->dt = body.dt;
  edited->cell = body.cell;
  edited->masses = lumped_masses(edited->mesh, body.material.density);
  edited->fixed.resize(node_source.size());
  for (size_t n = 0; n < node_source.size(); ++n) edited->fixed[n] = body.fixed[node_source[n]];
  point_view_at_mesh(*edited);
  return edited;
}

std::unique_ptr<ModelInstance> create_model(const tacta_descriptor& model, const TestBody& body) {
  SourceLocation where;
  where.file = "check-plugin's 2x2x2-cell test cube";
  return std::make_unique<ModelInstance>(model, body.setup(), where);
}

std::vector<double> elastic_forces(ModelInstance& model, const TestBody& body,
                                   const std::vector<double>& positions, std::string& how) {
  std::vector<double> forces(positions.size(), 0.0);
  if (model.internal_forces(positions.data(), forces.data())) {
    how = "internal_forces";
    return forces;
  }
  how = "one step from rest";
  NodeState s(positions);
  tacta_body_state state = s.view();
  model.begin(state, body.dt);
  model.step(state, body.dt);
  // From the position change, not the velocity: with v = 0 at the start, a one-step integrator
  // (explicit, implicit or central differences started by begin()) moves a node by a dt^2.
  for (size_t i = 0; i < forces.size(); ++i)
    forces[i] = body.masses[i / 3] * (s.x[i] - positions[i]) / (body.dt * body.dt);
  return forces;
}

double largest_node_force(const std::vector<double>& forces) {
  double worst = 0;
  for (size_t i = 0; i + 2 < forces.size(); i += 3)
    worst = std::max(worst, std::hypot(forces[i], forces[i + 1], forces[i + 2]));
  return worst;
}

std::string figure(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", value);
  return text;
}

}  // namespace tacta::conformance
