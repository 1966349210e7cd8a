// Cutting, as the public API and the scene see it: how a blade changes a body (CutMode) and what
// one cut did (CutSummary). docs/ARCHITECTURE.md "Cutting" has the whole path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace tacta {

// Removal (carving): the tets the blade passes through go. Separation: the body splits along
// the mesh faces the blade crosses, keeping every tet (and so its mass).
enum class CutMode : uint8_t { kRemove, kSeparate };

const char* cut_mode_name(CutMode mode) noexcept;  // "remove", "separate"
// The mode named `name` ("remove", "separate"); false for any other name.
bool parse_cut_mode(const std::string& name, CutMode& mode) noexcept;

// What one cut did to a body. A blade that misses the body changes nothing (revision stays).
struct CutSummary {
  bool changed = false;
  uint32_t revision = 0;  // the body's topology revision after the cut (0: never cut)
  size_t tets_removed = 0, nodes_removed = 0, nodes_added = 0, faces_separated = 0;
  size_t tets = 0, nodes = 0;  // the body's mesh after the cut
};

}  // namespace tacta
