// BVH per tick: refit (or rebuild) + self and body-body candidate pairs on two deforming grids,
// at about 5k and 50k triangles in all, against brute force over all swept element boxes.
#include <benchmark/benchmark.h>
#include <random>

#include "bounding_tree.hpp"
#include "collision_world.hpp"

namespace {

using tacta::collision::BoundingTree;
using tacta::collision::ElementView;
using tacta::testing::TestSurface;

struct Scene {
  TestSurface a, b;
  std::vector<double> a_end2, b_end2;  // a second proposed end, alternated each tick
  explicit Scene(int n)
      : a(tacta::testing::grid(n, 1.0, 0, 0, 0)), b(tacta::testing::grid(n, 1.0, 0.1, 0.1, 0.01)) {
    std::mt19937 rng(7);
    tacta::testing::deform(a, rng, 0.01, 0.0);
    tacta::testing::deform(b, rng, 0.01, 1.0);
    a_end2 = a.end;
    b_end2 = b.end;
    tacta::testing::deform(a, rng, 0.01, 0.5);
    tacta::testing::deform(b, rng, 0.01, 1.5);
  }
  static ElementView view(const TestSurface& s, const std::vector<double>& end) {
    ElementView v;
    v.start = s.start.data();
    v.end = end.data();
    v.elements = s.triangles.data();
    v.element_count = static_cast<uint32_t>(s.triangles.size() / 3);
    v.vertex_count = s.vertex_count();
    v.margin = 1e-3;
    return v;
  }
};

// Grid side n gives 2 n^2 triangles per body, two bodies: n = 35 -> 4,900; n = 112 -> 50,176.
void BM_BvhTick(benchmark::State& state) {
  Scene scene(static_cast<int>(state.range(0)));
  BoundingTree ta, tb;
  ta.reserve(static_cast<uint32_t>(scene.a.triangles.size() / 3));
  tb.reserve(static_cast<uint32_t>(scene.b.triangles.size() / 3));
  const auto volume =
      state.range(1) == 1 ? BoundingTree::Volume::kObb : BoundingTree::Volume::kAabb;
  bool flip = false;
  size_t pairs = 0;
  for (auto _ : state) {
    flip = !flip;
    ta.update(Scene::view(scene.a, flip ? scene.a.end : scene.a_end2), volume, 1.5);
    tb.update(Scene::view(scene.b, flip ? scene.b.end : scene.b_end2), volume, 1.5);
    pairs = 0;
    ta.pairs(tb, [&](uint32_t, uint32_t) { ++pairs; });
    ta.pairs(ta, [&](uint32_t, uint32_t) { ++pairs; });
    tb.pairs(tb, [&](uint32_t, uint32_t) { ++pairs; });
    benchmark::DoNotOptimize(pairs);
  }
  state.counters["triangles"] = static_cast<double>(scene.a.triangles.size() / 3 * 2);
  state.counters["pairs"] = static_cast<double>(pairs);
}

void BM_BruteForceTick(benchmark::State& state) {
  Scene scene(static_cast<int>(state.range(0)));
  BoundingTree ta, tb;  // only for the element boxes, computed the same way
  ta.reserve(static_cast<uint32_t>(scene.a.triangles.size() / 3));
  tb.reserve(static_cast<uint32_t>(scene.b.triangles.size() / 3));
  ta.update(Scene::view(scene.a, scene.a.end), BoundingTree::Volume::kAabb, 1.5);
  tb.update(Scene::view(scene.b, scene.b.end), BoundingTree::Volume::kAabb, 1.5);
  const uint32_t na = static_cast<uint32_t>(scene.a.triangles.size() / 3);
  const uint32_t nb = static_cast<uint32_t>(scene.b.triangles.size() / 3);
  size_t pairs = 0;
  for (auto _ : state) {
    pairs = 0;
    for (uint32_t i = 0; i < na; ++i)
      for (uint32_t j = 0; j < nb; ++j) pairs += ta.element_box(i).overlaps(tb.element_box(j));
    for (uint32_t i = 0; i < na; ++i)
      for (uint32_t j = i + 1; j < na; ++j) pairs += ta.element_box(i).overlaps(ta.element_box(j));
    for (uint32_t i = 0; i < nb; ++i)
      for (uint32_t j = i + 1; j < nb; ++j) pairs += tb.element_box(i).overlaps(tb.element_box(j));
    benchmark::DoNotOptimize(pairs);
  }
  state.counters["triangles"] = static_cast<double>(na + nb);
  state.counters["pairs"] = static_cast<double>(pairs);
}

BENCHMARK(BM_BvhTick)
    ->Name("bvh/refit_pairs")
    ->Args({35, 0})
    ->Args({35, 1})
    ->Args({112, 0})
    ->Args({112, 1})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BruteForceTick)
    ->Name("bvh/brute_force")
    ->Arg(35)
    ->Arg(112)
    ->Iterations(2)
    ->Unit(benchmark::kMillisecond);

}  // namespace
