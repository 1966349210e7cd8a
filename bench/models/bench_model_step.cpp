// Step time of every elastic model plugin against mesh size (about 500, 2k, 10k and 50k tets),
// all driven through the C ABI, on a clamped box under gravity at the haptic tick (dt = 1 ms).
// The 1 kHz budget is 1 ms per tick for everything (collision, haptics, every body), so a
// model's step should stay well below it. Models whose plugin is not built are skipped.
//
// Sweep/<model>/tets:N/threads:T: the size sweep (docs/BENCHMARKS.md, bench/models/size_sweep.py)
// over box size x engine threads x model, the models given the host's parallel_for on an engine
// JobPool of T threads as the engine gives it (threads 1: a pool of one, serial). T is 1, 2 and
// `auto` (the CPUs less one, as the scene key). With TACTA_BASELINE_PLUGIN_DIR set, the same
// cases with the plugins of that folder (an earlier build) as Sweep/baseline_<model>/..., so a
// baseline and this build can be timed in one interleaved run, and Paired/<model>/... steps the
// two in turn in one benchmark, for a noisy host (paired_steps).
#include <algorithm>
#include <benchmark/benchmark.h>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <sched.h>
#include <set>
#include <string>
#include <vector>

#include "bench_meshes.hpp"
#include "plugin_body.hpp"
#include "services/job_pool.hpp"

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
      {"vbd", "tacta_vbd.so", "vbd", {}, 20},
  };
  return cases;
}

// The engine's host services over a JobPool of `threads`, as the engine fills them.
struct BenchHost {
  explicit BenchHost(uint32_t threads) : pool(threads) {}
  JobPool pool;
  ScratchArena arena;
  tacta_host_services services = host_services(&pool, &arena);
};

// Soft tissue-like, and soft enough (c_p = 4.6 m/s, dt_crit about 2 ms on 1 cm cells) that the
// explicit models are stable at the 1 ms tick too, so every model is timed doing work.
tacta_material box_material() {
  tacta_material material = models::make_material(1e4, 0.4, 1000.0);
  material.rayleigh_mass = 0.1;
  material.rayleigh_stiffness = 0.01;
  return material;
}

double percentile(const std::vector<double>& sorted, double p) {
  return sorted.empty() ? 0.0 : sorted[static_cast<size_t>(p * (sorted.size() - 1))];
}

void step_by_size(benchmark::State& state, const ModelCase& model, uint32_t cells, uint32_t extra,
                  uint32_t threads = 0) {
  const models::TestMesh mesh = clamped_box(cells, extra);
  // threads 0: no host services (StepBySize, as before the sweep); else an engine pool.
  const std::unique_ptr<BenchHost> host =
      threads > 0 ? std::make_unique<BenchHost>(threads) : nullptr;
  PluginBody body(model.file, model.model, mesh, box_material(), {0.0, -9.81, 0.0}, 1e-3,
                  model.overrides, host ? &host->services : nullptr);
  for (int i = 0; i < 20; ++i) body.step();  // warm-up: solver history, caches
  uint32_t bits = 0;
  // Each step's thread CPU time as well: its 99th percentile is the slow steps' cost (a
  // tangent refresh, a second Newton iteration) without the preemptions of a loaded machine.
  // And each step's wall time: with workers, a step whose worker was preempted by another
  // process is slow on the wall only; the wall p10 is the speed with the cores to ourselves.
  std::vector<double> step_ms, wall_ms;
  step_ms.reserve(1 << 16);
  wall_ms.reserve(1 << 16);
  for (auto _ : state) {
    const double begin = thread_cpu_ms();
    const auto wall_begin = std::chrono::steady_clock::now();
    bits |= body.step();
    if (step_ms.size() < step_ms.capacity()) {
      step_ms.push_back(thread_cpu_ms() - begin);
      wall_ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall_begin)
              .count());
    }
  }
  std::sort(step_ms.begin(), step_ms.end());
  std::sort(wall_ms.begin(), wall_ms.end());
  state.counters["cpu_p50_ms"] = percentile(step_ms, 0.5);
  state.counters["cpu_p99_ms"] = percentile(step_ms, 0.99);
  state.counters["wall_p10_ms"] = percentile(wall_ms, 0.1);
  state.counters["wall_p50_ms"] = percentile(wall_ms, 0.5);
  state.counters["tets"] = static_cast<double>(mesh.tets.size() / 4);
  state.counters["nodes"] = mesh.node_count();
  state.counters["budget_ms"] = 1.0;
  state.counters["fault"] = (bits & TACTA_STEP_FAULT_MASK) ? 1 : 0;
  if (threads > 0) state.counters["threads"] = threads;
}

// Two bodies on the same box stepped in turn (which goes first alternating), each step's wall
// time kept: a busy host slows neighbouring steps alike, so the median of the pairs' ratios holds
// where separate runs of the same code drift by 1.3x. Each body's step starts with the other's
// data in the caches. Paired/<model>/...: this build's plugin against the baseline's
// (TACTA_BASELINE_PLUGIN_DIR), both on one pool of T threads. (Not for one build on 1 thread
// against 2: the pool idle while the other body steps parks its workers, and the threaded step
// then pays their wake-up and cold caches, 1.24x where back-to-back steps give 1.6x.)
void paired_steps(benchmark::State& state, const ModelCase& model, const ModelCase& baseline,
                  uint32_t cells, uint32_t extra, uint32_t threads) {
  const models::TestMesh mesh = clamped_box(cells, extra);
  BenchHost host(threads);
  PluginBody ours(model.file, model.model, mesh, box_material(), {0.0, -9.81, 0.0}, 1e-3,
                  model.overrides, &host.services);
  PluginBody theirs(baseline.file, baseline.model, mesh, box_material(), {0.0, -9.81, 0.0}, 1e-3,
                    baseline.overrides, &host.services);
  for (int i = 0; i < 20; ++i) ours.step(), theirs.step();
  const auto timed = [](PluginBody& body, uint32_t& bits) {
    const auto begin = std::chrono::steady_clock::now();
    bits |= body.step();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
        .count();
  };
  std::vector<double> ours_ms, theirs_ms, ratios;
  ours_ms.reserve(1 << 16);
  theirs_ms.reserve(1 << 16);
  ratios.reserve(1 << 16);
  uint32_t bits = 0;
  bool ours_first = true;
  for (auto _ : state) {
    double a = 0.0, b = 0.0;
    if (ours_first) {
      a = timed(ours, bits);
      b = timed(theirs, bits);
    } else {
      b = timed(theirs, bits);
      a = timed(ours, bits);
    }
    ours_first = !ours_first;
    if (ratios.size() < ratios.capacity()) {
      ours_ms.push_back(a);
      theirs_ms.push_back(b);
      ratios.push_back(a / b);
    }
  }
  for (std::vector<double>* v : {&ours_ms, &theirs_ms, &ratios}) std::sort(v->begin(), v->end());
  state.counters["ours_p50_ms"] = percentile(ours_ms, 0.5);
  state.counters["baseline_p50_ms"] = percentile(theirs_ms, 0.5);
  state.counters["ours_p10_ms"] = percentile(ours_ms, 0.1);
  state.counters["baseline_p10_ms"] = percentile(theirs_ms, 0.1);
  state.counters["ratio_p50"] = percentile(ratios, 0.5);
  state.counters["tets"] = static_cast<double>(mesh.tets.size() / 4);
  state.counters["threads"] = threads;
  state.counters["fault"] = (bits & TACTA_STEP_FAULT_MASK) ? 1 : 0;
}

// `threads: auto` as the scene loader reads it: the CPUs this process may use, less one.
uint32_t auto_threads() {
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  const int count = sched_getaffinity(0, sizeof cpus, &cpus) == 0 ? CPU_COUNT(&cpus) : 2;
  return static_cast<uint32_t>(std::clamp(count - 1, 1, 64));
}

// The sweep's models: each at its plugin defaults, here and (when given) in the baseline folder.
const std::vector<ModelCase>& sweep_cases() {
  static const std::vector<ModelCase> cases = [] {
    std::vector<ModelCase> list = {
        {"corotational_fem", "tacta_corotational_fem.so", "corotational_fem", {}, 20},
        // Only its element pass on the workers, its CG serial (what a body stepped in a group
        // runs; the default before the solve took the workers of a body stepped alone).
        {"corotational_fem_serial_solve",
         "tacta_corotational_fem.so",
         "corotational_fem",
         {{"threaded_solve", 0, nullptr}},
         20},
        {"hyperelastic", "tacta_hyperelastic.so", "hyperelastic", {}, 20},
        {"tensor_mass", "tacta_tensor_mass.so", "tensor_mass", {}, 20},
        {"vbd", "tacta_vbd.so", "vbd", {}, 20},
    };
    static std::vector<std::string> storage;  // labels and paths of the baseline cases
    storage.reserve(2 * list.size());
    if (const char* dir = std::getenv("TACTA_BASELINE_PLUGIN_DIR"); dir && *dir) {
      const size_t n = list.size();
      for (size_t i = 0; i < n; ++i) {
        const std::string path = std::string(dir) + "/" + list[i].file;
        if (!std::filesystem::exists(path)) continue;
        storage.push_back("baseline_" + std::string(list[i].label));
        const char* label = storage.back().c_str();
        storage.push_back(path);
        list.push_back({label, storage.back().c_str(), list[i].model, list[i].overrides, 20});
      }
    }
    return list;
  }();
  return cases;
}

bool case_built(const ModelCase& model) {
  const std::string file = model.file;
  return file.find('/') != std::string::npos ? std::filesystem::exists(file) : plugin_built(file);
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
  // The sweep: ~500 to ~50k tets (cells per side, extra cells in z).
  const std::pair<uint32_t, uint32_t> sweep_sizes[] = {{4, 1},  {7, 0},  {9, 0},
                                                       {12, 0}, {15, 0}, {20, 1}};
  std::set<uint32_t> thread_counts = {1, 2, auto_threads()};
  for (const ModelCase& model : sweep_cases()) {
    if (!case_built(model)) continue;
    for (auto [cells, extra] : sweep_sizes)
      for (uint32_t threads : thread_counts) {
        const uint32_t tets = 6 * cells * cells * (cells + extra);
        benchmark::RegisterBenchmark(("Sweep/" + std::string(model.label) + "/tets:" +
                                      std::to_string(tets) + "/threads:" + std::to_string(threads))
                                         .c_str(),
                                     [&model, cells, extra, threads](benchmark::State& s) {
                                       step_by_size(s, model, cells, extra, threads);
                                     })
            ->Unit(benchmark::kMillisecond)
            ->MinWarmUpTime(0.2);
      }
  }
  for (const ModelCase& model : sweep_cases()) {
    const std::string label = model.label;
    const auto baseline = std::find_if(
        sweep_cases().begin(), sweep_cases().end(),
        [&](const ModelCase& m) { return std::string(m.label) == "baseline_" + label; });
    if (!case_built(model) || baseline == sweep_cases().end() || !case_built(*baseline)) continue;
    for (auto [cells, extra] : sweep_sizes)
      for (uint32_t threads : thread_counts) {
        const uint32_t tets = 6 * cells * cells * (cells + extra);
        benchmark::RegisterBenchmark(
            ("Paired/" + label + "/tets:" + std::to_string(tets) +
             "/threads:" + std::to_string(threads))
                .c_str(),
            [&model, &base = *baseline, cells, extra, threads](benchmark::State& s) {
              paired_steps(s, model, base, cells, extra, threads);
            })
            ->Unit(benchmark::kMillisecond)
            ->MinWarmUpTime(0.2);
      }
  }
  return true;
}();

}  // namespace
}  // namespace tacta::bench
