#include "world/soft_body.hpp"

#include <algorithm>
#include <cmath>

#include "mesh/mesh_file_check.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

tacta_mesh_view make_view(const VolumeMesh& m) {
  tacta_mesh_view v{};
  v.node_count = static_cast<uint32_t>(m.node_count());
  v.rest_positions = m.positions.data();
  v.tet_count = static_cast<uint32_t>(m.tets.size() / 4);
  v.tets = m.tets.data();
  v.triangle_count = static_cast<uint32_t>(m.triangles.size() / 3);
  v.triangles = m.triangles.data();
  v.quad_count = static_cast<uint32_t>(m.quads.size() / 4);
  v.quads = m.quads.data();
  v.edge_count = static_cast<uint32_t>(m.edges.size() / 2);
  v.edges = m.edges.data();
  v.dimension = m.dimension;
  return v;
}

namespace {

tacta_material make_material(const MaterialDesc& d) {
  return {d.youngs_modulus, d.poisson_ratio, d.density,           d.lame_lambda,
          d.lame_mu,        d.rayleigh_mass, d.rayleigh_stiffness};
}

void check_node(uint32_t node, size_t count, const SourceLocation& where, const char* what) {
  if (node >= count)
    throw InputError(where, std::string(what) + ": node " + std::to_string(node) +
                                " is out of range (the mesh has " + std::to_string(count) +
                                " nodes)");
}

double bounding_diagonal(const std::vector<double>& x) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < x.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], x[i]);
    hi[i % 3] = std::max(hi[i % 3], x[i]);
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// Nodes whose trajectories are recorded for plots: the scene's list, else the probe, else the
// corners of a small mesh (every node up to 16), else none.
std::vector<uint32_t> recorded_nodes(const BodyDesc& desc, const SceneDesc& scene, size_t count) {
  std::vector<uint32_t> nodes;
  for (uint32_t n : scene.output.plot_nodes)
    if (n < count) nodes.push_back(n);
  if (nodes.empty() && desc.probe_node) nodes.push_back(*desc.probe_node);
  if (nodes.empty() && count <= 16)
    for (uint32_t n = 0; n < count; ++n) nodes.push_back(n);
  return nodes;
}

// Nodes with free axes are advanced against the model's internal forces (BoundaryMotion).
void require_internal_forces(const BodyConstraints& constraints, const ModelInstance& model,
                             const SourceLocation& where) {
  if (constraints.boundary && constraints.boundary->needs_internal_forces() &&
      !model.has_internal_forces())
    throw InputError(where,
                     std::string("model '") + model.name() +
                         "' gives no internal forces, which per-axis constraints and plates need "
                         "(use a model that does, e.g. corotational_fem)");
}

}  // namespace

ModelMailbox::~ModelMailbox() {
  delete incoming.exchange(nullptr);
  for (ModelInstance* m = retired.exchange(nullptr); m != nullptr;) {
    ModelInstance* next = m->retired_next;
    delete m;
    m = next;
  }
}

double kinetic_energy(std::span<const double> masses, std::span<const double> velocities) noexcept {
  double e = 0;
  for (size_t i = 0; i < masses.size(); ++i) {
    const double* v = &velocities[3 * i];
    e += 0.5 * masses[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return e;
}

double kinetic_energy(const NodeState& nodes, const BodyTopology& topology) noexcept {
  return kinetic_energy(topology.masses, nodes.velocities);
}

double SoftBody::kinetic_energy() const noexcept {
  return tacta::kinetic_energy(nodes, *shape.topology);
}

double begin_model(const SoftBody& b, double time, double haptic_dt) noexcept {
  const double energy =
      b.kinetic_energy() + b.model.instance->elastic_energy(b.nodes.positions.data());
  b.model.instance->begin(b.state_view(time), b.step_dt(haptic_dt));
  return energy;
}

BodyParts build_soft_body(const BodyDesc& desc, const SceneDesc& scene,
                          const ModelFactory& make_model) {
  BodyParts body;
  body.info.name = desc.name;
  body.shape.topology = std::make_unique<BodyTopology>();
  BodyTopology& topo = *body.shape.topology;
  if (desc.mesh.kind == MeshSourceDesc::Kind::File)
    require_mesh_file(desc.mesh.path, desc.mesh.where);
  if (!desc.mesh.surface_path.empty())
    require_mesh_file(desc.mesh.surface_path, desc.mesh.surface_where);
  topo.mesh = load_at(desc.mesh.where, [&] { return load_body_mesh(desc.mesh, &topo.load); });
  const size_t n = topo.mesh.node_count();
  if (n == 0) throw InputError(desc.where, "mesh: the mesh has no nodes");
  if (topo.mesh.embedding)
    body.surface.mesh = std::make_unique<EmbeddedSurface>(make_embedded_surface(topo.mesh));
  topo.view = make_view(topo.mesh);
  topo.material = make_material(desc.material);
  topo.masses = lumped_masses(topo.mesh, desc.material.density);
  topo.fixed.assign(n, 0);

  const std::vector<double>& rest = topo.mesh.positions;
  for (const FixedRegionDesc& region : desc.fixed)
    for (uint32_t node : select_nodes(region, topo.mesh, desc.where, "fixed")) topo.fixed[node] = 1;
  if (n > 0 &&
      std::count(topo.fixed.begin(), topo.fixed.end(), 1) == static_cast<std::ptrdiff_t>(n))
    body.info.load_warning =
        InputError(
            desc.fixed_where,
            "the fixed regions hold all " + std::to_string(n) + " nodes of body '" + desc.name +
                "', so it never moves (a device still touches it, as a rigid surface): to "
                "make it deform, fix fewer nodes (a box around one face, or a list of nodes); "
                "for a static thing no device touches, an `obstacles` entry costs nothing per tick")
            .what();

  body.constraints.boundary =
      BoundaryMotion::build(desc, topo.mesh, desc.material, topo.masses, topo.fixed);
  body.recording.probes = locate_probes(desc.probes, topo.mesh, desc.where);

  body.nodes.positions = rest;
  body.nodes.velocities.assign(3 * n, 0.0);
  for (size_t i = 0; i < n; ++i)
    if (!topo.fixed[i])
      for (int a = 0; a < 3; ++a) body.nodes.velocities[3 * i + a] = desc.uniform_velocity[a];
  for (const auto& d : desc.initial_displacement) {
    check_node(d.node, n, desc.where, "initial.displacement");
    for (int a = 0; a < 3; ++a) body.nodes.positions[3 * d.node + a] += d.value[a];
  }
  for (const auto& v : desc.initial_velocity) {
    check_node(v.node, n, desc.where, "initial.velocity");
    for (int a = 0; a < 3; ++a) body.nodes.velocities[3 * v.node + a] = v.value[a];
  }
  if (body.constraints.boundary)
    body.constraints.boundary->place(body.nodes.positions, body.nodes.velocities, 0.0);
  body.loads.external_forces.assign(3 * n, 0.0);
  body.loads.contact_forces.assign(3 * n, 0.0);
  body.nodes.step_start = body.nodes.positions;
  if (body.surface.mesh) update_embedded_surface(*body.surface.mesh, body.nodes.positions.data());
  if (desc.probe_node) check_node(*desc.probe_node, n, desc.where, "probe_node");
  body.recording.probe_node = desc.probe_node;
  body.recording.recorded_nodes = recorded_nodes(desc, scene, n);
  // Ten body sizes of displacement is far past any elastic regime: call it divergence.
  body.settings.divergence_limit_m = 10.0 * std::max(bounding_diagonal(rest), 1e-3);

  const double dt =
      desc.step_rate_hz > 0 ? 1.0 / desc.step_rate_hz : 1.0 / scene.clock.haptic_rate_hz;
  body.settings.period_s = desc.step_rate_hz > 0 ? dt : 0.0;
  body.settings.own_thread = desc.own_thread;
  body.settings.local_contact_yielding = desc.local_contact_yielding;
  body.model.instance = make_model(desc.model, desc.model_params, topo, dt, desc.where);
  require_internal_forces(body.constraints, *body.model.instance, desc.where);
  body.model.initial_model = desc.model;
  body.model.runtime_swaps.reserve(256);
  for (const SwapDesc& swap : scene.swaps) {
    if (swap.body != "*" && swap.body != desc.name) continue;
    body.model.swaps.push_back(
        {swap.time, swap.model, make_model(swap.model, swap.params, topo, dt, desc.where)});
    require_internal_forces(body.constraints, *body.model.swaps.back().model, desc.where);
  }
  std::stable_sort(
      body.model.swaps.begin(), body.model.swaps.end(),
      [](const ScheduledSwap& a, const ScheduledSwap& b) { return a.time_s < b.time_s; });
  return body;
}

}  // namespace tacta
