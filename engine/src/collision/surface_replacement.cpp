// CollisionContext's side of a cut made off the tick: the view copied at a tick boundary, the new
// surface and fresh plugin instances built from that copy on another thread, and the exchange at
// the boundary where the cut is applied (world/body_cut.hpp: prepare_cut, apply_cut).
#include "collision/surface_replacement.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include "collision/collision_context.hpp"
#include "collision/collision_instance.hpp"
#include "collision/embedded_collision.hpp"
#include "world/body_cut.hpp"

namespace tacta {

SurfaceReplacement::SurfaceReplacement() = default;
SurfaceReplacement::SurfaceReplacement(SurfaceReplacement&&) noexcept = default;
SurfaceReplacement& SurfaceReplacement::operator=(SurfaceReplacement&&) noexcept = default;
SurfaceReplacement::~SurfaceReplacement() = default;

namespace {
// Capacity for `count` values with a quarter more, keeping the size.
template <class T>
void reserve_with_room(std::vector<T>& v, size_t count) {
  if (count > v.capacity()) v.reserve(count + count / 4);
}
// Copies `count` values into `to` when its capacity holds them (no allocation); false otherwise.
bool copy_within(const double* from, size_t count, std::vector<double>& to) noexcept {
  if (count > to.capacity()) return false;
  to.resize(count);  // within the capacity: no allocation
  std::copy_n(from, count, to.begin());
  return true;
}
}  // namespace

void CollisionContext::reserve_view_copy(ViewCopy& copy) const {
  copy.surfaces.resize(surfaces_.size());
  for (size_t k = 0; k < surfaces_.size(); ++k) {
    const size_t values = 3 * size_t{surfaces_[k].vertex_count};
    reserve_with_room(copy.surfaces[k].start, values);
    reserve_with_room(copy.surfaces[k].end, values);
    const auto body = static_cast<size_t>(body_of_surface_[k]);
    if (embedded_[body] == nullptr) continue;
    const size_t nodes = 3 * world_.body(body).node_count();
    reserve_with_room(copy.surfaces[k].node_start, nodes);
    reserve_with_room(copy.surfaces[k].node_end, nodes);
  }
  reserve_with_room(copy.tools, tools_.size());
}

bool CollisionContext::copy_view(ViewCopy& copy) noexcept {
  copy.filled = false;
  if (copy.surfaces.size() != surfaces_.size() || copy.tools.capacity() < tools_.size())
    return false;
  for (size_t k = 0; k < surfaces_.size(); ++k) {
    const tacta_collision_surface& s = surfaces_[k];
    ViewCopy::Surface& c = copy.surfaces[k];
    const size_t values = 3 * size_t{s.vertex_count};
    if (!copy_within(s.positions_start, values, c.start) ||
        !copy_within(s.positions_end, values, c.end))
      return false;
    const auto body = static_cast<size_t>(body_of_surface_[k]);
    if (embedded_[body] == nullptr) {
      c.node_start.clear();
      c.node_end.clear();
      continue;
    }
    const SoftBody b = world_.body(body);
    if (!copy_within(b.nodes.step_start.data(), b.nodes.step_start.size(), c.node_start) ||
        !copy_within(b.nodes.positions.data(), b.nodes.positions.size(), c.node_end))
      return false;
  }
  sync_tools();
  copy.tools.assign(tools_.begin(), tools_.end());  // within the capacity checked above
  copy.time = view_.time;
  copy.dt = view_.dt;
  copy.filled = true;
  return true;
}

SurfaceReplacement CollisionContext::prepare_replacement(size_t body, PreparedCut& cut,
                                                         const ViewCopy& copy) {
  const SourceLocation where{world_.scene().path, 0, 0, "collision"};
  SurfaceReplacement r;
  r.body = body;
  if (!cut.changed || body >= surface_of_body_.size() || surface_of_body_[body] < 0) return r;
  const auto k = static_cast<size_t>(surface_of_body_[body]);
  if (!copy.filled || copy.surfaces.size() != surfaces_.size())
    throw InputError(where,
                     "a cut's collision surface needs a copy of the whole view "
                     "(copy_view) taken after its body's last change");
  // The cut body's node positions when the copy was taken: its surface's own, or (embedded) the
  // nodes the surface follows.
  const ViewCopy::Surface& mine = copy.surfaces[k];
  const std::vector<double>& node_start = embedded_[body] ? mine.node_start : mine.start;
  const std::vector<double>& node_end = embedded_[body] ? mine.node_end : mine.end;
  if (node_end.size() != 3 * cut.first_copy.size() || node_start.size() != node_end.size())
    throw InputError(where, "the view copy has " + std::to_string(node_end.size() / 3) +
                                " nodes for body " + std::to_string(body) +
                                ", the cut was prepared on " +
                                std::to_string(cut.first_copy.size()));
  // The arrays the body will have: prepare_cut carried the positions and velocities it was given
  // (the same state the copy holds); the step starts come from the copy (apply_cut sets all of
  // them again from the state at the apply).
  ShapeArrays& a = cut.arrays;
  for (size_t n = 0; n < cut.node_source.size(); ++n)
    std::copy_n(&node_start[3 * size_t{cut.node_source[n]}], 3, &a.step_start[3 * n]);
  const BodyTopology& topology = *cut.shape.topology;
  node_inverse_masses(topology, world_.body(body).settings.own_thread, r.inverse_masses);
  r.description = node_surface(body, topology, a.step_start.data(), a.positions.data(),
                               a.velocities.data(), r.inverse_masses);
  if (cut.shape.surface) {
    r.embedded = std::make_unique<EmbeddedCollisionSurface>(
        world_, body, *cut.shape.surface, cut.node_source.size(), r.inverse_masses.data());
    r.embedded->describe(r.description);
  }

  // The view the fresh instances are built over: the copy, with the new surface in place. The
  // plugins' prepare and update only read positions (velocities: none given).
  std::vector<tacta_collision_surface> build(surfaces_);
  for (size_t j = 0; j < build.size(); ++j) {
    if (j == k) continue;
    build[j].positions_start = copy.surfaces[j].start.data();
    build[j].positions_end = const_cast<double*>(copy.surfaces[j].end.data());
    build[j].velocities = nullptr;
  }
  build[k] = r.description;
  // Not a copy of view_: the ticks write its time and margin meanwhile.
  tacta_collision_world world{};
  world.struct_size = sizeof world;
  world.obstacles = obstacles_.data();
  world.obstacle_count = static_cast<uint32_t>(obstacles_.size());
  world.surfaces = build.data();
  world.surface_count = static_cast<uint32_t>(build.size());
  world.shapes = copy.tools.data();
  world.shape_count = static_cast<uint32_t>(copy.tools.size());
  world.time = copy.time;
  world.dt = copy.dt;
  world.query_margin = 0.0;

  // Prepared first: a plugin checks the surface's elements before anything reads through them.
  for (const auto& inst : instances_) {
    r.instances.emplace_back(inst->api, inst->create_sibling(where));
    if (inst->api.prepare == nullptr) continue;
    char message[kCollisionMessageCapacity] = {0};
    if (inst->api.prepare(r.instances.back().instance, &world, message, sizeof message) != TACTA_OK)
      throw InputError(where,
                       std::string("collision plugin '") + inst->descriptor.name + "': " + message);
  }
  if (r.embedded)
    r.embedded->refresh_from(a.step_start.data(), a.positions.data(), a.velocities.data(), 0);
  r.freshness.emplace(
      fresh_surface(r.description, cut.node_source.size(), r.embedded.get(), a.positions.data()));
  for (size_t i = 0; i < instances_.size(); ++i)
    if (instances_[i]->api.update != nullptr)
      r.build_bits |= instances_[i]->api.update(r.instances[i].instance, &world);

  size_t vertices = 0;
  for (const auto& s : build) vertices += s.vertex_count;
  r.pairs_needed = pairs_needed(vertices);
  r.contacts_needed = contacts_needed(vertices);
  r.patch_needed = std::max<size_t>(patch_triangles_.size(), r.description.triangle_count);
  if (r.pairs_needed > pairs_.capacity()) resize_with_room(r.pairs, r.pairs_needed);
  if (r.contacts_needed > contacts_.capacity()) resize_with_room(r.contacts, r.contacts_needed);
  if (r.patch_needed > patch_triangles_.capacity())
    resize_with_room(r.patch_triangles, r.patch_needed);
  r.surface = k;
  r.surface_count = surfaces_.size();
  return r;
}

void CollisionContext::apply_replacement(SurfaceReplacement& r) noexcept {
  if (r.surface == SurfaceReplacement::kNone || !replacement_fits(r)) return;
  const size_t k = r.surface;
  std::swap(surfaces_[k], r.description);
  std::swap(embedded_[r.body], r.embedded);
  std::swap(inverse_masses_[r.body], r.inverse_masses);
  std::swap(freshness_[k], *r.freshness);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  covered_[k] = {kInf, kInf, kInf, -kInf, -kInf, -kInf};
  last_distance_[k] = 0.0;
  drop_patches(static_cast<uint32_t>(k));  // the triangles are the new surface's
  sightings_[k] = {};
  // Grown within their capacity where it holds (no allocation), else exchanged for the ones
  // made with room; the contacts of the last tick stay readable.
  if (!r.contacts.empty()) {
    std::copy_n(contacts_.begin(), std::min<size_t>(contact_count_, r.contacts.size()),
                r.contacts.begin());
    std::swap(contacts_, r.contacts);
  }
  contacts_.resize(r.contacts_needed);
  if (!r.pairs.empty()) std::swap(pairs_, r.pairs);
  pairs_.resize(r.pairs_needed);
  if (!r.patch_triangles.empty()) std::swap(patch_triangles_, r.patch_triangles);
  patch_triangles_.resize(r.patch_needed);
  for (size_t i = 0; i < instances_.size(); ++i)
    std::swap(instances_[i]->instance, r.instances[i].instance);
  // The fresh hierarchies were built over the copy: the next refit refits them whole from the
  // bodies then (their element counts match: a refit, not a rebuild). Every surface's is new, in
  // an order of its own: each freshness binds its slices to it again then (until then the
  // margins take the largest node move and no slice box is trusted).
  for (SurfaceFreshness& fresh : freshness_) fresh.unbind();
  refitted_once_ = false;
}

}  // namespace tacta
