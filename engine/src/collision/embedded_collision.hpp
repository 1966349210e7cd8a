// The collision layer's side of a body's embedded surface (tacta/embedded_surface.hpp): the
// surface vertices are what the collision plugins see (start and end of the tick, velocities,
// inverse masses), and what the contact response does to them goes back to the tet nodes by the
// transpose of the embedding weights. Buffers are sized at load time; no allocation per tick.
#pragma once

#include <cstdint>
#include <vector>

#include "tacta/collision_api.h"
#include "world/world.hpp"

namespace tacta {

class EmbeddedCollisionSurface {
 public:
  // Body `body`'s `surface` over `node_count` nodes (the body's shape, or one a cut prepared
  // that becomes the body's when applied: the per-tick entries read the body's nodes and the
  // surface then). node_inverse_masses: 1 per node, 1/kg (0 fixed); its buffer must outlive
  // this object (a vector swapped elsewhere keeps it). The vertices are current once refreshed.
  EmbeddedCollisionSurface(World& world, size_t body, EmbeddedSurface& surface, size_t node_count,
                           const double* node_inverse_masses);
  // Points the plugin view at the surface's arrays.
  void describe(tacta_collision_surface& view) noexcept;
  // Start positions from the body's saved (start of tick) state, end positions, normals and
  // velocities from its current one; every vertex is then current as of proxy pass `pass`.
  void refresh(uint64_t pass = 0) noexcept;
  // The same from given node arrays (3 per node: start of tick, end, velocities), e.g. copies
  // of the body's taken for a build off the tick.
  void refresh_from(const double* node_start, const double* node_end, const double* velocities,
                    uint64_t pass) noexcept;
  // End positions of the listed triangles' vertices only, skipping those already current as of
  // `pass`: the slices a hierarchy is refit by and the patch the proxy's queries read. Their
  // start is set to their end: the proxy reads only where vertices are, and the boxes a slice
  // refit computes from start and end need be no wider. refresh(), which runs before a contact
  // response, makes start, end and velocities whole again. `after_step`: the nodes moved since
  // the pass's queries made vertices current (the upkeep after the write): none is skipped.
  void refresh_triangles(const uint32_t* triangles, uint32_t count, uint64_t pass,
                         bool after_step = false) noexcept;
  // Largest sum of |weight| over the vertices: no vertex moves further than this times the
  // furthest-moving node (1 inside the tets, more for extrapolated vertices).
  double weight_bound() const noexcept { return weight_bound_; }
  static constexpr uint32_t kNodesPerVertex = 4;  // a vertex follows its tet's nodes
  const uint32_t* vertex_nodes() const noexcept { return surface_->nodes.data(); }
  // Before the response: keeps the surface's end positions and velocities to see what it changed.
  void remember() noexcept;
  // After it: each vertex's correction is an impulse (its change over its inverse mass), spread
  // to the nodes by the weights (the transpose of the interpolation); a node reached by several
  // corrected vertices takes their mean, so a tet pushed by many vertices is not pushed many
  // times, and a few such passes bring the vertices to where the response put them. Then the
  // surface follows the nodes.
  void apply_response() noexcept;

 private:
  SoftBody body() noexcept { return world_.body(body_); }

  World& world_;
  size_t body_;
  EmbeddedSurface* surface_;
  const double* node_inverse_masses_;
  std::vector<double> start_;           // 3 per vertex, m
  std::vector<double> velocities_;      // 3 per vertex, m/s
  std::vector<double> inverse_masses_;  // 1 per vertex, 1/kg: sum of w^2 / m over its tet's nodes
  std::vector<double> end_before_;      // 3 per vertex, m
  std::vector<double> velocities_before_;     // 3 per vertex, m/s
  std::vector<double> target_positions_;      // 3 per vertex, m: where the response put it
  std::vector<double> target_velocities_;     // 3 per vertex, m/s
  std::vector<uint8_t> corrected_;            // 1 per vertex: the response changed it
  std::vector<double> node_position_change_;  // 3 per node, m
  std::vector<double> node_velocity_change_;  // 3 per node, m/s
  std::vector<uint32_t> node_reached_;        // 1 per node: corrected vertices that reach it
  std::vector<uint64_t> fresh_at_;  // 1 per vertex: the proxy pass it was last made current
  // The body's node arrays refresh_triangles reads in pass nodes_pass_ (its arrays change only
  // between ticks; each tick's haptic stage and upkeep are passes of their own).
  const double* nodes_end_ = nullptr;
  uint64_t nodes_pass_ = 0;
  double weight_bound_ = 1.0;
};

}  // namespace tacta
