#include "collision/embedded_collision.hpp"

#include <algorithm>
#include <cmath>

namespace tacta {

EmbeddedCollisionSurface::EmbeddedCollisionSurface(World& world, size_t body,
                                                   EmbeddedSurface& surface, size_t node_count,
                                                   const double* node_inverse_masses)
    : world_(world), body_(body), surface_(&surface), node_inverse_masses_(node_inverse_masses) {
  const EmbeddedSurface& s = surface;
  const size_t vertices = s.vertex_count(), nodes = node_count;
  start_.assign(3 * vertices, 0.0);
  velocities_.assign(3 * vertices, 0.0);
  end_before_.assign(3 * vertices, 0.0);
  velocities_before_.assign(3 * vertices, 0.0);
  inverse_masses_.assign(vertices, 0.0);
  target_positions_.assign(3 * vertices, 0.0);
  target_velocities_.assign(3 * vertices, 0.0);
  corrected_.assign(vertices, 0);
  // A unit impulse on vertex v moves it by sum_k w_k^2 / m_k (the nodes' own responses, seen
  // through the weights): that is the vertex's inverse mass.
  for (size_t v = 0; v < vertices; ++v)
    for (size_t k = 0; k < 4; ++k)
      inverse_masses_[v] +=
          s.weights[4 * v + k] * s.weights[4 * v + k] * node_inverse_masses_[s.nodes[4 * v + k]];
  node_position_change_.assign(3 * nodes, 0.0);
  node_velocity_change_.assign(3 * nodes, 0.0);
  node_reached_.assign(nodes, 0);
  fresh_at_.assign(vertices, 0);
  for (size_t v = 0; v < vertices; ++v) {
    double sum = 0;
    for (size_t k = 0; k < 4; ++k) sum += std::fabs(s.weights[4 * v + k]);
    weight_bound_ = std::max(weight_bound_, sum);
  }
}

void EmbeddedCollisionSurface::describe(tacta_collision_surface& view) noexcept {
  EmbeddedSurface& s = *surface_;
  view.vertex_count = static_cast<uint32_t>(s.vertex_count());
  view.positions_start = start_.data();
  view.positions_end = s.positions.data();
  view.velocities = velocities_.data();
  view.inverse_masses = inverse_masses_.data();
  view.triangle_count = static_cast<uint32_t>(s.triangle_count());
  view.triangles = s.triangles.data();
  view.tet_count = 0;  // the surface's vertices are not the tets' nodes
  view.tets = nullptr;
}

void EmbeddedCollisionSurface::refresh(uint64_t pass) noexcept {
  const SoftBody b = body();
  refresh_from(b.nodes.step_start.data(), b.nodes.positions.data(), b.nodes.velocities.data(),
               pass);
}

void EmbeddedCollisionSurface::refresh_from(const double* node_start, const double* node_end,
                                            const double* velocities, uint64_t pass) noexcept {
  interpolate_to_surface(*surface_, node_start, start_.data());
  update_embedded_surface(*surface_, node_end);
  interpolate_to_surface(*surface_, velocities, velocities_.data());
  std::fill(fresh_at_.begin(), fresh_at_.end(), pass);
}

void EmbeddedCollisionSurface::refresh_triangles(const uint32_t* triangles, uint32_t count,
                                                 uint64_t pass, bool after_step) noexcept {
  if (pass != nodes_pass_ || nodes_end_ == nullptr || after_step) {
    // Looked up once a pass: a query may call this for one triangle at a time.
    nodes_end_ = world_.body_nodes(body_).positions.data();
    nodes_pass_ = pass;
  }
  const EmbeddedSurface& s = *surface_;
  for (uint32_t i = 0; i < count; ++i)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t v = s.triangles[3 * size_t{triangles[i]} + k];
      if (fresh_at_[v] == pass && !after_step) continue;
      fresh_at_[v] = pass;
      double* end = &surface_->positions[3 * size_t{v}];
      interpolate_vertex(s, v, nodes_end_, end);
      std::copy(end, end + 3, &start_[3 * size_t{v}]);
    }
}

void EmbeddedCollisionSurface::remember() noexcept {
  const EmbeddedSurface& s = *surface_;
  std::copy(s.positions.begin(), s.positions.end(), end_before_.begin());
  std::copy(velocities_.begin(), velocities_.end(), velocities_before_.begin());
}

void EmbeddedCollisionSurface::apply_response() noexcept {
  const SoftBody b = body();
  EmbeddedSurface& s = *surface_;
  // What the response asked of each vertex: its corrected end position and velocity.
  bool any = false;
  for (size_t v = 0; v < s.vertex_count(); ++v) {
    bool moved = false;
    for (size_t a = 0; a < 3; ++a)
      moved = moved || s.positions[3 * v + a] != end_before_[3 * v + a] ||
              velocities_[3 * v + a] != velocities_before_[3 * v + a];
    corrected_[v] = moved && inverse_masses_[v] > 0;
    any = any || corrected_[v];
  }
  if (!any) return;
  std::copy(s.positions.begin(), s.positions.end(), target_positions_.begin());
  std::copy(velocities_.begin(), velocities_.end(), target_velocities_.begin());
  // Averaging under-corrects where vertices share nodes: a few passes close the gap to the targets.
  constexpr int kPasses = 4;
  for (int pass = 0; pass < kPasses; ++pass) {
    interpolate_to_surface(s, b.nodes.positions.data(), s.positions.data());
    interpolate_to_surface(s, b.nodes.velocities.data(), velocities_.data());
    for (size_t v = 0; v < s.vertex_count(); ++v) {
      if (!corrected_[v]) continue;
      double position_impulse[3], velocity_impulse[3];
      for (size_t a = 0; a < 3; ++a) {
        position_impulse[a] =
            (target_positions_[3 * v + a] - s.positions[3 * v + a]) / inverse_masses_[v];
        velocity_impulse[a] =
            (target_velocities_[3 * v + a] - velocities_[3 * v + a]) / inverse_masses_[v];
      }
      spread_to_nodes(s, static_cast<uint32_t>(v), position_impulse, node_position_change_.data());
      spread_to_nodes(s, static_cast<uint32_t>(v), velocity_impulse, node_velocity_change_.data());
      for (size_t k = 0; k < 4; ++k)
        if (s.weights[4 * v + k] != 0) ++node_reached_[s.nodes[4 * v + k]];
    }
    for (size_t n = 0; n < node_reached_.size(); ++n) {
      if (node_reached_[n] == 0) continue;
      const double scale = node_inverse_masses_[n] / static_cast<double>(node_reached_[n]);
      for (size_t a = 0; a < 3; ++a) {
        b.nodes.positions[3 * n + a] += scale * node_position_change_[3 * n + a];
        b.nodes.velocities[3 * n + a] += scale * node_velocity_change_[3 * n + a];
        node_position_change_[3 * n + a] = 0;
        node_velocity_change_[3 * n + a] = 0;
      }
      node_reached_[n] = 0;
    }
  }
  refresh();
}

}  // namespace tacta
