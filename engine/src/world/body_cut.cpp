#include "world/body_cut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "mesh/geometry.hpp"
#include "tacta/error.hpp"
#include "tacta/mesh_io.hpp"
#include "topology/cut_mesh.hpp"

namespace tacta {

namespace {

// Why body `b` cannot be cut now (cut_unsupported, or a state that passes); empty when it can.
std::string refusal(const SoftBody& b) {
  if (!b.present()) return "body '" + b.info.name + "' is not in the scene";
  if (std::string why = cut_unsupported(b); !why.empty()) return why;
  if (b.model.mailbox->incoming.load() != nullptr)
    return "body '" + b.info.name +
           "' has a model swap waiting for the next tick: step once, then cut";
  return {};
}

// Per old node: its first copy in the edited mesh, or -1 when the node went.
std::vector<int64_t> first_copies(const TopologyEdit& edit, size_t old_nodes) {
  std::vector<int64_t> copy(old_nodes, -1);
  for (size_t n = edit.node_source.size(); n-- > 0;) copy[edit.node_source[n]] = int64_t(n);
  return copy;
}

// The edited mesh's node nearest `p` at rest (a recorded node whose material was cut away).
uint32_t nearest_node(const VolumeMesh& mesh, const Vec3& p) {
  uint32_t best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (uint32_t n = 0; n < mesh.node_count(); ++n) {
    const double d2 = squared_norm(sub(mesh_detail::point(mesh.positions, n), p));
    if (d2 < best_d2) best_d2 = d2, best = n;
  }
  return best;
}

uint32_t carried_node(uint32_t old, const std::vector<int64_t>& copy, const VolumeMesh& old_mesh,
                      const VolumeMesh& mesh) {
  return copy[old] >= 0 ? static_cast<uint32_t>(copy[old])
                        : nearest_node(mesh, mesh_detail::point(old_mesh.positions, old));
}

// A probe follows its tet into the edited mesh (corner by corner through node_source); a probe
// whose tet was removed is bound to the remaining tet whose centroid is nearest at rest, with the
// extrapolated weights of its rest point there.
void carry_probe(Probe& probe, const VolumeMesh& old_mesh, const VolumeMesh& mesh,
                 const TopologyEdit& edit, const std::vector<int64_t>& new_tet_of_old) {
  std::array<uint32_t, 4> sorted = probe.nodes;
  std::sort(sorted.begin(), sorted.end());
  for (size_t t = 0; t < old_mesh.tet_count(); ++t) {
    std::array<uint32_t, 4> corners;
    std::copy_n(&old_mesh.tets[4 * t], 4, corners.begin());
    std::sort(corners.begin(), corners.end());
    if (corners != sorted || new_tet_of_old[t] < 0) continue;
    const uint32_t* now = &mesh.tets[4 * static_cast<size_t>(new_tet_of_old[t])];
    for (uint32_t& node : probe.nodes)
      for (int c = 0; c < 4; ++c)
        if (edit.node_source[now[c]] == node) {
          node = now[c];
          break;
        }
    return;
  }
  size_t best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    Vec3 centroid{0, 0, 0};
    for (int c = 0; c < 4; ++c)
      centroid =
          add(centroid, scaled(mesh_detail::point(mesh.positions, mesh.tets[4 * t + c]), 0.25));
    const double d2 = squared_norm(sub(centroid, probe.rest));
    if (d2 < best_d2) best_d2 = d2, best = t;
  }
  const uint32_t* n = &mesh.tets[4 * best];
  const auto w = mesh_detail::barycentric(probe.rest, mesh_detail::point(mesh.positions, n[0]),
                                          mesh_detail::point(mesh.positions, n[1]),
                                          mesh_detail::point(mesh.positions, n[2]),
                                          mesh_detail::point(mesh.positions, n[3]));
  for (int c = 0; c < 4; ++c) probe.nodes[c] = n[c], probe.weights[c] = w[c];
}

// Copies 3 values per node from the old array through node_source.
std::vector<double> carried(const std::vector<double>& old, const TopologyEdit& edit) {
  std::vector<double> out(3 * edit.node_source.size());
  for (size_t n = 0; n < edit.node_source.size(); ++n)
    std::copy_n(&old[3 * size_t{edit.node_source[n]}], 3, &out[3 * n]);
  return out;
}

}  // namespace

std::string cut_unsupported(const SoftBody& b) {
  const std::string name = "body '" + b.info.name + "'";
  if (b.settings.own_thread)
    return name + " steps on its own thread (step_thread: own): cutting it is not supported";
  if (!(b.model.instance->claims() & TACTA_MODEL_CLAIM_TOPOLOGY_EDITS))
    return name + "'s model '" + b.model.instance->name() +
           "' does not take topology edits (no TACTA_MODEL_CLAIM_TOPOLOGY_EDITS; `tacta plugins` "
           "lists the models that do)";
  return {};
}

CutSummary cut_body(World& world, size_t slot, std::span<const double> triangles, CutMode mode,
                    double time) {
  const SoftBody b = world.body(slot);
  const SourceLocation where{world.scene().path, 0, 0, "bodies." + b.info.name};
  for (double v : triangles)
    if (!std::isfinite(v)) throw InputError(where, "cut: a blade corner is not a finite number");
  if (const std::string why = refusal(b); !why.empty()) throw InputError(where, "cut: " + why);

  BodyTopology& old = *b.shape.topology;
  CutResult result =
      cut_mesh(old.mesh, b.shape.cut_triangles, b.nodes.positions, triangles, mode, b.shape.crack);
  if (!result.refused.empty()) throw InputError(where, "cut: " + result.refused);
  CutSummary summary;
  if (!result.edit.changed()) {
    b.shape.crack = std::move(result.crack);
    ++b.shape.cuts.cuts_missed;
    summary.revision = b.shape.cuts.revision;
    summary.tets = old.mesh.tet_count();
    summary.nodes = old.mesh.node_count();
    return summary;
  }
  TopologyEdit& edit = result.edit;
  const double haptic_dt = 1.0 / world.scene().clock.haptic_rate_hz;
  const double energy_before =
      b.kinetic_energy() + b.model.instance->elastic_energy(b.nodes.positions.data());

  // The new shape, and the models rebuilt on it (throws before anything is replaced).
  NewShape shape;
  shape.topology = std::make_unique<BodyTopology>();
  BodyTopology& topology = *shape.topology;
  topology.material = old.material;
  topology.load = old.load;
  topology.masses = lumped_masses(edit.mesh, old.material.density);
  topology.fixed.resize(edit.node_source.size());
  for (size_t n = 0; n < edit.node_source.size(); ++n)
    topology.fixed[n] = old.fixed[edit.node_source[n]];
  shape.cut_triangles = std::move(edit.cut_triangle);
  shape.crack = std::move(result.crack);
  if (b.surface.mesh) {
    CutSurface s =
        cut_embedded_surface(*b.surface.mesh, b.surface.mesh->cut_triangles, old.mesh, edit);
    shape.surface = std::make_unique<EmbeddedSurface>(std::move(s.surface));
    shape.surface->cut_triangles = std::move(s.cut_triangle);
  }
  std::vector<int64_t> new_tet_of_old(old.mesh.tet_count(), -1);
  for (size_t t = 0; t < edit.tet_source.size(); ++t)
    new_tet_of_old[edit.tet_source[t]] = int64_t(t);
  const std::vector<int64_t> copy = first_copies(edit, old.mesh.node_count());
  topology.mesh = std::move(edit.mesh);
  topology.view = make_view(topology.mesh);
  shape.loaded_node.resize(edit.node_source.size());
  for (size_t n = 0; n < edit.node_source.size(); ++n)
    shape.loaded_node[n] = b.shape.loaded_node.empty() ? edit.node_source[n]
                                                       : b.shape.loaded_node[edit.node_source[n]];
  if (b.constraints.boundary)
    shape.boundary =
        b.constraints.boundary->carried(edit.node_source, topology.mesh, topology.masses);
  ShapeModels models = make_shape_models(world, b, topology, where);

  // From here on nothing throws: the body takes the new arrays.
  const VolumeMesh& mesh = topology.mesh;
  for (uint32_t& n : b.recording.recorded_nodes) n = carried_node(n, copy, old.mesh, mesh);
  if (b.recording.probe_node)
    b.recording.probe_node = carried_node(*b.recording.probe_node, copy, old.mesh, mesh);
  for (Probe& p : b.recording.probes) carry_probe(p, old.mesh, mesh, edit, new_tet_of_old);
  const size_t n = edit.node_source.size();
  std::vector<double> applied;
  if (!b.loads.applied_forces.empty()) {
    // A force on a split node stays on its first copy, so the total applied stays the same.
    applied.assign(3 * n, 0.0);
    for (size_t o = 0; o < copy.size(); ++o)
      if (copy[o] >= 0)
        std::copy_n(&b.loads.applied_forces[3 * o], 3, &applied[3 * size_t(copy[o])]);
  }
  const double removed_mass = [&] {
    double before = 0, after = 0;
    for (double m : old.masses) before += m;
    for (double m : topology.masses) after += m;
    return before - after;
  }();
  install_shape(b, std::move(shape), std::move(models), carried(b.nodes.positions, edit),
                carried(b.nodes.velocities, edit), carried(b.nodes.step_start, edit));
  b.loads.applied_forces = std::move(applied);

  CutTotals& totals = b.shape.cuts;
  ++totals.revision;
  totals.tets_removed += result.edit.tets_removed;
  totals.nodes_removed += result.edit.nodes_removed;
  totals.nodes_added += result.edit.nodes_added;
  totals.faces_separated += result.edit.faces_separated;
  totals.removed_mass_kg += mode == CutMode::kRemove ? removed_mass : 0.0;
  const double energy_after = begin_model(b, time, haptic_dt);
  totals.removed_energy_J += energy_before - energy_after;

  summary.changed = true;
  summary.revision = totals.revision;
  summary.tets_removed = result.edit.tets_removed;
  summary.nodes_removed = result.edit.nodes_removed;
  summary.nodes_added = result.edit.nodes_added;
  summary.faces_separated = result.edit.faces_separated;
  summary.tets = b.shape.topology->mesh.tet_count();
  summary.nodes = b.node_count();
  return summary;
}

ShapeModels make_shape_models(World& world, const SoftBody& b, const BodyTopology& topology,
                              const SourceLocation& where) {
  const double dt = b.step_dt(1.0 / world.scene().clock.haptic_rate_hz);
  const SourceLocation at{where.file, 0, 0, where.key_path + ".model"};
  ShapeModels models;
  models.instance =
      world.make_model(b.model.instance->name(), b.model.instance->params(), topology, dt, at);
  for (size_t s = b.model.next_swap; s < b.model.swaps.size(); ++s)
    models.future_swaps.push_back(world.make_model(
        b.model.swaps[s].model->name(), b.model.swaps[s].model->params(), topology, dt, at));
  return models;
}

void install_shape(const SoftBody& b, NewShape shape, ShapeModels models,
                   std::vector<double> positions, std::vector<double> velocities,
                   std::vector<double> step_start) {
  RetiredArrays retired;
  retired.positions = std::exchange(b.nodes.positions, std::move(positions));
  retired.velocities = std::exchange(b.nodes.velocities, std::move(velocities));
  b.nodes.step_start = std::move(step_start);
  b.loads.external_forces.assign(b.nodes.positions.size(), 0.0);
  b.loads.contact_forces.assign(b.nodes.positions.size(), 0.0);
  b.loads.applied_forces.clear();
  for (size_t s = 0; s < b.model.next_swap; ++s) b.model.swaps[s].model.reset();  // outgoing
  for (size_t s = b.model.next_swap, k = 0; s < b.model.swaps.size(); ++s, ++k)
    b.model.swaps[s].model = std::move(models.future_swaps[k]);
  b.model.instance = std::move(models.instance);  // the old instance goes before its topology
  retired.topology = std::exchange(b.shape.topology, std::move(shape.topology));
  retired.surface = std::exchange(b.surface.mesh, std::move(shape.surface));
  retired.boundary = std::exchange(b.constraints.boundary, std::move(shape.boundary));
  b.shape.retired.push_back(std::move(retired));
  b.shape.cut_triangles = std::move(shape.cut_triangles);
  b.shape.crack = std::move(shape.crack);
  b.shape.loaded_node = std::move(shape.loaded_node);
  if (b.surface.mesh) update_embedded_surface(*b.surface.mesh, b.nodes.positions.data());
}

}  // namespace tacta
