#include "boundary/probes.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "mesh/geometry.hpp"

namespace tacta {

std::vector<Probe> locate_probes(const std::vector<ProbeDesc>& probes, const VolumeMesh& mesh,
                                 const SourceLocation& where) {
  std::vector<Probe> out;
  if (probes.empty()) return out;
  if (mesh.tets.empty())
    throw InputError(where, "probes: the body's mesh has no tetrahedra to bind a probe to");
  // A point on a face shared by two tets, or on the surface, is inside up to rounding.
  constexpr double kInsideTolerance = 1e-9;
  for (const ProbeDesc& desc : probes) {
    const Vec3 p{desc.rest[0], desc.rest[1], desc.rest[2]};
    double best = -1e300;
    Probe probe{desc.name, desc.rest, {}, {}};
    for (size_t t = 0; t < mesh.tet_count(); ++t) {
      const uint32_t* n = &mesh.tets[4 * t];
      bool far = false;  // outside the tet's bounding box: skip the weights
      for (size_t a = 0; a < 3 && !far; ++a) {
        double lo = 1e300, hi = -1e300;
        for (int c = 0; c < 4; ++c) {
          lo = std::min(lo, mesh.positions[3 * size_t{n[c]} + a]);
          hi = std::max(hi, mesh.positions[3 * size_t{n[c]} + a]);
        }
        const double margin = 1e-9 * (hi - lo + 1e-12);
        far = p[a] < lo - margin || p[a] > hi + margin;
      }
      if (far && best > -kInsideTolerance) continue;
      const auto w = mesh_detail::barycentric(
          p, mesh_detail::point(mesh.positions, n[0]), mesh_detail::point(mesh.positions, n[1]),
          mesh_detail::point(mesh.positions, n[2]), mesh_detail::point(mesh.positions, n[3]));
      const double worst = *std::min_element(w.begin(), w.end());
      if (worst > best) {
        best = worst;
        std::copy(n, n + 4, probe.nodes.begin());
        std::copy(w.begin(), w.end(), probe.weights.begin());
      }
      if (best >= 0) break;
    }
    if (best < -kInsideTolerance)
      throw InputError(where,
                       fmt::format("probes: '{}' at [{}, {}, {}] m lies outside the body's mesh",
                                   desc.name, desc.rest[0], desc.rest[1], desc.rest[2]));
    out.push_back(probe);
  }
  return out;
}

}  // namespace tacta
