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

// After exchange_shape: the old instances are freed (before the topology they were made on) and
// the old topology, positions, velocities, surface and boundary motion kept.
void keep_retired(const SoftBody& b, NewShape& old, ShapeModels& old_models, ShapeArrays& arrays) {
  old_models = {};
  RetiredArrays retired;
  retired.topology = std::move(old.topology);
  retired.positions = std::move(arrays.positions);
  retired.velocities = std::move(arrays.velocities);
  retired.surface = std::move(old.surface);
  retired.boundary = std::move(old.boundary);
  b.shape.retired.push_back(std::move(retired));
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

PreparedCut prepare_cut(World& world, size_t slot, std::span<const double> triangles, CutMode mode,
                        std::span<const double> positions, std::span<const double> velocities) {
  const SoftBody b = world.body(slot);
  const SourceLocation where{world.scene().path, 0, 0, "bodies." + b.info.name};
  for (double v : triangles)
    if (!std::isfinite(v)) throw InputError(where, "cut: a blade corner is not a finite number");
  if (const std::string why = refusal(b); !why.empty()) throw InputError(where, "cut: " + why);

  const BodyTopology& old = *b.shape.topology;
  if (velocities.size() != positions.size())
    throw InputError(where, "cut: " + std::to_string(velocities.size()) + " velocities for " +
                                std::to_string(positions.size()) + " position values");
  CutResult result =
      cut_mesh(old.mesh, b.shape.cut_triangles, positions, triangles, mode, b.shape.crack);
  if (!result.refused.empty()) throw InputError(where, "cut: " + result.refused);
  PreparedCut cut;
  cut.slot = slot;
  cut.mode = mode;
  cut.prepared_on = &old;
  cut.model_then = b.model.instance.get();
  cut.next_swap_then = b.model.next_swap;
  if (!result.edit.changed()) {
    cut.crack = std::move(result.crack);
    return cut;
  }
  TopologyEdit& edit = result.edit;
  cut.changed = true;
  cut.tets_removed = edit.tets_removed;
  cut.nodes_removed = edit.nodes_removed;
  cut.nodes_added = edit.nodes_added;
  cut.faces_separated = edit.faces_separated;

  // The new shape, and the models rebuilt on it (throws before anything is replaced).
  NewShape& shape = cut.shape;
  shape.topology = std::make_unique<BodyTopology>();
  BodyTopology& topology = *shape.topology;
  topology.material = old.material;
  topology.load = old.load;
  topology.masses = lumped_masses(edit.mesh, old.material.density);
  const size_t n = edit.node_source.size();
  topology.fixed.resize(n);
  for (size_t i = 0; i < n; ++i) topology.fixed[i] = old.fixed[edit.node_source[i]];
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
  cut.first_copy = first_copies(edit, old.mesh.node_count());
  topology.mesh = std::move(edit.mesh);
  topology.view = make_view(topology.mesh);
  shape.loaded_node.resize(n);
  for (size_t i = 0; i < n; ++i)
    shape.loaded_node[i] = b.shape.loaded_node.empty() ? edit.node_source[i]
                                                       : b.shape.loaded_node[edit.node_source[i]];
  if (b.constraints.boundary)
    shape.boundary =
        b.constraints.boundary->carried(edit.node_source, topology.mesh, topology.masses);
  cut.models = make_shape_models(world, b, topology, where);

  const VolumeMesh& mesh = topology.mesh;
  cut.recorded_nodes = b.recording.recorded_nodes;
  for (uint32_t& node : cut.recorded_nodes)
    node = carried_node(node, cut.first_copy, old.mesh, mesh);
  if (b.recording.probe_node)
    cut.probe_node = carried_node(*b.recording.probe_node, cut.first_copy, old.mesh, mesh);
  cut.probes = b.recording.probes;
  for (Probe& p : cut.probes) carry_probe(p, old.mesh, mesh, edit, new_tet_of_old);
  ShapeArrays& a = cut.arrays;
  for (std::vector<double>* v :
       {&a.positions, &a.velocities, &a.step_start, &a.external_forces, &a.contact_forces})
    v->assign(3 * n, 0.0);
  if (!b.loads.applied_forces.empty()) a.applied_forces.assign(3 * n, 0.0);
  for (size_t i = 0; i < n; ++i) {  // the state then, carried (apply_cut carries the state now)
    std::copy_n(&positions[3 * size_t{edit.node_source[i]}], 3, &a.positions[3 * i]);
    std::copy_n(&velocities[3 * size_t{edit.node_source[i]}], 3, &a.velocities[3 * i]);
  }
  cut.positions_then.assign(positions.begin(), positions.end());
  cut.velocities_then.assign(velocities.begin(), velocities.end());
  cut.energy_after_J = kinetic_energy(topology.masses, a.velocities) +
                       cut.models.instance->elastic_energy(a.positions.data());
  double mass_before = 0, mass_after = 0;
  for (double m : old.masses) mass_before += m;
  for (double m : topology.masses) mass_after += m;
  cut.removed_mass_kg = mass_before - mass_after;
  cut.node_source = std::move(edit.node_source);
  return cut;
}

bool still_fits(const World& world, const PreparedCut& cut) noexcept {
  const SoftBody b = world.body(cut.slot);
  return b.shape.topology.get() == cut.prepared_on && b.model.instance.get() == cut.model_then &&
         b.model.next_swap == cut.next_swap_then;
}

CutSummary apply_cut(World& world, PreparedCut& cut, double time) noexcept {
  const SoftBody b = world.body(cut.slot);
  CutTotals& totals = b.shape.cuts;
  CutSummary summary;
  if (!cut.changed) {
    std::swap(b.shape.crack, cut.crack);
    ++totals.cuts_missed;
    summary.revision = totals.revision;
    summary.tets = b.shape.topology->mesh.tet_count();
    summary.nodes = b.node_count();
    return summary;
  }
  // The state now, carried through node_source; a force on a split node stays on its first copy,
  // so the total applied stays the same.
  ShapeArrays& a = cut.arrays;
  for (size_t n = 0; n < cut.node_source.size(); ++n) {
    const size_t from = 3 * size_t{cut.node_source[n]};
    std::copy_n(&b.nodes.positions[from], 3, &a.positions[3 * n]);
    std::copy_n(&b.nodes.velocities[from], 3, &a.velocities[3 * n]);
    std::copy_n(&b.nodes.step_start[from], 3, &a.step_start[3 * n]);
  }
  if (!a.applied_forces.empty() && b.loads.applied_forces.size() == 3 * cut.first_copy.size())
    for (size_t o = 0; o < cut.first_copy.size(); ++o)
      if (cut.first_copy[o] >= 0)
        std::copy_n(&b.loads.applied_forces[3 * o], 3,
                    &a.applied_forces[3 * size_t(cut.first_copy[o])]);
  if (cut.shape.boundary) cut.shape.boundary->carry_state_from(*b.constraints.boundary);
  std::swap(b.recording.recorded_nodes, cut.recorded_nodes);
  std::swap(b.recording.probe_node, cut.probe_node);
  std::swap(b.recording.probes, cut.probes);
  exchange_shape(b, cut.shape, cut.models, cut.arrays);

  ++totals.revision;
  totals.tets_removed += cut.tets_removed;
  totals.nodes_removed += cut.nodes_removed;
  totals.nodes_added += cut.nodes_added;
  totals.faces_separated += cut.faces_separated;
  totals.removed_mass_kg += cut.mode == CutMode::kRemove ? cut.removed_mass_kg : 0.0;
  b.model.instance->begin(b.state_view(time), b.step_dt(1.0 / world.scene().clock.haptic_rate_hz));

  summary.changed = true;
  summary.revision = totals.revision;
  summary.tets_removed = cut.tets_removed;
  summary.nodes_removed = cut.nodes_removed;
  summary.nodes_added = cut.nodes_added;
  summary.faces_separated = cut.faces_separated;
  summary.tets = b.shape.topology->mesh.tet_count();
  summary.nodes = b.node_count();
  return summary;
}

void retire_cut(World& world, PreparedCut& cut) {
  if (!cut.changed) return;
  const SoftBody b = world.body(cut.slot);
  // After the exchange `cut` holds the old shape and model.
  const double energy_before = kinetic_energy(cut.shape.topology->masses, cut.velocities_then) +
                               cut.models.instance->elastic_energy(cut.positions_then.data());
  b.shape.cuts.removed_energy_J += energy_before - cut.energy_after_J;
  keep_retired(b, cut.shape, cut.models, cut.arrays);
}

CutSummary cut_body(World& world, size_t slot, std::span<const double> triangles, CutMode mode,
                    double time) {
  const SoftBody b = world.body(slot);
  PreparedCut cut =
      prepare_cut(world, slot, triangles, mode, b.nodes.positions, b.nodes.velocities);
  const CutSummary summary = apply_cut(world, cut, time);
  retire_cut(world, cut);
  return summary;
}

ShapeModels make_shape_models(World& world, const SoftBody& b, const BodyTopology& topology,
                              const SourceLocation& where) {
  const double dt = b.step_dt(1.0 / world.scene().clock.haptic_rate_hz);
  const SourceLocation at{where.file, 0, 0, where.key_path + ".model"};
  ShapeModels models;
  models.instance =
      world.make_model(b.model.instance->name(), b.model.instance->params(), topology, dt, at);
  models.future_swaps.resize(b.model.swaps.size());  // null for the swaps already made
  for (size_t s = b.model.next_swap; s < b.model.swaps.size(); ++s)
    models.future_swaps[s] = world.make_model(b.model.swaps[s].model->name(),
                                              b.model.swaps[s].model->params(), topology, dt, at);
  return models;
}

void exchange_shape(const SoftBody& b, NewShape& shape, ShapeModels& models,
                    ShapeArrays& arrays) noexcept {
  std::swap(b.nodes.positions, arrays.positions);
  std::swap(b.nodes.velocities, arrays.velocities);
  std::swap(b.nodes.step_start, arrays.step_start);
  std::swap(b.loads.external_forces, arrays.external_forces);
  std::swap(b.loads.contact_forces, arrays.contact_forces);
  std::swap(b.loads.applied_forces, arrays.applied_forces);
  // Swaps still to come take the instances made on the new mesh; those made (outgoing) leave.
  for (size_t s = 0; s < b.model.swaps.size(); ++s)
    std::swap(b.model.swaps[s].model, models.future_swaps[s]);
  std::swap(b.model.instance, models.instance);
  std::swap(b.shape.topology, shape.topology);
  std::swap(b.surface.mesh, shape.surface);
  std::swap(b.constraints.boundary, shape.boundary);
  std::swap(b.shape.cut_triangles, shape.cut_triangles);
  std::swap(b.shape.crack, shape.crack);
  std::swap(b.shape.loaded_node, shape.loaded_node);
  if (b.surface.mesh) update_embedded_surface(*b.surface.mesh, b.nodes.positions.data());
}

void install_shape(const SoftBody& b, NewShape shape, ShapeModels models,
                   std::vector<double> positions, std::vector<double> velocities,
                   std::vector<double> step_start) {
  ShapeArrays arrays;
  arrays.external_forces.assign(positions.size(), 0.0);
  arrays.contact_forces.assign(positions.size(), 0.0);
  arrays.positions = std::move(positions);
  arrays.velocities = std::move(velocities);
  arrays.step_start = std::move(step_start);
  exchange_shape(b, shape, models, arrays);
  keep_retired(b, shape, models, arrays);
}

}  // namespace tacta
