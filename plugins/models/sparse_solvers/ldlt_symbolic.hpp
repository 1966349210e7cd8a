// The symbolic analysis of a sparse LDL^T factorisation: the elimination tree and how many
// entries each column of L holds below its diagonal, from the upper triangle of a symmetric
// matrix. Eigen's SimplicialLDLT::analyzePattern finds them by climbing the tree once per entry
// of L, so its cost grows with the factor's fill (tens of ms for a 48k-tet body); this takes time
// near linear in the matrix's entries (the row-subtree counts of Gilbert, Ng and Peyton, 1994).
// The results are the same numbers.
#pragma once

#include <span>

namespace tacta::models::sparse {

// upper: n columns in compressed form (outer: n + 1 starts, inner: row indices <= the column,
// no duplicates). parent[j]: j's parent in the elimination tree (-1: a root); below[j]: the
// entries of L's column j under the diagonal. Both have n entries.
void ldlt_symbolic(int n, const int* outer, const int* inner, std::span<int> parent,
                   std::span<int> below);

}  // namespace tacta::models::sparse
