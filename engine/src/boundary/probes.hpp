// Probes: points of a body given in rest coordinates, bound at load time to the tetrahedron that
// holds them by barycentric weights, so that their positions follow the body (probes.csv).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tacta/mesh.hpp"
#include "tacta/scene.hpp"

namespace tacta {

struct Probe {
  std::string name;
  Vec3 rest{};                      // m
  std::array<uint32_t, 4> nodes{};  // the tet that holds it
  std::array<double, 4> weights{};  // barycentric, sum 1

  Vec3 position(const double* positions) const noexcept {
    Vec3 p{0, 0, 0};
    for (size_t c = 0; c < 4; ++c)
      for (size_t a = 0; a < 3; ++a) p[a] += weights[c] * positions[3 * size_t{nodes[c]} + a];
    return p;
  }
};

// Binds each probe to its tet. Throws InputError (at `where`) for a mesh without tetrahedra or a
// probe outside the mesh.
std::vector<Probe> locate_probes(const std::vector<ProbeDesc>& probes, const VolumeMesh& mesh,
                                 const SourceLocation& where);

}  // namespace tacta
