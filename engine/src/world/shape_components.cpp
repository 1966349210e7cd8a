#include "world/shape_components.hpp"

#include <cmath>

#include "mesh/mesh_file_check.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {
constexpr tacta_pose kIdentityPose{{0, 0, 0}, {1, 0, 0, 0}};
}  // namespace

RigidShape build_rigid_shape(const ShapeDesc& d, uint32_t id) {
  RigidShape rigid;
  tacta_collision_shape& s = rigid.shape;
  s.body_id = id;
  s.radius = d.radius;
  s.half_length = d.half_length;
  for (int a = 0; a < 3; ++a) s.half_extents[a] = d.half_extents[static_cast<size_t>(a)];
  s.pose_start = kIdentityPose;
  for (int a = 0; a < 3; ++a) s.pose_start.position[a] = d.position[static_cast<size_t>(a)];
  s.pose_end = s.pose_start;
  switch (d.kind) {
    case ShapeDesc::Kind::Sphere: s.type = TACTA_SHAPE_SPHERE; break;
    case ShapeDesc::Kind::Capsule: s.type = TACTA_SHAPE_CAPSULE; break;
    case ShapeDesc::Kind::Box: s.type = TACTA_SHAPE_BOX; break;
    case ShapeDesc::Kind::Plane: {
      s.type = TACTA_SHAPE_PLANE;
      const double n = std::sqrt(d.normal[0] * d.normal[0] + d.normal[1] * d.normal[1] +
                                 d.normal[2] * d.normal[2]);
      for (int a = 0; a < 3; ++a)
        s.plane_normal[a] = d.normal[static_cast<size_t>(a)] / (n > 0 ? n : 1);
      s.plane_offset = d.offset;
      break;
    }
    case ShapeDesc::Kind::Mesh: {
      s.type = TACTA_SHAPE_HULL;
      require_mesh_file(d.path, d.path_where);
      rigid.hull_points = load_at(d.path_where, [&] { return load_surface(d.path).positions; });
      s.points = rigid.hull_points.data();
      s.point_count = static_cast<uint32_t>(rigid.hull_points.size() / 3);
      s.radius = 0;
      break;
    }
  }
  return rigid;
}

Tool build_tool(const ShapeDesc& desc, uint32_t id, uint32_t device) {
  Tool tool{build_rigid_shape(desc, id), device, desc.radius, 0, {}};
  if (desc.blade) {
    tool.blade.enabled = true;
    tool.blade.desc = *desc.blade;
    tool.blade.swept.reserve(9 * BladeSweep::kCapacityTriangles);
  }
  return tool;
}

}  // namespace tacta
