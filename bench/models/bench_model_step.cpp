// Step time of every elastic model plugin against mesh size (about 500, 2k, 10k and 50k tets),
// all driven through the C ABI, on a clamped box under gravity at the haptic tick (dt = 1 ms).
// The 1 kHz budget is 1 ms per tick for everything (collision, haptics, every body), so a
// model's step should stay well below it. Models whose plugin is not built are skipped.
#include <algorithm>
#include <benchmark/benchmark.h>
#include <ctime>
#include <string>
#include <vector>

#include "bench_meshes.hpp"
#include "plugin_body.hpp"

namespace tacta::bench {
namespace {

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

struct ModelCase {
  const char* label;
  const char* file;
  const char* model;
  std::vector<ParamOverride> overrides;
  uint32_t max_cells;  // skip sizes above this (cells per side), where a step takes too long
};

const std::vector<ModelCase>& model_cases() {
  static const std::vector<ModelCase> cases = {
      {"corotational_pcg", "tacta_corotational_fem.so", "corotational_fem", {}, 20},
      {"corotational_cholesky",
       "tacta_corotational_fem.so",
       "corotational_fem",
       {{"solver", 1, "cholesky"}},
       12},
      {"hyperelastic", "tacta_hyperelastic.so", "hyperelastic", {}, 12},
      {"hyperelastic_1_newton",
       "tacta_hyperelastic.so",
       "hyperelastic",
       {{"newton_iterations", 1, nullptr}},
       12},
      {"hyperelastic_cg_1e-5",
       "tacta_hyperelastic.so",
       "hyperelastic",
       {{"tolerance", 1e-5, nullptr}},
       12},
      {"hyperelastic_nodal_average",
       "tacta_hyperelastic.so",
       "hyperelastic",
       {{"volumetric", 2, "nodal_average"}},
       12},
      {"hyperelastic_fresh_tangent",
       "tacta_hyperelastic.so",
       "hyperelastic",
       {{"tangent_reuse_steps", 0, nullptr}, {"tolerance", 1e-6, nullptr}},
       12},
      {"bullet_softbody", "tacta_bullet_softbody.so", "bullet_softbody", {}, 20},
      {"mass_spring", "tacta_mass_spring.so", "mass_spring", {}, 20},
      {"tensor_mass", "tacta_tensor_mass.so", "tensor_mass", {}, 20},
      {"fd_debunne", "tacta_fd_debunne.so", "fd_debunne", {}, 20},
  };
  return cases;
}

void step_by_size(benchmark::State& state, const ModelCase& model, uint32_t cells, uint32_t extra) {
  const models::TestMesh mesh = clamped_box(cells, extra);
  // Soft tissue-like, and soft enough (c_p = 4.6 m/s, dt_crit about 2 ms on 1 cm cells) that
  // the explicit models are stable at the 1 ms tick too, so every model is timed doing work.
  tacta_material material = models::make_material(1e4, 0.4, 1000.0);
  material.rayleigh_mass = 0.1;
  material.rayleigh_stiffness = 0.01;
  PluginBody body(model.file, model.model, mesh, material, {0.0, -9.81, 0.0}, 1e-3,
                  model.overrides);
  for (int i = 0; i < 20; ++i) body.step();  // warm-up: solver history, caches
  uint32_t bits = 0;
  // Each step's thread CPU time as well: its 99th percentile is the slow steps' cost (a
  // tangent refresh, a second Newton iteration) without the preemptions of a loaded machine.
  std::vector<double> step_ms;
  step_ms.reserve(1 << 16);
  for (auto _ : state) {
    const double begin = thread_cpu_ms();
    bits |= body.step();
    if (step_ms.size() < step_ms.capacity()) step_ms.push_back(thread_cpu_ms() - begin);
  }
  std::sort(step_ms.begin(), step_ms.end());
  const auto percentile = [&](double p) {
    return step_ms.empty() ? 0.0 : step_ms[static_cast<size_t>(p * (step_ms.size() - 1))];
  };
  state.counters["cpu_p50_ms"] = percentile(0.5);
  state.counters["cpu_p99_ms"] = percentile(0.99);
  state.counters["tets"] = static_cast<double>(mesh.tets.size() / 4);
  state.counters["nodes"] = mesh.node_count();
  state.counters["budget_ms"] = 1.0;
  state.counters["fault"] = (bits & TACTA_STEP_FAULT_MASK) ? 1 : 0;
}

const bool registered = [] {
  const std::pair<uint32_t, uint32_t> sizes[] = {{4, 1}, {7, 0}, {12, 0}, {20, 1}};
  for (const ModelCase& model : model_cases()) {
    if (!plugin_built(model.file)) continue;
    for (auto [cells, extra] : sizes) {
      if (cells > model.max_cells) continue;
      const uint32_t tets = 6 * cells * cells * (cells + extra);
      benchmark::RegisterBenchmark(
          ("StepBySize/" + std::string(model.label) + "/tets:" + std::to_string(tets)).c_str(),
          [&model, cells, extra](benchmark::State& s) { step_by_size(s, model, cells, extra); })
          ->Unit(benchmark::kMillisecond)
          ->MinWarmUpTime(0.2);
    }
  }
  return true;
}();

}  // namespace
}  // namespace tacta::bench
