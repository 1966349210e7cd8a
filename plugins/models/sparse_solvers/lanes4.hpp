// Four doubles as one GCC vector: one AVX2 register in the x86-64-v3 clones (hot_path.hpp),
// two SSE2 ones in the baseline. Loaded and stored with memcpy (unaligned) and never passed
// to or returned from a function (that would change the ABI between the clones).
#pragma once

#include <cstring>

namespace tacta::models::sparse {

typedef double Lanes4 __attribute__((vector_size(32)));

}  // namespace tacta::models::sparse

// All four lanes set to one value.
#define TACTA_SPLAT4(value) (::tacta::models::sparse::Lanes4{(value), (value), (value), (value)})
