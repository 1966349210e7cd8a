// The paper's Moore-Wilhelms test done the plain floating-point way, kept as the baseline the
// conservative test is measured against: roots of the coplanarity cubic in [0, 1], then an
// inside test at each root with exact comparisons (no tolerance). It misses contacts when
// rounding moves a root or a barycentric coordinate across a boundary, and in the degenerate
// cases (coplanar over the whole tick, parallel edges).
#pragma once

#include "inclusion_ccd.hpp"

namespace tacta::collision {

CcdResult vertex_face_plain(const double* points) noexcept;
CcdResult edge_edge_plain(const double* points) noexcept;

}  // namespace tacta::collision
