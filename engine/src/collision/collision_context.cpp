#include "collision/collision_context.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <fmt/format.h>
#include <limits>

#include "collision/collision_instance.hpp"
#include "collision/embedded_collision.hpp"
#include "collision/proxy_query.hpp"
#include "mesh/mesh_file_check.hpp"
#include "plugin/complete_params.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {
constexpr double kMaxThicknessPerEdge = 0.5;  // collision.thickness <= this x the mean surface edge
// The proxy's query margin is kept below this x mean edge, and never past the cap (a whole
// refit). When patches answer the queries near the tool, the margin widens only the patches'
// gathers and the queries too large for a patch: a larger target refits fewer slices (the liver
// demo's fine surface: 474 slices in 1.5 s against 888 at a quarter edge).
constexpr double kMarginTargetPerEdge = 0.25;
constexpr double kPatchedMarginTargetPerEdge = 1.0;
constexpr double kMarginCapPerEdge = 3.0;

// Mean length of a collision surface's triangle edges (each shared edge counted twice), m: the
// tets' boundary, or the embedded surface a body is collided through.
double mean_edge_length(const tacta_collision_surface& s) {
  double sum = 0;
  for (size_t i = 0; i < 3 * size_t{s.triangle_count}; ++i) {
    const double* a = &s.positions_end[3 * size_t{s.triangles[i]}];
    const double* b = &s.positions_end[3 * size_t{s.triangles[i % 3 == 2 ? i - 2 : i + 1]}];
    sum += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                     (a[2] - b[2]) * (a[2] - b[2]));
  }
  return s.triangle_count == 0 ? 0.0 : sum / (3.0 * s.triangle_count);
}

// The contact margin is bounded by the surfaces' edges: with a margin past half an edge every
// feature is in reach of its neighbours' neighbours, the candidate pairs grow fast with
// thickness / edge and the edge-edge CCD with them (1000 m on soft_drop: ~0.6 s of CPU a tick).
void check_thickness(const CollisionDesc& c, const World& world,
                     const std::vector<tacta_collision_surface>& surfaces,
                     const std::vector<int>& body_of_surface) {
  for (size_t k = 0; k < surfaces.size(); ++k) {
    const double edge = mean_edge_length(surfaces[k]);
    const double limit = kMaxThicknessPerEdge * edge;
    if (c.thickness > limit)
      throw InputError(
          c.thickness_where,
          fmt::format(
              "a contact thickness of {:g} m is too thick for body '{}': at most {:g} of its mean "
              "surface edge ({:.3g} m), i.e. {:.3g} m; a thicker margin puts every surface feature "
              "in reach of many others and the edge-edge CCD cost per tick grows fast with "
              "thickness / edge (a 1000 m margin on soft_drop took ~0.6 s of CPU a tick, against "
              "~0.1 ms)",
              c.thickness, world.body(static_cast<size_t>(body_of_surface[k])).info.name,
              kMaxThicknessPerEdge, edge, limit));
  }
}

}  // namespace

CollisionContext::CollisionContext(World& world, const PluginRegistry& plugins) : world_(world) {
  const SceneDesc& scene = world.scene();
  const CollisionDesc& c = scene.collision;
  const double dt = 1.0 / scene.clock.haptic_rate_hz;
  response_enabled_ = c.enabled;

  patch_slots_ = std::max<size_t>(1, world.device_count());
  // Per slot, so a body added later (add_surface) finds its entries.
  surface_of_body_.assign(world.body_capacity(), -1);
  refits_seen_.assign(world.body_capacity(), 0);
  inverse_masses_.resize(world.body_capacity());
  embedded_.resize(world.body_capacity());
  surfaces_.reserve(world.body_capacity());
  for (size_t i = 0; i < world.body_count(); ++i) {
    tacta_collision_surface s{};
    if (describe_body(i, s)) append(i, s);
  }
  if (c.enabled) check_thickness(c, world, surfaces_, body_of_surface_);
  // Shape ids follow every body slot (added bodies too): tools first, then obstacles, so contacts
  // name them uniquely.
  // The plugins see the tools' and obstacles' shapes in two packed arrays (the C view), copied
  // from their entities: obstacles once, tools each tick (their poses and any change of tool).
  world.registry().view<Tool>().each(
      [&](ecs::Entity, Tool& t) { tools_.push_back(t.rigid.shape); });
  world.registry().view<Collider>().each(
      [&](ecs::Entity, Collider& collider) { obstacles_.push_back(collider.rigid.shape); });

  view_.struct_size = sizeof view_;
  view_.shape_count = static_cast<uint32_t>(tools_.size());
  view_.shapes = tools_.data();
  view_.obstacle_count = static_cast<uint32_t>(obstacles_.size());
  view_.obstacles = obstacles_.data();
  view_.dt = dt;

  // The plugins: the broad phase is needed for the proxy's queries even without contact response.
  const SourceLocation where{scene.path, 0, 0, "collision"};
  auto add = [&](const std::string& name, ParamSet params, const SourceLocation& at) {
    const LoadedDescriptor* found = plugins.find(TACTA_KIND_COLLISION, name);
    if (found == nullptr)
      throw InputError(at, plugins.unknown_name_message(TACTA_KIND_COLLISION, name));
    // Collision off in the scene: the broad phase (the proxy's queries) gets its defaults.
    params = complete_params(*found->descriptor, params);
    // collision.friction is the scene's one Coulomb coefficient, given to every plugin that has
    // a `friction` parameter. The loader has already resolved it: a plugin's own `friction`
    // written in the scene sets collision.friction, and two different values are refused
    // (world_reader.cpp, read_collision), so this never replaces a value the scene wrote.
    params.set_number("friction", c.friction);
    instances_.push_back(std::make_unique<CollisionInstance>(*found, params, dt, at));
  };
  const bool needed = c.enabled || world.device_count() > 0;
  if (needed && !c.broad_phase.empty()) add(c.broad_phase, c.broad_params, where);
  if (c.enabled && !c.narrow_phase.empty()) add(c.narrow_phase, c.narrow_params, where);
  if (c.enabled && !c.convex.empty() && (!obstacles_.empty() || !tools_.empty()))
    add(c.convex, c.convex_params, where);
  pick_roles(c, needed, add);
  prepare_plugins(where);
  const CollisionInstance* proxy = served_[role_index(TACTA_COLLISION_ROLE_PROXY)];
  query_ = std::make_unique<Query>(*this, proxy);
  // Slices need one plugin keeping hierarchies (the slices follow its order), refittable a run
  // at a time, serving the proxy and saying which triangles a box reaches (the embedded patch).
  size_t keepers = 0;
  for (auto& inst : instances_)
    if (inst->api.update != nullptr) {
      ++keepers;
      slicer_ = inst->update_elements != nullptr ? inst.get() : nullptr;
    }
  // The proxy's own plugin is the one sliced: its overlap_shape and queries then honour the
  // margin (a proxy built against an older header would ignore it).
  sliced_ = c.proxy_refit_sliced && keepers == 1 && slicer_ != nullptr && slicer_ == proxy &&
            proxy->api.overlap_shape != nullptr;
  // The margins' targets hang on whether patches answer the proxy (known now).
  for (uint32_t k = 0; k < surfaces_.size() && patches_wanted(); ++k) {
    const auto body = static_cast<size_t>(body_of_surface_[k]);
    const NodeState& nodes = world.body_nodes(body);
    freshness_[k] = fresh_surface(surfaces_[k], nodes.positions.size() / 3, embedded_[body].get(),
                                  nodes.positions.data());
  }
}

// 1 per node, 1/kg (0: fixed, or moved by its own thread).
void node_inverse_masses(const BodyTopology& topology, bool own_thread, std::vector<double>& inv) {
  inv.resize(topology.masses.size());
  // A body stepping on its own thread has its state replaced at each refresh, so a correction
  // made here would be lost: for the response it is a moving obstacle (infinite mass).
  for (size_t n = 0; n < inv.size(); ++n)
    inv[n] =
        own_thread || topology.fixed[n] || topology.masses[n] <= 0 ? 0.0 : 1.0 / topology.masses[n];
}

tacta_collision_surface CollisionContext::node_surface(
    size_t body, const BodyTopology& topology, double* start, double* end, double* velocities,
    const std::vector<double>& inverse_masses) const {
  tacta_collision_surface s{};
  s.body_id = static_cast<uint32_t>(body);
  s.vertex_count = static_cast<uint32_t>(inverse_masses.size());
  s.positions_start = start;
  s.positions_end = end;
  s.velocities = velocities;
  s.inverse_masses = inverse_masses.data();
  s.triangle_count = static_cast<uint32_t>(topology.mesh.triangles.size() / 3);
  s.triangles = topology.mesh.triangles.data();
  s.tet_count = static_cast<uint32_t>(topology.mesh.tets.size() / 4);
  s.tets = s.tet_count ? topology.mesh.tets.data() : nullptr;
  s.thickness = world_.scene().collision.thickness;
  return s;
}

bool CollisionContext::describe_body(size_t i, tacta_collision_surface& s) {
  const SoftBody b = world_.body(i);
  if (!world_.body_desc(i).collide || b.shape.topology->mesh.triangles.empty() ||
      b.shape.topology->mesh.dimension != 3)
    return false;
  node_inverse_masses(*b.shape.topology, b.settings.own_thread, inverse_masses_[i]);
  s = node_surface(i, *b.shape.topology, b.nodes.step_start.data(), b.nodes.positions.data(),
                   b.nodes.velocities.data(), inverse_masses_[i]);
  // A body with an embedded surface is seen, touched and collided through that surface.
  if (b.surface.mesh) {
    embedded_[i] = std::make_unique<EmbeddedCollisionSurface>(
        world_, i, *b.surface.mesh, b.node_count(), inverse_masses_[i].data());
    embedded_[i]->refresh();
    embedded_[i]->describe(s);
  }
  return true;
}

void CollisionContext::append(size_t body, const tacta_collision_surface& s) {
  surface_of_body_[body] = static_cast<int>(surfaces_.size());
  body_of_surface_.push_back(static_cast<int>(body));
  surfaces_.push_back(s);
  const SoftBody b = world_.body(body);
  freshness_.push_back(
      fresh_surface(s, b.node_count(), embedded_[body].get(), b.nodes.positions.data()));
  constexpr double kInf = std::numeric_limits<double>::infinity();
  covered_.push_back({kInf, kInf, kInf, -kInf, -kInf, -kInf});
  last_distance_.push_back(0.0);
  sightings_.emplace_back();
  patches_.resize(patches_.size() + patch_slots_);
  patch_triangles_.resize(std::max<size_t>(patch_triangles_.size(), s.triangle_count));
}

SurfaceFreshness CollisionContext::fresh_surface(const tacta_collision_surface& s,
                                                 size_t node_count,
                                                 const EmbeddedCollisionSurface* embedded,
                                                 const double* nodes) const {
  // A margin of a fraction of a mean edge adds few triangles to a query; one of a few mean edges
  // adds many: cheaper to refit the whole surface then.
  const double weight_bound = embedded ? embedded->weight_bound() : 1.0;
  const double edge = mean_edge_length(s);
  const double target = patches_wanted() ? kPatchedMarginTargetPerEdge : kMarginTargetPerEdge;
  SurfaceFreshness fresh(node_count, s.triangle_count, weight_bound, target * edge,
                         kMarginCapPerEdge * edge,
                         embedded ? EmbeddedCollisionSurface::kNodesPerVertex : 1);
  fresh.reset(nodes);
  return fresh;
}

void CollisionContext::prepare_plugins(const SourceLocation& where) {
  view_.surface_count = static_cast<uint32_t>(surfaces_.size());
  view_.surfaces = surfaces_.data();
  for (auto& inst : instances_) {
    if (inst->api.prepare == nullptr) continue;
    char message[kCollisionMessageCapacity] = {0};
    if (inst->api.prepare(inst->instance, &view_, message, sizeof message) != TACTA_OK)
      throw InputError(where,
                       std::string("collision plugin '") + inst->descriptor.name + "': " + message);
  }
  size_t vertices = 0;
  for (const auto& s : surfaces_) vertices += s.vertex_count;
  resize_with_room(pairs_, pairs_needed(vertices));
  resize_with_room(contacts_, contacts_needed(vertices));
  refitted_once_ = false;  // the plugins' hierarchies are built again at the next refit
}

void CollisionContext::add_surface(size_t body) {
  if (body >= surface_of_body_.size() || surface_of_body_[body] >= 0) return;
  tacta_collision_surface s{};
  if (!describe_body(body, s)) return;
  const CollisionDesc& c = world_.scene().collision;
  if (c.enabled) check_thickness(c, world_, {s}, {static_cast<int>(body)});
  append(body, s);
  prepare_plugins({world_.scene().path, 0, 0, "collision"});
}

void CollisionContext::replace_surface(size_t body) {
  if (body >= surface_of_body_.size() || surface_of_body_[body] < 0) return;
  const auto k = static_cast<size_t>(surface_of_body_[body]);
  tacta_collision_surface s{};
  embedded_[body].reset();
  if (!describe_body(body, s)) return;  // a cut keeps the body's triangles: not reached
  surfaces_[k] = s;
  const SoftBody b = world_.body(body);
  freshness_[k] = fresh_surface(s, b.node_count(), embedded_[body].get(), b.nodes.positions.data());
  constexpr double kInf = std::numeric_limits<double>::infinity();
  covered_[k] = {kInf, kInf, kInf, -kInf, -kInf, -kInf};
  last_distance_[k] = 0.0;
  sightings_[k] = {};
  drop_patches(static_cast<uint32_t>(k));
  patch_triangles_.resize(std::max<size_t>(patch_triangles_.size(), s.triangle_count));
  prepare_plugins({world_.scene().path, 0, 0, "collision"});
}

// The scene's collision.plugins first (a plugin no stage loaded is loaded for its role; one that
// does not declare the role is refused at the key), then for each role left the first loaded
// plugin declaring it. A proxy serves the haptic proxy even with contact response off.
template <class Add>
void CollisionContext::pick_roles(const CollisionDesc& c, bool needed, Add& add) {
  for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r) {
    const uint32_t role = 1u << r;
    const std::string& name = c.role_plugins[r];
    if (name.empty() || !(role == TACTA_COLLISION_ROLE_PROXY ? needed : c.enabled)) continue;
    auto named = [&] {
      for (auto& inst : instances_)
        if (name == inst->descriptor.name) return inst.get();
      return static_cast<CollisionInstance*>(nullptr);
    };
    if (named() == nullptr) add(name, c.role_params[r], c.role_where[r]);
    CollisionInstance* inst = named();
    if (!(inst->roles & role))
      throw InputError(
          c.role_where[r],
          fmt::format("collision plugin '{}' does not declare the {} role (it declares: {}); "
                      "name a plugin that does (`tacta plugins` lists each plugin's roles)",
                      name, tacta_collision_role_name(role), role_names(inst->roles)));
    served_[r] = inst;
  }
  for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r)
    for (auto& inst : instances_)
      if (served_[r] == nullptr && (inst->roles & (1u << r))) served_[r] = inst.get();
}

std::string role_names(uint32_t roles) {
  std::string out;
  for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r)
    if (roles & (1u << r))
      out += (out.empty() ? "" : ", ") + std::string(tacta_collision_role_name(1u << r));
  return out.empty() ? "none" : out;
}

std::vector<CollisionPluginUse> CollisionContext::plugin_uses() const {
  std::vector<CollisionPluginUse> uses;
  for (const auto& inst : instances_) {
    CollisionPluginUse u{inst->descriptor.name, inst->roles, inst->roles_guessed, 0};
    for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r)
      if (served_[r] == inst.get()) u.serves |= 1u << r;
    uses.push_back(std::move(u));
  }
  return uses;
}

CollisionContext::~CollisionContext() = default;

bool CollisionContext::surface_present(uint32_t surface) const noexcept {
  return world_.body_present(static_cast<size_t>(body_of_surface_[surface]));
}

uint32_t CollisionContext::drop_absent(uint32_t first, uint32_t count) noexcept {
  // Contacts name bodies by id: surfaces' ids are body slots, tools' and obstacles' come after
  // the bodies the context was built with.
  const auto absent = [this](uint32_t id) {
    return id < surface_of_body_.size() && surface_of_body_[id] >= 0 &&
           !surface_present(static_cast<uint32_t>(surface_of_body_[id]));
  };
  uint32_t kept = 0;
  for (uint32_t c = first; c < first + count; ++c)
    if (!absent(contacts_[c].body_a) && !absent(contacts_[c].body_b))
      contacts_[first + kept++] = contacts_[c];
  return kept;
}

const haptics::SurfaceQuery& CollisionContext::surface_query(int body, size_t device) noexcept {
  asking_ = device < patch_slots_ ? device : 0;
  query_->restrict_to(body >= 0 && static_cast<size_t>(body) < surface_of_body_.size()
                          ? surface_of_body_[static_cast<size_t>(body)]
                          : -1);
  return *query_;
}

void CollisionContext::sync_tools() noexcept {
  world_.registry().view<Tool>().each(
      [&](ecs::Entity, const Tool& t) { tools_[t.device] = t.rigid.shape; });
}

void CollisionContext::refit(double time, double dt) noexcept {
  sync_tools();
  view_.time = time;
  view_.dt = dt;
  // Bodies on their own thread only move when a finished step is taken in: while none of the
  // surfaces moved, the hierarchies from the last update still hold (a 12k-tet liver: 0.26 ms a
  // tick saved on 9 ticks of 10).
  bool moved = !refitted_once_;
  for (size_t i = 0; i < surface_of_body_.size(); ++i) {
    if (surface_of_body_[i] < 0) continue;
    const SoftBody b = world_.body(i);
    if (!b.settings.own_thread || b.progress.refreshes != refits_seen_[i]) moved = true;
    refits_seen_[i] = b.progress.refreshes;
  }
  if (!moved) return;
  refitted_once_ = true;
  for (auto& e : embedded_)
    if (e) e->refresh(proxy_pass_);
  bool reordered = false;  // a rebuilt hierarchy may order its elements anew
  for (auto& inst : instances_) {
    if (inst->api.update == nullptr) continue;
    const uint32_t bits = inst->api.update(inst->instance, &view_);
    raised_bits_ |= bits;
    reordered = reordered || (inst.get() == slicer_ && (bits & TACTA_COLLIDE_REBUILT));
  }
  for (uint32_t k = 0; k < freshness_.size(); ++k) {
    const size_t body = static_cast<size_t>(body_of_surface_[k]);
    freshness_[k].reset(world_.body_nodes(body).positions.data());
    if (!sliced_ || (freshness_[k].bound() && !reordered)) continue;
    const uint32_t* order = nullptr;
    uint32_t total = 0;
    if (slicer_->element_order(slicer_->instance, k, &order, &total) != TACTA_COLLIDE_OK ||
        total != surfaces_[k].triangle_count) {
      freshness_[k].unbind();
      continue;
    }
    const EmbeddedCollisionSurface* e = embedded_[body].get();
    freshness_[k].bind(order, surfaces_[k].triangles, e ? e->vertex_nodes() : nullptr);
  }
}

}  // namespace tacta
