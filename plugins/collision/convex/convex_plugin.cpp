// Plugin "convex": shape against shape (or a triangle) at the end-of-tick poses through libccd.
// Overlap: MPR penetration gives depth, direction and a contact point. Separated: libccd 2.0 has
// no distance query, so the distance is found by bisection on a radius r added to a's support
// (a grown by r touches b exactly when r = distance), each step one GJK intersection test.
// detect (pairs == NULL): surface vertices against tools and obstacles (vertex_shape_contacts.hpp),
// hulls through one GJK test and one MPR query per nearby vertex.
#include <array>
#include <ccd/ccd.h>
#include <cmath>

#include "tacta/sdk/collision.hpp"
#include "tacta/vec3.hpp"
#include "vertex_shape_contacts.hpp"

namespace tacta::collision {
namespace {

struct ConvexObject {
  const tacta_collision_shape* shape = nullptr;
  const double* triangle = nullptr;  // 9 doubles when shape is null
  double grow = 0.0;                 // m, extra radius (distance bisection)
  double r[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double p[3] = {0, 0, 0};
};

void set_pose(ConvexObject& o) {
  if (o.shape == nullptr) return;
  const tacta_pose& pose = o.shape->pose_end;
  const double w = pose.rotation[0], x = pose.rotation[1], y = pose.rotation[2],
               z = pose.rotation[3];
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  for (int i = 0; i < 3; ++i) {
    o.p[i] = pose.position[i];
    for (int j = 0; j < 3; ++j) o.r[i][j] = r[i][j];
  }
}

// Support point in world direction d (libccd callback).
void support(const void* object, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto& o = *static_cast<const ConvexObject*>(object);
  const double d[3] = {dir->v[0], dir->v[1], dir->v[2]};
  const double len = norm(d);
  const double u[3] = {len > 0 ? d[0] / len : 1, len > 0 ? d[1] / len : 0,
                       len > 0 ? d[2] / len : 0};
  double world[3] = {0, 0, 0};
  double radius = o.grow;
  if (o.shape == nullptr) {
    int best = 0;
    double best_dot = -1e300;
    for (int i = 0; i < 3; ++i) {
      const double s =
          o.triangle[3 * i] * u[0] + o.triangle[3 * i + 1] * u[1] + o.triangle[3 * i + 2] * u[2];
      if (s > best_dot) best_dot = s, best = i;
    }
    for (int k = 0; k < 3; ++k) world[k] = o.triangle[3 * best + k];
  } else {
    double local_dir[3];  // R^T u
    for (int k = 0; k < 3; ++k)
      local_dir[k] = o.r[0][k] * u[0] + o.r[1][k] * u[1] + o.r[2][k] * u[2];
    double local[3] = {0, 0, 0};
    const tacta_collision_shape& s = *o.shape;
    radius += s.radius;
    if (s.type == TACTA_SHAPE_CAPSULE) {
      local[2] = local_dir[2] >= 0 ? s.half_length : -s.half_length;
    } else if (s.type == TACTA_SHAPE_BOX) {
      radius -= s.radius;
      for (int k = 0; k < 3; ++k)
        local[k] = local_dir[k] >= 0 ? s.half_extents[k] : -s.half_extents[k];
    } else if (s.type == TACTA_SHAPE_HULL && s.points != nullptr && s.point_count > 0) {
      double best_dot = -1e300;
      for (uint32_t i = 0; i < s.point_count; ++i) {
        const double* q = s.points + 3 * i;
        const double dot = q[0] * local_dir[0] + q[1] * local_dir[1] + q[2] * local_dir[2];
        if (dot > best_dot) {
          best_dot = dot;
          for (int k = 0; k < 3; ++k) local[k] = q[k];
        }
      }
    }
    for (int k = 0; k < 3; ++k)
      world[k] = o.p[k] + o.r[k][0] * local[0] + o.r[k][1] * local[1] + o.r[k][2] * local[2];
  }
  for (int k = 0; k < 3; ++k) out->v[k] = world[k] + radius * u[k];
}

void center(const void* object, ccd_vec3_t* out) {
  const auto& o = *static_cast<const ConvexObject*>(object);
  for (int k = 0; k < 3; ++k)
    out->v[k] = o.shape ? o.p[k] : (o.triangle[k] + o.triangle[3 + k] + o.triangle[6 + k]) / 3.0;
}

}  // namespace

class ConvexNarrowPhase {
 public:
  static constexpr const char* kName = "convex";
  // Narrow phase of surfaces against tools and obstacles (it ignores the broad phase pairs).
  static constexpr uint32_t kRoles = TACTA_COLLISION_ROLE_NARROW_PHASE;
  static constexpr const char* kDescription =
      "convex: libccd GJK/MPR depth, normal and distance for spheres, capsules, boxes, hulls";
  static constexpr uint32_t kVersion = 10000;
  static constexpr std::array<tacta_param_spec, 1> kParams{
      sdk::real_param("tolerance", "m", 1e-9, 1e-15, 1e-3, "MPR boundary and distance tolerance"),
  };

  explicit ConvexNarrowPhase(const tacta_collision_setup& setup) {
    tolerance_ = sdk::Params(kParams, setup.params, setup.param_count).real("tolerance");
  }

  uint32_t shape_query(const tacta_collision_shape& a, const tacta_collision_shape* b,
                       const double* triangle, tacta_shape_result& out) noexcept {
    out = tacta_shape_result{};
    if (b == nullptr && triangle == nullptr) return TACTA_COLLIDE_DEGENERATE;
    if (a.type == TACTA_SHAPE_PLANE || (b && b->type == TACTA_SHAPE_PLANE))
      return TACTA_COLLIDE_DEGENERATE;  // unbounded: handled by the response's plane test
    ConvexObject oa, ob;
    oa.shape = &a;
    ob.shape = b;
    ob.triangle = triangle;
    set_pose(oa);
    set_pose(ob);
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(oa.p[k]) || !std::isfinite(ob.p[k])) return TACTA_COLLIDE_NOT_FINITE;
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = support;
    ccd.support2 = support;
    ccd.center1 = center;
    ccd.center2 = center;
    ccd.max_iterations = 200;
    ccd.mpr_tolerance = tolerance_;
    ccd.dist_tolerance = tolerance_;
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    if (ccdMPRPenetration(&oa, &ob, &ccd, &depth, &dir, &pos) == 0) {
      out.intersecting = 1;
      out.depth = depth;
      // libccd's direction moves b out of a; our normal points from b towards a.
      for (int k = 0; k < 3; ++k) {
        out.normal[k] = -dir.v[k];
        out.point_a[k] = pos.v[k] - 0.5 * depth * out.normal[k];
        out.point_b[k] = pos.v[k] + 0.5 * depth * out.normal[k];
      }
      return TACTA_COLLIDE_OK;
    }
    // Separated: bisection on the growth radius of a.
    double lo = 0.0, hi = 1.0;
    oa.grow = hi;
    for (int i = 0; i < 60 && !ccdGJKIntersect(&oa, &ob, &ccd); ++i) oa.grow = hi *= 2.0;
    for (int i = 0; i < 80 && hi - lo > tolerance_; ++i) {
      oa.grow = 0.5 * (lo + hi);
      if (ccdGJKIntersect(&oa, &ob, &ccd))
        hi = oa.grow;
      else
        lo = oa.grow;
    }
    out.distance = 0.5 * (lo + hi);
    oa.grow = hi;
    if (ccdMPRPenetration(&oa, &ob, &ccd, &depth, &dir, &pos) == 0)
      for (int k = 0; k < 3; ++k) {
        out.normal[k] = -dir.v[k];
        out.point_b[k] = pos.v[k];
        out.point_a[k] = pos.v[k] + out.distance * out.normal[k];
      }
    return TACTA_COLLIDE_OK;
  }

  // Contacts of every surface vertex with the tools and obstacles; the candidate pairs (surface
  // triangles) are for the other narrow phase and are ignored here.
  uint32_t detect(const tacta_collision_world& world, const tacta_collision_pair*, uint32_t,
                  tacta_contact* contacts, uint32_t capacity, uint32_t& count) noexcept {
    count = 0;
    return vertex_shape_contacts(world, &ConvexNarrowPhase::hull_distance, this, contacts, capacity,
                                 count);
  }

 private:
  // A ball of radius reach at x against the hull: overlap gives the signed distance reach - depth.
  static bool hull_distance(void* context, const tacta_collision_shape& hull, const double* x,
                            double reach, double& distance, double* normal, double* point) {
    const auto& self = *static_cast<const ConvexNarrowPhase*>(context);
    tacta_collision_shape ball{};
    ball.type = TACTA_SHAPE_SPHERE;
    ball.radius = reach;
    ball.pose_end = {{x[0], x[1], x[2]}, {1, 0, 0, 0}};
    ConvexObject oa, ob;
    oa.shape = &ball;
    ob.shape = &hull;
    set_pose(oa);
    set_pose(ob);
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = support;
    ccd.support2 = support;
    ccd.center1 = center;
    ccd.center2 = center;
    ccd.max_iterations = 200;
    ccd.mpr_tolerance = self.tolerance_;
    ccd.dist_tolerance = self.tolerance_;
    if (!ccdGJKIntersect(&oa, &ob, &ccd)) return false;
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    if (ccdMPRPenetration(&oa, &ob, &ccd, &depth, &dir, &pos) != 0) return false;
    distance = reach - depth;
    for (int k = 0; k < 3; ++k) {
      normal[k] = -dir.v[k];
      point[k] = x[k] - distance * normal[k];
    }
    return true;
  }

  double tolerance_ = 1e-9;
};

}  // namespace tacta::collision

TACTA_PLUGIN_EXPORT(tacta::sdk::collision_descriptor<tacta::collision::ConvexNarrowPhase>())
