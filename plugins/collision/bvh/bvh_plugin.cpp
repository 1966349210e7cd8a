// Plugin "bvh": broad phase. One bounding tree per surface over the swept boxes of its
// triangles (or tets), refit each tick and rebuilt when its quality degrades; candidate pairs
// body against body and self (elements sharing a vertex excluded); tool shapes against a body;
// and the haptic proxy's sphere cast and closest point.
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "bounding_tree.hpp"
#include "tacta/sdk/collision.hpp"
#include "triangle_queries.hpp"

namespace tacta::collision {

class BvhBroadPhase {
 public:
  static constexpr const char* kName = "bvh";
  static constexpr uint32_t kRoles = TACTA_COLLISION_ROLE_BROAD_PHASE | TACTA_COLLISION_ROLE_PROXY;
  static constexpr const char* kDescription =
      "broad phase: AABB/OBB trees refit per tick, pairs, self-collision, haptic proxy queries";
  static constexpr uint32_t kVersion = 10000;
  // The proxy queries make each triangle current (world.make_current) before reading it, and
  // test only the host's candidates when it names them.
  static constexpr uint32_t kProxyFlags =
      TACTA_COLLISION_PROXY_MAKES_CURRENT | TACTA_COLLISION_PROXY_TAKES_CANDIDATES;
  static constexpr std::array<tacta_param_spec, 4> kParams{
      sdk::choice_param("volume", "aabb|obb", 0,
                        "internal node volume: axis-aligned or principal axes"),
      sdk::real_param("rebuild_ratio", "", 1.5, 1.0, 100.0,
                      "rebuild when total node area exceeds this multiple of the area at build"),
      sdk::bool_param("self_collision", true,
                      "report pairs within one surface (adjacent excluded)"),
      sdk::choice_param("elements", "triangles|tets", 0, "elements the trees are built over"),
  };

  explicit BvhBroadPhase(const tacta_collision_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    volume_ =
        params.choice("volume") == 1 ? BoundingTree::Volume::kObb : BoundingTree::Volume::kAabb;
    rebuild_ratio_ = params.real("rebuild_ratio");
    self_collision_ = params.flag("self_collision");
    tets_ = params.choice("elements") == 1;
  }

  void prepare(const tacta_collision_world& world) {
    // The host prepares again when a body joins while the scene runs: its surface comes last and
    // the trees already built are kept, so the others' hierarchies stay as they were.
    trees_.resize(world.surface_count);
    for (uint32_t s = 0; s < world.surface_count; ++s) {
      const tacta_collision_surface& surface = world.surfaces[s];
      const ElementView view = element_view(surface);
      for (uint64_t i = 0; i < uint64_t{view.element_count} * view.vertices_per_element; ++i)
        if (view.elements[i] >= surface.vertex_count)
          throw std::invalid_argument(
              "surface " + std::to_string(s) + " (body " + std::to_string(surface.body_id) +
              "): element " + std::to_string(i / view.vertices_per_element) + " names vertex " +
              std::to_string(view.elements[i]) + ", expected below the vertex count " +
              std::to_string(surface.vertex_count));
      trees_[s].reserve(view.element_count);
    }
  }

  uint32_t update(const tacta_collision_world& world) noexcept {
    if (world.surface_count != trees_.size()) return TACTA_COLLIDE_UNPREPARED;
    uint32_t bits = 0;
    for (uint32_t s = 0; s < world.surface_count; ++s) {
      if (trees_[s].update(element_view(world.surfaces[s]), volume_, rebuild_ratio_))
        bits |= TACTA_COLLIDE_REBUILT;
      if (trees_[s].bad_elements() > 0) bits |= TACTA_COLLIDE_NOT_FINITE;
    }
    return bits;
  }

  uint32_t element_order(uint32_t surface, const uint32_t*& order, uint32_t& count) noexcept {
    if (surface >= trees_.size() || tets_ || !trees_[surface].built())
      return TACTA_COLLIDE_UNPREPARED;
    order = trees_[surface].order();
    count = trees_[surface].element_count();
    return TACTA_COLLIDE_OK;
  }

  uint32_t update_elements(const tacta_collision_world& world, uint32_t surface, uint32_t first,
                           uint32_t count) noexcept {
    if (world.surface_count != trees_.size() || surface >= trees_.size() || tets_)
      return TACTA_COLLIDE_UNPREPARED;
    if (!trees_[surface].refit_range(element_view(world.surfaces[surface]), first, count))
      return TACTA_COLLIDE_UNPREPARED;
    return trees_[surface].bad_elements() > 0 ? TACTA_COLLIDE_NOT_FINITE : TACTA_COLLIDE_OK;
  }

  uint32_t find_pairs(const tacta_collision_world& world, tacta_collision_pair* pairs,
                      uint32_t capacity, uint32_t& count) noexcept {
    count = 0;
    if (world.surface_count != trees_.size()) return TACTA_COLLIDE_UNPREPARED;
    uint32_t bits = 0;
    for (uint32_t a = 0; a < world.surface_count; ++a) {
      for (uint32_t b = a; b < world.surface_count; ++b) {
        if (a == b && !self_collision_) continue;
        const ElementView va = element_view(world.surfaces[a]);
        const bool complete = trees_[a].pairs(trees_[b], [&](uint32_t ea, uint32_t eb) {
          if (a == b && adjacent(va, ea, eb)) return;
          if (count >= capacity) {
            bits |= TACTA_COLLIDE_OVERFLOW;
            return;
          }
          pairs[count++] = {a, ea, b, eb};
        });
        if (!complete) bits |= TACTA_COLLIDE_OVERFLOW;
      }
    }
    return bits;
  }

  uint32_t overlap_shape(const tacta_collision_world& world, const tacta_collision_shape& shape,
                         uint32_t surface, uint32_t* triangles, uint32_t capacity,
                         uint32_t& count) noexcept {
    count = 0;
    if (surface >= trees_.size()) return TACTA_COLLIDE_UNPREPARED;
    uint32_t bits = 0;
    const Aabb swept = shape_box(shape);
    if (swept.empty()) return TACTA_COLLIDE_NOT_FINITE;
    const Aabb box = widened(swept, query_margin(world));
    if (!trees_[surface].query(box, [&](uint32_t e) {
          if (count >= capacity) {
            bits |= TACTA_COLLIDE_OVERFLOW;
            return;
          }
          triangles[count++] = e;
        }))
      bits |= TACTA_COLLIDE_OVERFLOW;
    return bits;
  }

  bool closest_point(const tacta_collision_world& world, uint32_t surface, const double* point,
                     double max_distance, tacta_surface_hit& hit) noexcept {
    if (surface >= world.surface_count || surface >= trees_.size() || tets_) return false;
    const tacta_collision_surface& s = world.surfaces[surface];
    const Vec3 p{point[0], point[1], point[2]};
    double best = max_distance;
    bool found = false;
    const auto test = [&](uint32_t t) {
      Vec3 x[3];
      corners(s, t, x);
      std::array<double, 3> w;
      const Vec3 q = closest_on_triangle(p, x[0], x[1], x[2], w);
      const Vec3 d = sub(p, q);
      const double dist = std::sqrt(dot(d, d));
      // Of equal distances the lowest triangle: the answer does not hang on the search order.
      if (!(dist <= best) || (found && dist == best && t > hit.triangle)) return;
      best = dist;
      found = true;
      fill_hit(hit, t, w, q, x);
      hit.distance = dist;
      hit.toi = 0.0;
    };
    if (const Candidates c(world, s); c.list != nullptr) {
      for (uint32_t i = 0; i < c.count; ++i)
        if (c.list[i] < s.triangle_count &&
            squared_distance(triangle_box(s, c.list[i]), p) <= best * best)
          test(c.list[i]);
      return found;
    }
    const CurrentMaker make_current(world, surface);
    trees_[surface].nearest(p, query_margin(world), best, [&](uint32_t t) {
      make_current(t);
      test(t);
    });
    return found;
  }

  bool sphere_cast(const tacta_collision_world& world, uint32_t surface, const double* from,
                   const double* to, double radius, tacta_surface_hit& hit) noexcept {
    if (surface >= world.surface_count || surface >= trees_.size() || tets_) return false;
    const tacta_collision_surface& s = world.surfaces[surface];
    const Vec3 a{from[0], from[1], from[2]}, b{to[0], to[1], to[2]};
    Aabb box;
    for (int k = 0; k < 3; ++k) {
      box.lo[k] = std::min(a[k], b[k]) - radius;
      box.hi[k] = std::max(a[k], b[k]) + radius;
    }
    double best = 2.0;
    const auto test = [&](uint32_t t) {
      Vec3 x[3];
      corners(s, t, x);
      const double toi = sphere_cast_triangle(a, b, radius, x[0], x[1], x[2]);
      // Of equal times the lowest triangle: the answer does not hang on the search order.
      if (toi < 0.0 || toi > best || (toi == best && t > hit.triangle)) return;
      best = toi;
      const Vec3 c{a[0] + toi * (b[0] - a[0]), a[1] + toi * (b[1] - a[1]),
                   a[2] + toi * (b[2] - a[2])};
      std::array<double, 3> w;
      const Vec3 q = closest_on_triangle(c, x[0], x[1], x[2], w);
      fill_hit(hit, t, w, q, x);
      hit.toi = toi;
      hit.distance = 0.0;
    };
    // The host's candidates met this sweep's box when it chose them: each is tested outright
    // (sphere_cast_triangle turns most away on its plane).
    if (const Candidates c(world, s); c.list != nullptr) {
      for (uint32_t i = 0; i < c.count; ++i)
        if (c.list[i] < s.triangle_count) test(c.list[i]);
      return best <= 1.0;
    }
    const CurrentMaker make_current(world, surface);
    trees_[surface].query(widened(box, query_margin(world)), [&](uint32_t t) {
      make_current(t);
      test(t);
    });
    return best <= 1.0;
  }

 private:
  // m: how far the host says vertices may be from where their boxes were computed (0 from a
  // host whose world view predates the field).
  static double query_margin(const tacta_collision_world& world) noexcept {
    const bool has = world.struct_size >=
                     offsetof(tacta_collision_world, query_margin) + sizeof(world.query_margin);
    return has && world.query_margin > 0.0 ? world.query_margin : 0.0;
  }
  // The host's make_current for one surface (nothing from a host whose world view predates it).
  struct CurrentMaker {
    CurrentMaker(const tacta_collision_world& world, uint32_t s) : surface(s) {
      if (world.struct_size >= offsetof(tacta_collision_world, make_current_context) +
                                   sizeof(world.make_current_context)) {
        call = world.make_current;
        context = world.make_current_context;
      }
    }
    void operator()(uint32_t triangle) const noexcept {
      if (call != nullptr) call(context, surface, triangle);
    }
    void (*call)(void*, uint32_t, uint32_t) = nullptr;
    void* context = nullptr;
    uint32_t surface;
  };
  // The host's candidate triangles for a proxy query (none from a host whose world view
  // predates them, or when it names none: the whole surface).
  struct Candidates {
    Candidates(const tacta_collision_world& world, const tacta_collision_surface& s) {
      if (world.struct_size >= offsetof(tacta_collision_world, proxy_candidate_count) +
                                   sizeof(world.proxy_candidate_count) &&
          s.triangles != nullptr) {
        list = world.proxy_candidates;
        count = world.proxy_candidate_count;
      }
    }
    const uint32_t* list = nullptr;
    uint32_t count = 0;
  };
  // A triangle's box from its end positions, m.
  static Aabb triangle_box(const tacta_collision_surface& s, uint32_t t) noexcept {
    Aabb box;
    const double* x = &s.positions_end[3 * size_t{s.triangles[3 * size_t{t}]}];
    box.lo = box.hi = {x[0], x[1], x[2]};
    for (int i = 1; i < 3; ++i) {
      x = &s.positions_end[3 * size_t{s.triangles[3 * size_t{t} + i]}];
      for (int k = 0; k < 3; ++k) {
        box.lo[k] = std::min(box.lo[k], x[k]);
        box.hi[k] = std::max(box.hi[k], x[k]);
      }
    }
    return box;
  }
  static Aabb widened(Aabb box, double margin) noexcept {
    for (int k = 0; k < 3; ++k) {
      box.lo[k] -= margin;
      box.hi[k] += margin;
    }
    return box;
  }

  ElementView element_view(const tacta_collision_surface& s) const noexcept {
    ElementView v;
    v.start = s.positions_start;
    v.end = s.positions_end;
    v.vertex_count = s.vertex_count;
    v.margin = s.thickness;
    if (tets_ && s.tets != nullptr) {
      v.elements = s.tets;
      v.element_count = s.tet_count;
      v.vertices_per_element = 4;
    } else {
      v.elements = s.triangles;
      v.element_count = s.triangles != nullptr ? s.triangle_count : 0;
      v.vertices_per_element = 3;
    }
    return v;
  }

  static bool adjacent(const ElementView& v, uint32_t a, uint32_t b) noexcept {
    const uint32_t n = v.vertices_per_element;
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t j = 0; j < n; ++j)
        if (v.elements[n * a + i] == v.elements[n * b + j]) return true;
    return false;
  }

  static void corners(const tacta_collision_surface& s, uint32_t t, Vec3* x) noexcept {
    for (int i = 0; i < 3; ++i) {
      const uint32_t v = s.triangles[3 * t + i];
      x[i] = {s.positions_end[3 * v], s.positions_end[3 * v + 1], s.positions_end[3 * v + 2]};
    }
  }

  static void fill_hit(tacta_surface_hit& hit, uint32_t t, const std::array<double, 3>& w,
                       const Vec3& q, const Vec3* x) noexcept {
    hit.triangle = t;
    const Vec3 e1 = sub(x[1], x[0]), e2 = sub(x[2], x[0]);
    Vec3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
           e1[0] * e2[1] - e1[1] * e2[0]};
    const double len = std::sqrt(dot(n, n));
    for (int k = 0; k < 3; ++k) {
      hit.barycentric[k] = w[k];
      hit.point[k] = q[k];
      hit.normal[k] = len > 0.0 ? n[k] / len : 0.0;
    }
  }

  // Swept axis-aligned box of a shape over the tick (both poses), m.
  static Aabb shape_box(const tacta_collision_shape& shape) noexcept {
    Aabb box;
    box.lo = {1e300, 1e300, 1e300};
    box.hi = {-1e300, -1e300, -1e300};
    for (const tacta_pose* pose : {&shape.pose_start, &shape.pose_end}) {
      // Rotation matrix rows from the quaternion (w, x, y, z).
      const double w = pose->rotation[0], x = pose->rotation[1], y = pose->rotation[2],
                   z = pose->rotation[3];
      const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                              {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                              {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
      double extent[3] = {0, 0, 0};
      double grow_by = shape.radius;
      if (shape.type == TACTA_SHAPE_CAPSULE) {
        for (int k = 0; k < 3; ++k) extent[k] = std::abs(r[k][2]) * shape.half_length;
      } else if (shape.type == TACTA_SHAPE_BOX) {
        for (int k = 0; k < 3; ++k)
          for (int j = 0; j < 3; ++j) extent[k] += std::abs(r[k][j]) * shape.half_extents[j];
        grow_by = 0.0;
      } else if (shape.type == TACTA_SHAPE_HULL && shape.points != nullptr) {
        for (uint32_t i = 0; i < shape.point_count; ++i)
          for (int k = 0; k < 3; ++k) {
            double q = 0.0;
            for (int j = 0; j < 3; ++j) q += r[k][j] * shape.points[3 * i + j];
            extent[k] = std::max(extent[k], std::abs(q));
          }
      }
      for (int k = 0; k < 3; ++k) {
        const double c = pose->position[k];
        if (!std::isfinite(c) || !std::isfinite(extent[k])) return Aabb{{1, 1, 1}, {0, 0, 0}};
        box.lo[k] = std::min(box.lo[k], c - extent[k] - grow_by);
        box.hi[k] = std::max(box.hi[k], c + extent[k] + grow_by);
      }
    }
    return box;
  }

  BoundingTree::Volume volume_ = BoundingTree::Volume::kAabb;
  double rebuild_ratio_ = 1.5;
  bool self_collision_ = true;
  bool tets_ = false;
  std::vector<BoundingTree> trees_;
};

}  // namespace tacta::collision

TACTA_PLUGIN_EXPORT(tacta::sdk::collision_descriptor<tacta::collision::BvhBroadPhase>())
