// The engine's side of collision: the per-tick world view handed to the collision plugins
// (surfaces of the bodies, the tools, the obstacles), the plugin instances the scene names
// (broad phase, narrow phase, convex), and the per-tick pipeline: refit, candidate pairs, exact
// contacts, response. Buffers are sized at load time; the tick path allocates nothing.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "collision/proxy_freshness.hpp"
#include "collision/proxy_patch.hpp"
#include "collision/surface_replacement.hpp"
#include "tacta/collision_api.h"
#include "tacta/haptics/surface_query.hpp"
#include "tacta/plugin_registry.hpp"
#include "world/world.hpp"

namespace tacta {

class CollisionInstance;
struct PreparedCut;

// One loaded collision plugin: the roles it declares (or, guessed, its entries imply) and the
// roles the engine gave it (TACTA_COLLISION_ROLE_* bits).
struct CollisionPluginUse {
  std::string name;
  uint32_t roles = 0;
  bool roles_guessed = false;
  uint32_t serves = 0;
};

// "broad_phase, response" for a TACTA_COLLISION_ROLE_* mask ("none" for 0).
std::string role_names(uint32_t roles);
constexpr uint32_t role_index(uint32_t role) { return static_cast<uint32_t>(__builtin_ctz(role)); }
class EmbeddedCollisionSurface;

// A body's node inverse masses for the contact response, 1 per node, 1/kg: 0 for a fixed node,
// and for every node of a body stepping on its own thread.
void node_inverse_masses(const BodyTopology& topology, bool own_thread, std::vector<double>& inv);
class CollisionContext {
 public:
  // Builds the world view and the plugin instances; throws InputError (bad mesh, unknown plugin).
  CollisionContext(World& world, const PluginRegistry& plugins);
  ~CollisionContext();
  CollisionContext(const CollisionContext&) = delete;
  CollisionContext& operator=(const CollisionContext&) = delete;

  // Tool shapes (one per device, their Tool components): the host moves them each tick (pose at
  // start and end); refit and detect_and_respond copy them into the plugins' view.
  tacta_collision_shape& tool(size_t device) { return world_.tool(device).rigid.shape; }
  // Body index -> surface index in the view (-1 when the body does not collide).
  int surface_of(size_t body) const {
    return body < surface_of_body_.size() ? surface_of_body_[body] : -1;
  }
  // False while the surface's body waits to be added, and after it was removed.
  bool surface_present(uint32_t surface) const noexcept;
  int body_of(uint32_t surface) const { return body_of_surface_[surface]; }

  // A body added while the scene runs gets its surface here, on the thread that runs the ticks,
  // between them (lockstep): builds the surface, checks its thickness (InputError) and has the
  // plugins prepare again (allocates). The surface stays out of every query and contact until
  // the body enters at a tick boundary, as an event's body is until its time.
  void add_surface(size_t body);
  // A body whose mesh a cut changed: its surface is described again from the new mesh (or
  // embedded surface) and the plugins prepare again (allocates; between ticks, on the thread
  // that runs them). The hierarchies are rebuilt at the next refit (a cut calls
  // build_between_ticks for that).
  void replace_surface(size_t body);

  // A cut's collision side built off the tick, in three steps. reserve_view_copy sizes `copy`
  // for the view as it is, with room for a quarter more (allocates; off the tick). copy_view, on
  // the thread that ticks, between two ticks: the positions the plugins see, the tools and the
  // time, into `copy`; allocates nothing; false (copy.filled false) when the copy lacks room
  // (reserve again, then copy).
  void reserve_view_copy(ViewCopy& copy) const;
  bool copy_view(ViewCopy& copy) noexcept;
  // On any thread, after prepare_cut(world, body, ...) and before its apply_cut: the surface of
  // `cut`'s new shape (inverse masses, embedded surface, freshness) described over the arrays
  // the body will have once the cut is applied, and every plugin instance made again, prepared
  // and built over `copy` with that surface in it (cut.arrays' positions are filled from the
  // copy; apply_cut sets them again). Reads nothing a tick writes. Allocates. Throws InputError
  // (nothing changed) when a plugin refuses.
  SurfaceReplacement prepare_replacement(size_t body, PreparedCut& cut, const ViewCopy& copy);
  // On the thread that ticks, right after the world's apply_cut of that cut: swaps the surface
  // and the plugin instances in (`r` then holds the old ones: destroy it off the tick), and the
  // next refit refits every surface whole. Allocates nothing.
  void apply_replacement(SurfaceReplacement& r) noexcept;
  // Whether `r` still fits the view (no surface added since it was built): checked with the
  // cut's still_fits before apply_cut, else both are prepared again.
  bool replacement_fits(const SurfaceReplacement& r) const noexcept {
    return r.surface == SurfaceReplacement::kNone || r.surface_count == surfaces_.size();
  }

  // Refits the hierarchies to the bodies' current motion (start: saved positions, end: current).
  void refit(double time, double dt) noexcept;
  // After replace_surface, between ticks: the hierarchies built now, from the bodies as the last
  // tick (ending at `time`, of `dt` s) left them, so the next tick's proxy pass goes on by slices
  // instead of building them whole inside the tick (about 1 ms for the liver's fine surface).
  void build_between_ticks(double time, double dt) noexcept {
    ++proxy_pass_;
    ++proxy_whole_refits_;
    refit(time, dt);
  }
  // A restored run's hierarchies are first built where the saved run's were: at the bodies'
  // initial state, as its first tick's whole refit did (a hierarchy keeps the shape it was built
  // in until it degrades), before the checkpoint's state comes in.
  void build_as_at_start(double dt) noexcept {
    ++proxy_pass_;
    refit(0.0, dt);
    raised_bits_ = 0;  // the saved run counted them at its first tick
  }
  // Checkpoints: the proxy passes and refit counts so far (report.json collision.proxy_refits).
  std::array<uint64_t, 3> proxy_counters() const noexcept {
    return {proxy_pass_, proxy_whole_refits_, proxy_slices_};
  }
  void set_proxy_counters(const std::array<uint64_t, 3>& c) noexcept {
    // The pass may go back: no patch keeps a stamp of a pass still to come.
    for (ProxyPatch& patch : patches_) patch.drop();
    proxy_pass_ = c[0];
    proxy_whole_refits_ = c[1];
    proxy_slices_ = c[2];
  }
  // Before the haptic proxy's queries: with collision.proxy_refit sliced (and a broad phase that
  // offers update_elements) the margins take in what moved since the last upkeep_for_proxy
  // (which refits the slices, after the write), the queries are widened by what the surface may
  // have moved (SurfaceFreshness), and a margin past its cap refits whole; an embedded surface's
  // vertices are brought up to date only where a query looks (the patch near the tool).
  // Otherwise a whole refit.
  // The vertices made current stay so for the rest of this pass only because nothing moves a
  // node between this call and the proxy's last query of the tick (the reaction only adds
  // contact forces; the step and the response come after): a query made later in the tick must
  // call this again first.
  void refit_for_proxy(double time, double dt) noexcept;
  // After the tick's device write, off the haptic path (`time`: the next tick's start, s): the
  // sliced hierarchies follow what the tick moved (a slice while a margin is past its target, up
  // to four while past half its cap; a whole refit past the cap). The queries answer alike
  // whenever the slices are refit: they are widened by the margin.
  // Then the proxy's patches the tick used are made ready for the next tick's queries (gathered
  // again ahead of need, their embedded vertices made current): the haptic stage then only
  // checks them, as long as nothing moves a node between the upkeep and the next tick's queries
  // (a node moved is seen by SurfaceFreshness::last_move, and the patch made current again).
  void upkeep_for_proxy(double time, double dt) noexcept;
  // Time (ms) spent since the last refit_for_proxy in the proxy's queries, and the part of it
  // that brought embedded vertices up to date for them; for the tick breakdown.
  double query_ms() const noexcept { return query_ms_; }
  double patch_ms() const noexcept { return patch_ms_; }
  // TACTA_COLLIDE_* bits the plugins returned outside detect_and_respond (hierarchy updates,
  // slice refits, the proxy's patch queries) since the last call; clears them.
  uint32_t take_bits() noexcept { return std::exchange(raised_bits_, 0u); }
  // Whole refits the proxy path made (every tick when not sliced; when sliced, the first and
  // any whose margin passed its cap), and slices refit, since load.
  uint64_t proxy_whole_refits() const noexcept { return proxy_whole_refits_; }
  uint64_t proxy_slices() const noexcept { return proxy_slices_; }
  // Of those, the slices upkeep_for_proxy refit (after the write) since load; for tests.
  uint64_t proxy_upkeep_slices() const noexcept { return proxy_upkeep_slices_; }
  // The proxy's hierarchies are refit by slices (collision.proxy_refit sliced, and a broad phase
  // serving the proxy that offers it); false: whole, every tick.
  bool proxy_sliced() const noexcept { return sliced_; }
  // Tests: make every query's box current beforehand, as for a proxy plugin that does not call
  // make_current, even when it does (the two must touch alike).
  void set_eager_patches(bool eager) noexcept { eager_patches_ = eager; }
  // Tests: the proxy's queries search the hierarchies even where a patch could answer them (the
  // two must answer alike).
  void set_proxy_patches(bool on) noexcept { patches_on_ = on; }
  // Gathers of the proxy's patches since load, and the queries they answered.
  uint64_t patch_gathers() const noexcept { return patch_gathers_; }
  // Of those, the gathers the upkeep made ahead of need (after the write).
  uint64_t patch_upkeep_gathers() const noexcept { return patch_upkeep_gathers_; }
  uint64_t patch_queries() const noexcept { return patch_queries_; }
  // Free-space checks answered without a closest-point search (Query::clear_of), and of those
  // the ones the slices' boxes answered where the last closest points alone did not.
  uint64_t clear_answers() const noexcept { return clear_answers_; }
  uint64_t clear_bound_answers() const noexcept { return clear_bound_answers_; }
  // Contacts over the tick and the response (positions and velocities corrected in place).
  // Returns TACTA_COLLIDE_* bits.
  uint32_t detect_and_respond(double time, double dt) noexcept;
  const tacta_contact* contacts() const noexcept { return contacts_.data(); }
  uint32_t contact_count() const noexcept { return contact_count_; }

  // Answers the god-object proxy's queries against one body's surface (or every surface, -1).
  // For device `device`'s proxy: each keeps its own patches (two tools on one body do not gather
  // over each other's).
  const haptics::SurfaceQuery& surface_query(int body, size_t device = 0) noexcept;
  tacta_collision_world& view() noexcept { return view_; }

  std::vector<CollisionPluginUse> plugin_uses() const;
  // The pair and contact buffers (sized from the surfaces at load) and the most a tick used.
  uint32_t pairs_capacity() const noexcept { return static_cast<uint32_t>(pairs_.size()); }
  uint32_t contacts_capacity() const noexcept { return static_cast<uint32_t>(contacts_.size()); }
  uint32_t pairs_high_water() const noexcept { return pairs_high_water_; }
  uint32_t contacts_high_water() const noexcept { return contacts_high_water_; }

 private:
  class Query;
  // Before a proxy query on `surface` over the box lo..hi (m): the view's margin is the surface's,
  // and an embedded surface's vertices the query can reach are made current, or (a proxy plugin
  // with TACTA_COLLISION_PROXY_MAKES_CURRENT) will be as it reads them, by make_current_entry.
  void prepare_query(uint32_t surface, const Vec3& lo, const Vec3& hi) noexcept;
  // The margins take in the nodes' moves and up to max_slices of the stalest slices are refit;
  // false: a whole refit is needed (not built yet, a margin past its cap, a hierarchy that
  // cannot refit in part).
  bool refit_slices(double time, double dt, int max_slices) noexcept;
  void refit_whole_for_proxy(double time, double dt) noexcept;
  // Each run of kSliceElements in order[first, first + count) of the surface's element order
  // gives the surface's freshness its box, from the vertices where they are (current).
  void box_slices(uint32_t surface, const uint32_t* order, uint32_t first, uint32_t count) noexcept;
  static void make_current_entry(void* context, uint32_t surface, uint32_t triangle) noexcept;
  // The query over `box` is answered from the surface's patch, gathered again first when it does
  // not cover the box; false: from the hierarchy (the patch would hold too many triangles).
  bool use_patch(uint32_t surface, const ProxyPatch::Box& box, const CollisionInstance& proxy,
                 EmbeddedCollisionSurface* embedded) noexcept;
  bool gather(uint32_t surface, const ProxyPatch::Box& box, bool alone,
              const CollisionInstance& proxy) noexcept;
  // In the upkeep: each patch the tick's queries used gathered again where its slack is running
  // out, and its embedded vertices made current for the next tick.
  void prepare_patches() noexcept;
  // Of patch_triangles_[0, count), made current, those whose box meets the cube (centre, half
  // size, m) are moved to the front; returns how many.
  uint32_t keep_in_cube(uint32_t surface, const std::array<double, 3>& center, double half,
                        uint32_t count) noexcept;
  // True when a query on `surface` reads only what lies near it (an embedded surface made
  // current where a query looks, or a patch): its closest point is searched in growing balls.
  bool patched(uint32_t surface) const noexcept {
    return sliced_ && (embedded_[static_cast<size_t>(body_of_surface_[surface])] != nullptr ||
                       patches_wanted());
  }
  bool patches_wanted() const noexcept;
  // The proxy's freshness bookkeeping for surface `s` (over `embedded`, or null: the tets'
  // boundary) of a body of `node_count` nodes, current as of `nodes` (3 per node, m).
  SurfaceFreshness fresh_surface(const tacta_collision_surface& s, size_t node_count,
                                 const EmbeddedCollisionSurface* embedded,
                                 const double* nodes) const;
  // Drops contacts touching an absent body from contacts_[first, first + count); returns those kept.
  uint32_t drop_absent(uint32_t first, uint32_t count) noexcept;
  bool describe_body(size_t body, tacta_collision_surface& s);  // false: the body does not collide
  // The surface over a body's tets' boundary for `topology` and node arrays (3 per node).
  tacta_collision_surface node_surface(size_t body, const BodyTopology& topology, double* start,
                                       double* end, double* velocities,
                                       const std::vector<double>& inverse_masses) const;
  // What pairs_, contacts_ and patch_triangles_ need for surfaces of these sizes.
  size_t pairs_needed(size_t vertices) const noexcept { return 16384 + 16 * vertices; }
  size_t contacts_needed(size_t vertices) const noexcept { return 4096 + 4 * vertices; }
  void append(size_t body, const tacta_collision_surface& s);
  void prepare_plugins(const SourceLocation& where);
  void sync_tools() noexcept;  // Tool components -> the packed view
  template <class Add>
  void pick_roles(const CollisionDesc& c, bool needed, Add& add);
  World& world_;
  tacta_collision_world view_{};
  std::vector<tacta_collision_surface> surfaces_;
  std::vector<std::vector<double>> inverse_masses_;
  std::vector<tacta_collision_shape> tools_;
  std::vector<tacta_collision_shape> obstacles_;
  std::vector<int> surface_of_body_;
  std::vector<std::unique_ptr<EmbeddedCollisionSurface>>
      embedded_;                       // per body; null: its tets' boundary
  std::vector<uint64_t> refits_seen_;  // per body: its StepProgress::refreshes at the last refit
  bool refitted_once_ = false;
  std::vector<SurfaceFreshness> freshness_;     // per surface
  std::vector<std::array<double, 6>> covered_;  // per surface: box made current this pass, m
  std::vector<double> last_distance_;           // per surface: the last closest point's distance, m
  std::vector<uint32_t> patch_triangles_;       // overlap_shape's answer (capacity: triangles)
  // A query's candidates: the patch's triangles its box meets (ProxyPatch::meeting).
  std::vector<uint32_t> patch_candidates_ = std::vector<uint32_t>(ProxyPatch::kCapacity);
  // Where a surface's last closest point was asked, how far it was (or at least, by the slices'
  // boxes), and the surface's odometer_base then (for Query::clear_of); outside false: not known
  // to be outside.
  struct Sighting {
    Vec3 point{0, 0, 0};       // m
    double distance = 0;       // m
    double odometer_base = 0;  // m
    bool outside = false;
  };
  std::vector<Sighting> sightings_;  // per surface
  std::vector<ProxyPatch> patches_;  // per surface, patch_slots_ each (one per device)
  size_t patch_slots_ = 1;
  size_t asking_ = 0;  // the device whose proxy asks (surface_query)
  ProxyPatch& patch_of(uint32_t surface) noexcept {
    return patches_[surface * patch_slots_ + asking_];
  }
  void drop_patches(uint32_t surface) noexcept {
    for (size_t d = 0; d < patch_slots_; ++d) patches_[surface * patch_slots_ + d].drop();
  }
  bool patches_on_ = true;  // tests: false searches the hierarchies
  uint64_t patch_gathers_ = 0, patch_queries_ = 0, clear_answers_ = 0, patch_upkeep_gathers_ = 0;
  uint64_t clear_bound_answers_ = 0;
  bool sliced_ = false;                        // refit_for_proxy refits slices
  bool eager_patches_ = false;                 // tests: the box pass even for MAKES_CURRENT
  const CollisionInstance* slicer_ = nullptr;  // the plugin whose hierarchies are sliced
  uint64_t proxy_pass_ = 0;  // proxy passes (the haptic stage's and the upkeep's), for freshness
  double query_ms_ = 0, patch_ms_ = 0;
  uint32_t raised_bits_ = 0;  // see take_bits()
  uint64_t proxy_whole_refits_ = 0, proxy_slices_ = 0, proxy_upkeep_slices_ = 0;
  std::vector<int> body_of_surface_;
  std::vector<std::unique_ptr<CollisionInstance>> instances_;  // broad, narrow, convex (as named)
  std::vector<tacta_collision_pair> pairs_;
  std::vector<tacta_contact> contacts_;
  uint32_t contact_count_ = 0;
  uint32_t pairs_high_water_ = 0, contacts_high_water_ = 0;
  std::array<CollisionInstance*, TACTA_COLLISION_ROLE_COUNT> served_{};  // per role index
  bool response_enabled_ = false;
  std::unique_ptr<Query> query_;
};

}  // namespace tacta
