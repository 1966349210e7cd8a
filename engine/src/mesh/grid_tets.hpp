// The split of one cube cell into 6 tets around its main diagonal (Kuhn / Freudenthal). Grids use
// the symmetric split (alternating_mirror): each cell is its neighbours' mirror image, as SOFA's
// Hexa2Tetra with swapping, so no diagonal direction is preferred and a symmetric load gives a
// symmetric response; the same diagonal in every cell is 25% stiffer in bending and twists a beam.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace tacta::mesh_detail {

// corner[dx + 2 dy + 4 dz] is the node at the cell corner offset (dx, dy, dz). Appends 6 positively
// oriented tets (for cells aligned with +x, +y, +z). mirror (bit 0: x, 1: y, 2: z) splits the cell as
// if those axes were reversed, so the diagonal starts at another corner; the tets stay positive and
// the split still matches a neighbour across a face perpendicular to a mirrored axis mirrored the same way.
inline void append_cell_tets(const uint32_t corner[8], std::vector<uint32_t>& tets,
                             unsigned mirror = 0) {
  // One tet per ordering of the axes: 0 -> e_a -> e_a + e_b -> 7. Odd orderings are listed with
  // their last two nodes swapped so that all six come out positive.
  static constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 7, 5}, {0, 2, 7, 3},
                                      {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 7, 6}};
  const bool odd = ((mirror & 1) ^ ((mirror >> 1) & 1) ^ ((mirror >> 2) & 1)) !=
                   0;  // a reflection flips orientation
  for (const auto& t : kTets) {
    uint32_t v[4];
    for (int k = 0; k < 4; ++k) v[k] = corner[static_cast<unsigned>(t[k]) ^ mirror];
    if (odd) std::swap(v[2], v[3]);
    tets.insert(tets.end(), v, v + 4);
  }
}

// The mirror bits of cell (i, j, k) in the symmetric split: an axis is reversed in odd cells along it.
// Conforming: a face perpendicular to axis a is cut by the mirror bits of the other two axes, which
// the two cells sharing that face have in common.
inline unsigned alternating_mirror(int64_t i, int64_t j, int64_t k) {
  return static_cast<unsigned>((i & 1) | ((j & 1) << 1) | ((k & 1) << 2));
}

// Which of the 6 tets of append_cell_tets holds a point with local cell coordinates u, v, w in
// [0, 1]: the ordering of (u, v, w), largest first, after reversing the mirrored axes.
inline int cell_tet_of(double u, double v, double w, unsigned mirror = 0) {
  if (mirror & 1) u = 1 - u;
  if (mirror & 2) v = 1 - v;
  if (mirror & 4) w = 1 - w;
  if (u >= v && v >= w) return 0;  // x, y, z
  if (u >= w && w >= v) return 1;  // x, z, y
  if (v >= u && u >= w) return 2;  // y, x, z
  if (v >= w && w >= u) return 3;  // y, z, x
  if (w >= u && u >= v) return 4;  // z, x, y
  return 5;                        // z, y, x
}

}  // namespace tacta::mesh_detail
