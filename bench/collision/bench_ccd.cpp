// CCD ns per query on the reference queries (tests/data/ccd): conservative inclusion test
// against the plain Moore-Wilhelms (cubic roots then inside test).
#include <benchmark/benchmark.h>

#include "inclusion_ccd.hpp"
#include "plain_ccd.hpp"
#include "tacta/ccd_queries.hpp"

namespace {

const std::vector<tacta::CcdQuery>& queries() {
  static const auto all =
      tacta::read_ccd_paths({std::string(TACTA_SOURCE_DIR) + "/tests/data/ccd"});
  return all;
}

template <bool kInclusion>
void BM_CcdQuery(benchmark::State& state) {
  const auto& q = queries();
  const tacta::collision::CcdTolerance tolerance;
  size_t i = 0;
  for (auto _ : state) {
    const auto& query = q[i];
    tacta::collision::CcdResult r;
    if constexpr (kInclusion) {
      r = query.vertex_face ? tacta::collision::vertex_face_inclusion(query.points, tolerance)
                            : tacta::collision::edge_edge_inclusion(query.points, tolerance);
    } else {
      r = query.vertex_face ? tacta::collision::vertex_face_plain(query.points)
                            : tacta::collision::edge_edge_plain(query.points);
    }
    benchmark::DoNotOptimize(r);
    i = i + 1 == q.size() ? 0 : i + 1;
  }
  state.SetLabel("ns per query, mean over all reference queries in turn");
}

BENCHMARK(BM_CcdQuery<true>)->Name("ccd/inclusion_conservative");
BENCHMARK(BM_CcdQuery<false>)->Name("ccd/plain_moore_wilhelms");

}  // namespace
