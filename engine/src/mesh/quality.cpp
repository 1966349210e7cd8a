// Mesh measures: element quality, enclosed volume, closedness, lumped masses.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "mesh/geometry.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

using mesh_detail::point;

namespace {

double tet_volume(const VolumeMesh& mesh, size_t t) {
  const uint32_t* v = &mesh.tets[4 * t];
  Vec3 a = point(mesh.positions, v[0]);
  return triple(sub(point(mesh.positions, v[1]), a), sub(point(mesh.positions, v[2]), a),
                sub(point(mesh.positions, v[3]), a)) /
         6.0;
}

double polygon_area(const VolumeMesh& mesh, const uint32_t* v, size_t count) {
  Vec3 sum{0, 0, 0};
  Vec3 a = point(mesh.positions, v[0]);
  for (size_t k = 1; k + 1 < count; ++k)
    sum = add(sum,
              cross(sub(point(mesh.positions, v[k]), a), sub(point(mesh.positions, v[k + 1]), a)));
  return 0.5 * norm(sum);
}

// Longest edge over shortest altitude, scaled so that the regular tet scores 1.
double tet_aspect(const VolumeMesh& mesh, size_t t) {
  const uint32_t* v = &mesh.tets[4 * t];
  double longest = 0, largest_face = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j)
      longest =
          std::max(longest, distance(point(mesh.positions, v[i]), point(mesh.positions, v[j])));
    uint32_t face[3];
    for (int k = 0, n = 0; k < 4; ++k)
      if (k != i) face[n++] = v[k];
    largest_face = std::max(largest_face, polygon_area(mesh, face, 3));
  }
  double shortest_altitude = 3.0 * std::abs(tet_volume(mesh, t)) / largest_face;
  return longest / shortest_altitude * std::sqrt(2.0 / 3.0);
}

// Radius ratio 3 r_in / r_circ (1 for the regular tet), r_in = 3V / area, and the tet's six
// dihedral angles (radians) from the outward face normals: pi minus the angle between two of them.
double tet_shape(const VolumeMesh& mesh, size_t t, double& min_dihedral, double& max_dihedral) {
  const uint32_t* v = &mesh.tets[4 * t];
  const Vec3 o = point(mesh.positions, v[0]);
  const Vec3 a = sub(point(mesh.positions, v[1]), o), b = sub(point(mesh.positions, v[2]), o),
             c = sub(point(mesh.positions, v[3]), o);
  const double six_volume = triple(a, b, c);
  const Vec3 centre_times = add(add(scaled(cross(b, c), dot(a, a)), scaled(cross(c, a), dot(b, b))),
                                scaled(cross(a, b), dot(c, c)));
  const double circumradius = norm(centre_times) / (2.0 * std::abs(six_volume));
  static constexpr int kFace[4][3] = {
      {1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};  // opposite vertex k
  Vec3 normal[4];
  double area = 0;
  for (int f = 0; f < 4; ++f) {
    const Vec3 p0 = point(mesh.positions, v[kFace[f][0]]);
    const Vec3 n = cross(sub(point(mesh.positions, v[kFace[f][1]]), p0),
                         sub(point(mesh.positions, v[kFace[f][2]]), p0));
    area += 0.5 * norm(n);
    normal[f] = scaled(n, 1.0 / norm(n));
  }
  min_dihedral = std::numbers::pi;
  max_dihedral = 0;
  for (int f = 0; f < 4; ++f)
    for (int g = f + 1; g < 4; ++g) {
      const double angle = std::acos(std::clamp(-dot(normal[f], normal[g]), -1.0, 1.0));
      min_dihedral = std::min(min_dihedral, angle);
      max_dihedral = std::max(max_dihedral, angle);
    }
  const double inradius = 3.0 * (std::abs(six_volume) / 6.0) / area;
  return 3.0 * inradius / circumradius;
}

}  // namespace

MeshQuality mesh_quality(const VolumeMesh& mesh) {
  MeshQuality q;
  const size_t n = mesh.node_count();
  for (int k = 0; k < 3; ++k) {
    q.bounds_min[k] = n ? std::numeric_limits<double>::infinity() : 0;
    q.bounds_max[k] = n ? -std::numeric_limits<double>::infinity() : 0;
  }
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < 3; ++k) {
      q.bounds_min[k] = std::min(q.bounds_min[k], mesh.positions[3 * i + k]);
      q.bounds_max[k] = std::max(q.bounds_max[k], mesh.positions[3 * i + k]);
    }
  }
  double min_v = std::numeric_limits<double>::infinity(), max_v = 0, worst = 0;
  auto take = [&](double volume, double aspect) {
    min_v = std::min(min_v, volume);
    max_v = std::max(max_v, volume);
    worst = std::max(worst, aspect);
  };
  if (mesh.dimension == 3) {
    for (size_t t = 0; t < mesh.tet_count(); ++t) take(tet_volume(mesh, t), tet_aspect(mesh, t));
    constexpr double kDegrees = 180.0 / std::numbers::pi;
    double min_ratio = std::numeric_limits<double>::infinity(), sum_ratio = 0,
           lo = std::numbers::pi, hi = 0;
    for (size_t t = 0; t < mesh.tet_count(); ++t) {
      double tet_lo = 0, tet_hi = 0;
      const double ratio = tet_shape(mesh, t, tet_lo, tet_hi);
      min_ratio = std::min(min_ratio, ratio);
      sum_ratio += ratio;
      lo = std::min(lo, tet_lo);
      hi = std::max(hi, tet_hi);
    }
    if (mesh.tet_count() > 0) {
      q.min_radius_ratio = min_ratio;
      q.mean_radius_ratio = sum_ratio / static_cast<double>(mesh.tet_count());
      q.min_dihedral_deg = lo * kDegrees;
      q.max_dihedral_deg = hi * kDegrees;
    }
  } else {
    // Planar: area, and longest edge^2 / area (1 for a square; the right-angled half of one scores 2).
    bool quads = !mesh.quads.empty();
    const std::vector<uint32_t>& elements = quads ? mesh.quads : mesh.triangles;
    size_t per = quads ? 4 : 3;
    for (size_t e = 0; e < elements.size() / per; ++e) {
      const uint32_t* v = &elements[per * e];
      double area = polygon_area(mesh, v, per), longest = 0;
      for (size_t k = 0; k < per; ++k)
        longest = std::max(longest, distance(point(mesh.positions, v[(k + 1) % per]),
                                             point(mesh.positions, v[k])));
      take(area, longest * longest / area * (quads ? 1.0 : 0.5));
    }
  }
  q.min_volume = std::isfinite(min_v) ? min_v : 0;
  q.max_volume = max_v;
  q.worst_aspect_ratio = worst;
  double min_e = std::numeric_limits<double>::infinity(), max_e = 0;
  for (size_t e = 0; e + 1 < mesh.edges.size(); e += 2) {
    double length =
        distance(point(mesh.positions, mesh.edges[e + 1]), point(mesh.positions, mesh.edges[e]));
    min_e = std::min(min_e, length);
    max_e = std::max(max_e, length);
  }
  q.min_edge = std::isfinite(min_e) ? min_e : 0;
  q.max_edge = max_e;
  return q;
}

std::vector<double> piece_volumes(const VolumeMesh& mesh) {
  mesh_detail::NodeUnion pieces_of(mesh.node_count());
  pieces_of.join_elements(mesh.tets, 4);
  std::vector<double> volume_of_root(mesh.node_count(), 0.0);
  for (size_t t = 0; t < mesh.tet_count(); ++t)
    volume_of_root[pieces_of.root(mesh.tets[4 * t])] += std::abs(tet_volume(mesh, t));
  std::vector<double> pieces;
  for (double v : volume_of_root)
    if (v > 0) pieces.push_back(v);
  std::sort(pieces.rbegin(), pieces.rend());
  return pieces;
}

double enclosed_volume(const SurfaceMesh& surface) {
  double six_volume = 0;
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    const uint32_t* v = &surface.triangles[3 * t];
    six_volume += triple(point(surface.positions, v[0]), point(surface.positions, v[1]),
                         point(surface.positions, v[2]));
  }
  return six_volume / 6.0;
}

void check_closed(const SurfaceMesh& surface, LoadReport& report) {
  std::vector<std::array<uint32_t, 2>> edges;
  edges.reserve(surface.triangles.size());
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    for (size_t k = 0; k < 3; ++k) {
      uint32_t a = surface.triangles[3 * t + k], b = surface.triangles[3 * t + (k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  report.boundary_edges = report.nonmanifold_edges = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) ++report.boundary_edges;
    if (j - i > 2) ++report.nonmanifold_edges;
    i = j;
  }
}

std::vector<double> lumped_masses(const VolumeMesh& mesh, double density) {
  std::vector<double> masses(mesh.node_count(), 0.0);
  if (mesh.dimension == 3) {
    for (size_t t = 0; t < mesh.tet_count(); ++t) {
      double share = density * std::abs(tet_volume(mesh, t)) / 4.0;
      for (int k = 0; k < 4; ++k) masses[mesh.tets[4 * t + static_cast<size_t>(k)]] += share;
    }
    return masses;
  }
  bool quads = !mesh.quads.empty();
  const std::vector<uint32_t>& elements = quads ? mesh.quads : mesh.triangles;
  size_t per = quads ? 4 : 3;
  for (size_t e = 0; e < elements.size() / per; ++e) {
    double share = density * polygon_area(mesh, &elements[per * e], per) / static_cast<double>(per);
    for (size_t k = 0; k < per; ++k) masses[elements[per * e + k]] += share;
  }
  return masses;
}

}  // namespace tacta
