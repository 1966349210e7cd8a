// CollisionContext's side of the haptic proxy: the hierarchies refit a slice at a time while
// the bodies move (SurfaceFreshness), and an embedded surface's vertices brought up to date where
// a query looks: each triangle it reads (a plugin that calls make_current), else every triangle
// in its box beforehand.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include "collision/collision_context.hpp"
#include "collision/collision_instance.hpp"
#include "collision/embedded_collision.hpp"
#include "collision/proxy_patch.hpp"

namespace tacta {

namespace {
constexpr int kMaxSlicesPerTick = 4;  // while the margin is past half its cap (the upkeep's)
// The upkeep gathers a patch in use again while its last query's box, grown by this share of
// its side on every side, leaves the cube: a few millimetres of slack for the next ticks.
constexpr double kAheadShare = 0.25;
}  // namespace

void CollisionContext::refit_for_proxy(double time, double dt) noexcept {
  ++proxy_pass_;  // every embedded vertex is stale until made current in this pass
  query_ms_ = patch_ms_ = 0;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (auto& c : covered_) c = {kInf, kInf, kInf, -kInf, -kInf, -kInf};
  if (!sliced_) {
    ++proxy_whole_refits_;
    refit(time, dt);
    return;
  }
  // The slices are the upkeep's, after the last tick's write: here the margins take in what
  // moved since (nothing, in a tick as the loop runs it), and a margin past its cap refits whole.
  if (!refit_slices(time, dt, 0)) {
    refit_whole_for_proxy(time, dt);
    return;
  }
  // The patches the upkeep made current (prepare_patches) still are where nothing the surface
  // follows has moved since: their vertices are where the nodes put them.
  for (uint32_t k = 0; k < view_.surface_count; ++k) {
    if (!surface_present(k) || !(freshness_[k].last_move() == 0.0)) continue;
    for (size_t d = 0; d < patch_slots_; ++d) {
      ProxyPatch& patch = patches_[k * patch_slots_ + d];
      if (!patch.held()) continue;
      if (patch.made_current_in() == proxy_pass_ - 1) patch.set_made_current_in(proxy_pass_);
      if (patch.boxes_in() == proxy_pass_ - 1) patch.set_boxes_in(proxy_pass_);
    }
  }
}

void CollisionContext::upkeep_for_proxy(double time, double dt) noexcept {
  if (!sliced_ || !refitted_once_) return;  // refit whole every tick, or not built yet
  // A pass of its own: the step has moved the nodes since the tick's queries made vertices
  // current, and what it makes current now serves the next tick's queries.
  ++proxy_pass_;
  const uint64_t before = proxy_slices_;
  if (!refit_slices(time, dt, kMaxSlicesPerTick)) {
    refit_whole_for_proxy(time, dt);
    return;
  }
  proxy_upkeep_slices_ += proxy_slices_ - before;
  prepare_patches();
}

void CollisionContext::prepare_patches() noexcept {
  if (!patches_wanted()) return;
  const CollisionInstance& proxy = *served_[role_index(TACTA_COLLISION_ROLE_PROXY)];
  const size_t asking = asking_;
  for (uint32_t k = 0; k < view_.surface_count; ++k) {
    if (!surface_present(k)) continue;
    EmbeddedCollisionSurface* e = embedded_[static_cast<size_t>(body_of_surface_[k])].get();
    for (size_t d = 0; d < patch_slots_; ++d) {
      asking_ = d;
      ProxyPatch& patch = patch_of(k);
      // Only the patches the tick's queries used (the pass before this one).
      if (!patch.held() || patch.served_in() != proxy_pass_ - 1) continue;
      // Gathered again here, while the last query's box grown by kAheadShare of its side on every
      // side no longer fits the cube (less the surface's travel since): the next tick's queries,
      // the tool and the surface a little further on, then find it ready.
      const ProxyPatch::Box& last = patch.last_served();
      double side = 0.0;
      for (int a = 0; a < 3; ++a) side = std::max(side, last[a + 3] - last[a]);
      ProxyPatch::Box ahead = last;
      for (int a = 0; a < 3; ++a) {
        ahead[a] -= kAheadShare * side;
        ahead[a + 3] += kAheadShare * side;
      }
      if (!patch.covers(ahead, freshness_[k].odometer()) &&
          patch.worth_gathering(last, proxy_pass_)) {
        view_.query_margin = freshness_[k].margin();
        const uint64_t before = patch_gathers_;
        if (gather(k, last, false, proxy) || (patch.widens(last) && gather(k, last, true, proxy)))
          patch.note_served(last, proxy_pass_ - 1);  // still the patch in use
        // A failed gather leaves the patch as it was: still good while queries fit its cube.
        patch_upkeep_gathers_ += patch_gathers_ - before;
      }
      if (e != nullptr) {
        e->refresh_triangles(patch.triangles(), patch.count(), proxy_pass_);
        patch.set_made_current_in(proxy_pass_);
      }
      patch.set_boxes(surfaces_[k].positions_end, surfaces_[k].triangles, proxy_pass_);
    }
  }
  asking_ = asking;
  view_.query_margin = 0.0;  // as every proxy query leaves it: other callers read boxes as current
}

void CollisionContext::refit_whole_for_proxy(double time, double dt) noexcept {
  ++proxy_whole_refits_;
  refitted_once_ = false;  // a whole refit, whatever moved (the margin restarts from it)
  refit(time, dt);
  // The free-space check's boxes, every vertex being current: here only, where the refit is the
  // proxy's own (rare). The contact rounds' refits (collision response on: up to three a tick)
  // leave them unknown, as a box pass over the whole surface each would cost 0.05 ms a tick on
  // the demo.
  for (uint32_t k = 0; sliced_ && k < view_.surface_count; ++k) {
    const uint32_t* order = nullptr;
    uint32_t total = 0;
    if (freshness_[k].bound() &&
        slicer_->element_order(slicer_->instance, k, &order, &total) == TACTA_COLLIDE_OK &&
        total == surfaces_[k].triangle_count)
      box_slices(k, order, 0, total);
  }
}

bool CollisionContext::refit_slices(double time, double dt, int max_slices) noexcept {
  bool whole = !refitted_once_;
  for (uint32_t k = 0; k < view_.surface_count; ++k) {
    if (!surface_present(k)) {  // its moves are not followed while it is away
      drop_patches(k);
      sightings_[k] = {};
    } else if (!whole &&
               !freshness_[k].advance(
                   world_.body_nodes(static_cast<size_t>(body_of_surface_[k])).positions.data())) {
      whole = true;  // a margin past its cap
    }
  }
  if (whole) return false;
  sync_tools();
  view_.time = time;
  view_.dt = dt;
  for (uint32_t k = 0; k < view_.surface_count; ++k) {
    if (!surface_present(k)) continue;
    uint32_t first = 0, count = 0, total = 0;
    const uint32_t* order = nullptr;
    if (slicer_->element_order(slicer_->instance, k, &order, &total) != TACTA_COLLIDE_OK ||
        total != surfaces_[k].triangle_count)
      return false;  // no hierarchy yet, or one over other elements than triangles (tets)
    // One slice while the margin is past its target, up to max_slices while a fast body keeps
    // it past half its cap: the cost follows the motion, and a whole refit (a spike of the
    // whole surface's cost) waits for motion faster than that.
    for (int n = 0; n < max_slices; ++n) {
      freshness_[k].next_slice(first, count);
      if (count == 0) break;
      // After the step: in the upkeep's own pass, and (after_step) recomputed even where this
      // pass already made them current, as the slice's boxes need them where they are now.
      if (EmbeddedCollisionSurface* e = embedded_[static_cast<size_t>(body_of_surface_[k])].get())
        e->refresh_triangles(order + first, count, proxy_pass_, true);
      // UNPREPARED (no hierarchy to refit in part) is answered here by a whole refit.
      const uint32_t bits = slicer_->update_elements(slicer_->instance, &view_, k, first, count);
      raised_bits_ |= bits & ~uint32_t{TACTA_COLLIDE_UNPREPARED};
      if (bits & TACTA_COLLIDE_UNPREPARED) return false;
      box_slices(k, order, first, count);
      ++proxy_slices_;
      if (n == 0 && !(freshness_[k].margin() > 0.5 * freshness_[k].margin_cap())) break;
    }
  }
  return true;
}

void CollisionContext::box_slices(uint32_t surface, const uint32_t* order, uint32_t first,
                                  uint32_t count) noexcept {
  const tacta_collision_surface& s = surfaces_[surface];
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (uint32_t start = first; start < first + count; start += SurfaceFreshness::kSliceElements) {
    const uint32_t end = std::min(first + count, start + SurfaceFreshness::kSliceElements);
    std::array<double, 6> box{kInf, kInf, kInf, -kInf, -kInf, -kInf};
    double finite = 0.0;  // 0 * x is NaN for a NaN or infinite x
    for (uint32_t e = start; e < end; ++e)
      for (size_t c = 0; c < 3; ++c) {
        const double* x = &s.positions_end[3 * size_t{s.triangles[3 * size_t{order[e]} + c]}];
        for (size_t a = 0; a < 3; ++a) {
          box[a] = std::min(box[a], x[a]);
          box[a + 3] = std::max(box[a + 3], x[a]);
          finite += 0.0 * x[a];
        }
      }
    if (std::isnan(finite)) box = {-kInf, -kInf, -kInf, kInf, kInf, kInf};  // holds every point
    freshness_[surface].set_slice_box(start, box);
  }
}

void CollisionContext::make_current_entry(void* context, uint32_t surface,
                                          uint32_t triangle) noexcept {
  auto& c = *static_cast<CollisionContext*>(context);
  if (surface >= c.view_.surface_count || triangle >= c.surfaces_[surface].triangle_count) return;
  EmbeddedCollisionSurface* e = c.embedded_[static_cast<size_t>(c.body_of_surface_[surface])].get();
  if (e != nullptr) e->refresh_triangles(&triangle, 1, c.proxy_pass_);
}

bool CollisionContext::patches_wanted() const noexcept {
  const CollisionInstance* proxy = served_[role_index(TACTA_COLLISION_ROLE_PROXY)];
  return patches_on_ && !eager_patches_ && proxy != nullptr &&
         (proxy->proxy_flags & TACTA_COLLISION_PROXY_TAKES_CANDIDATES) != 0 &&
         proxy->api.overlap_shape != nullptr;
}

void CollisionContext::prepare_query(uint32_t surface, const Vec3& lo, const Vec3& hi) noexcept {
  // No candidates unless a patch answers this query: a search that falls back to the hierarchy
  // (a growing ball's second try, another surface) must not read the last one's.
  view_.proxy_candidates = nullptr;
  view_.proxy_candidate_count = 0;
  // The query widens its search by how far any vertex may be from its element's box.
  view_.query_margin = sliced_ ? freshness_[surface].margin() : 0.0;
  if (!sliced_) return;
  EmbeddedCollisionSurface* e = embedded_[static_cast<size_t>(body_of_surface_[surface])].get();
  const CollisionInstance* proxy = served_[role_index(TACTA_COLLISION_ROLE_PROXY)];
  if (patches_wanted() && use_patch(surface, {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]}, *proxy, e))
    return;
  if (e == nullptr) return;
  if ((proxy->proxy_flags & TACTA_COLLISION_PROXY_MAKES_CURRENT) != 0 && !eager_patches_) {
    // The query makes current each triangle it reads, and nothing else.
    view_.make_current = &make_current_entry;
    view_.make_current_context = this;
    return;
  }
  std::array<double, 6>& c = covered_[surface];
  if (c[0] <= lo[0] && c[1] <= lo[1] && c[2] <= lo[2] && hi[0] <= c[3] && hi[1] <= c[4] &&
      hi[2] <= c[5])
    return;
  const auto start = std::chrono::steady_clock::now();
  // An embedded surface's vertices are current only where a query looked this tick: those of
  // every triangle the widened box reaches (the hull of this box and what was covered) are
  // brought up to date, so the query reads where they are now.
  for (size_t a = 0; a < 3; ++a) {
    c[a] = std::min(c[a], lo[a]);
    c[a + 3] = std::max(c[a + 3], hi[a]);
  }
  tacta_collision_shape box{};
  box.type = TACTA_SHAPE_BOX;
  for (size_t a = 0; a < 3; ++a) {
    box.half_extents[a] = 0.5 * (c[a + 3] - c[a]);
    box.pose_start.position[a] = 0.5 * (c[a + 3] + c[a]);
  }
  box.pose_start.rotation[0] = 1.0;
  box.pose_end = box.pose_start;
  uint32_t count = 0;
  raised_bits_ |=
      proxy->api.overlap_shape(proxy->instance, &view_, &box, surface, patch_triangles_.data(),
                               static_cast<uint32_t>(patch_triangles_.size()), &count);
  e->refresh_triangles(patch_triangles_.data(), count, proxy_pass_);
  patch_ms_ +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

bool CollisionContext::use_patch(uint32_t surface, const ProxyPatch::Box& box,
                                 const CollisionInstance& proxy,
                                 EmbeddedCollisionSurface* embedded) noexcept {
  ProxyPatch& patch = patch_of(surface);
  const bool gathering = !patch.covers(box, freshness_[surface].odometer());
  if (gathering && !patch.worth_gathering(box, proxy_pass_)) return false;
  const bool refreshing = embedded != nullptr && patch.made_current_in() != proxy_pass_;
  if (!gathering && !refreshing) {
    patch.note_served(box, proxy_pass_);
  } else {
    // Timed only when there is work (a gather, or the tick's first refresh): two clock reads on
    // every query would cost about what the query does.
    const auto start = std::chrono::steady_clock::now();
    // The cube for the queries the patch served, or for this one alone when that is too many.
    const bool held = !gathering || gather(surface, box, false, proxy) ||
                      (patch.widens(box) && gather(surface, box, true, proxy));
    if (held && embedded != nullptr && patch.made_current_in() != proxy_pass_) {
      embedded->refresh_triangles(patch.triangles(), patch.count(), proxy_pass_);
      patch.set_made_current_in(proxy_pass_);
    }
    patch_ms_ +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!held) return false;
    patch.note_served(box, proxy_pass_);
  }
  ++patch_queries_;
  // The pass's positions stay put through its queries: the boxes are computed once a pass (or
  // carried from the upkeep's), and each query gets the triangles its box meets.
  if (patch.boxes_in() != proxy_pass_)
    patch.set_boxes(surfaces_[surface].positions_end, surfaces_[surface].triangles, proxy_pass_);
  view_.proxy_candidates = patch_candidates_.data();
  view_.proxy_candidate_count = patch.meeting(box, patch_candidates_.data());
  return true;
}

bool CollisionContext::gather(uint32_t surface, const ProxyPatch::Box& box, bool alone,
                              const CollisionInstance& proxy) noexcept {
  ProxyPatch& patch = patch_of(surface);
  std::array<double, 3> center{};
  double half = 0.0;
  patch.cube_for(box, alone, center, half);
  tacta_collision_shape cube{};
  cube.type = TACTA_SHAPE_BOX;
  for (size_t a = 0; a < 3; ++a) {
    cube.half_extents[a] = half;
    cube.pose_start.position[a] = center[a];
  }
  cube.pose_start.rotation[0] = 1.0;
  cube.pose_end = cube.pose_start;
  uint32_t count = 0;
  // Widened by the margin (set by prepare_query): every triangle that may be in the cube.
  const uint32_t bits =
      proxy.api.overlap_shape(proxy.instance, &view_, &cube, surface, patch_triangles_.data(),
                              static_cast<uint32_t>(patch_triangles_.size()), &count);
  raised_bits_ |= bits;
  ++patch_gathers_;
  if (bits == TACTA_COLLIDE_OK) count = keep_in_cube(surface, center, half, count);
  return bits == TACTA_COLLIDE_OK && patch.keep(center, half, patch_triangles_.data(), count, box,
                                                proxy_pass_, freshness_[surface].odometer_base());
}

uint32_t CollisionContext::keep_in_cube(uint32_t surface, const std::array<double, 3>& center,
                                        double half, uint32_t count) noexcept {
  // The hierarchy's answer holds every triangle that may be within the margin of the cube; made
  // current, those whose box is clear of the cube itself are dropped (with a margin of a mean
  // edge or more, most of them).
  const tacta_collision_surface& s = surfaces_[surface];
  if (EmbeddedCollisionSurface* e = embedded_[static_cast<size_t>(body_of_surface_[surface])].get())
    e->refresh_triangles(patch_triangles_.data(), count, proxy_pass_);
  uint32_t kept = 0;
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t t = patch_triangles_[i];
    bool clear = false;
    for (size_t a = 0; a < 3 && !clear; ++a) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (size_t c = 0; c < 3; ++c) {
        const double x = s.positions_end[3 * size_t{s.triangles[3 * size_t{t} + c]} + a];
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      clear = !(lo <= center[a] + half && hi >= center[a] - half);  // NaN: clear, never kept
    }
    if (!clear) patch_triangles_[kept++] = t;
  }
  return kept;
}

// Rounds of detect + respond: the response's corrections are motions too, and can cross a
// face that the first round never tested; the next round's CCD (start -> corrected end) finds
// those. Rounds stop when a round finds no surface-surface contact. Contacts of all rounds are
// published (a resting contact found again has a force near zero: its velocity was corrected).
uint32_t CollisionContext::detect_and_respond(double time, double dt) noexcept {
  sync_tools();
  constexpr int kMaxRounds = 3;
  contact_count_ = 0;
  if (!response_enabled_) return TACTA_COLLIDE_OK;
  uint32_t bits = 0;
  const CollisionInstance* broad = served_[role_index(TACTA_COLLISION_ROLE_BROAD_PHASE)];
  const CollisionInstance* narrow = served_[role_index(TACTA_COLLISION_ROLE_NARROW_PHASE)];
  const CollisionInstance* response = served_[role_index(TACTA_COLLISION_ROLE_RESPONSE)];
  const bool self_collision = world_.scene().collision.self_collision;
  // Bodies waiting to be added, or removed, are out of every pair and contact.
  bool all_present = true;
  for (uint32_t k = 0; k < view_.surface_count; ++k)
    all_present = all_present && surface_present(k);
  for (int round = 0; round < kMaxRounds; ++round) {
    refit(time, dt);
    uint32_t pair_count = 0;
    // One surface and no self-collision: every pair the broad phase could find would be dropped.
    if (broad != nullptr && broad->api.find_pairs != nullptr &&
        (self_collision || view_.surface_count > 1))
      bits |= broad->api.find_pairs(broad->instance, &view_, pairs_.data(),
                                    static_cast<uint32_t>(pairs_.size()), &pair_count);
    if (!self_collision ||
        !all_present) {  // collision.self_collision off: drop pairs within one surface
      uint32_t kept = 0;
      for (uint32_t p = 0; p < pair_count; ++p)
        if ((self_collision || pairs_[p].surface_a != pairs_[p].surface_b) &&
            surface_present(pairs_[p].surface_a) && surface_present(pairs_[p].surface_b))
          pairs_[kept++] = pairs_[p];
      pair_count = kept;
    }
    pairs_high_water_ = std::max(pairs_high_water_, pair_count);
    // Every narrow phase detects; the one serving the role gets the broad phase's pairs, the
    // others (convex: surfaces against tools and obstacles) the whole world (pairs NULL).
    const uint32_t first = contact_count_;
    for (auto& inst : instances_) {
      if (inst->api.detect == nullptr || !(inst->roles & TACTA_COLLISION_ROLE_NARROW_PHASE))
        continue;
      uint32_t found = 0;
      const bool pairwise = inst.get() == narrow && broad != nullptr;
      bits |= inst->api.detect(inst->instance, &view_, pairwise ? pairs_.data() : nullptr,
                               pairwise ? pair_count : 0, contacts_.data() + contact_count_,
                               static_cast<uint32_t>(contacts_.size()) - contact_count_, &found);
      if (!all_present) found = drop_absent(contact_count_, found);
      contact_count_ += found;
    }
    for (auto& e : embedded_)
      if (e) e->remember();
    if (response != nullptr && response->api.respond != nullptr)
      bits |= response->api.respond(response->instance, &view_, contacts_.data() + first,
                                    contact_count_ - first);
    for (auto& e : embedded_)
      if (e) e->apply_response();
    bool surface_contacts = false;
    for (uint32_t c = first; c < contact_count_; ++c)
      surface_contacts = surface_contacts || contacts_[c].type == TACTA_CONTACT_VERTEX_FACE ||
                         contacts_[c].type == TACTA_CONTACT_EDGE_EDGE;
    if (!surface_contacts) break;
  }
  contacts_high_water_ = std::max(contacts_high_water_, contact_count_);
  return bits;
}

}  // namespace tacta
