// `tacta ccd-bench PATH...`: runs the ccd plugin's vertex-face and edge-edge tests on query files
// with exact ground truth (format: tests/data/ccd/README.md), files or folders searched
// recursively, and prints one JSON object: our conservative test and, under "baseline", the plain
// floating-point Moore-Wilhelms (cubic roots then inside test), counted and timed in the same run.
// Exit code 1 when ours has a false negative (the one thing it must never have).
#include <algorithm>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "command.hpp"
#include "tacta/ccd_queries.hpp"
#include "tacta/collision_api.h"
#include "tacta/error.hpp"
#include "tacta/log.hpp"
#include "tacta/param_defaults.hpp"
#include "tacta/plugin_registry.hpp"

namespace {

tacta::SourceLocation at(const std::string& file) { return tacta::SourceLocation{file, 0, 0, ""}; }

struct Score {
  long false_negatives = 0, false_positives = 0;
  double median_ns = 0.0, mean_ns = 0.0;
};

// Answers every query once for the counts, then times `repeat` passes per query (ns each).
Score score(const tacta_collision_api& api, void* instance,
            const std::vector<tacta::CcdQuery>& queries, int repeat) {
  Score s;
  std::vector<double> ns(queries.size());
  double total = 0.0;
  for (size_t i = 0; i < queries.size(); ++i) {
    const tacta::CcdQuery& q = queries[i];
    auto run = [&] {
      tacta_ccd_hit hit{};
      return q.vertex_face ? api.vertex_face(instance, q.points, &hit)
                           : api.edge_edge(instance, q.points, &hit);
    };
    const bool found = run() != 0;
    if (q.truth && !found) ++s.false_negatives;
    if (!q.truth && found) ++s.false_positives;
    const auto start = std::chrono::steady_clock::now();
    int sink = 0;
    for (int r = 0; r < repeat; ++r) sink += run();
    const auto stop = std::chrono::steady_clock::now();
    if (sink < 0) std::cerr << "";  // keeps the loop from being optimised away
    ns[i] = std::chrono::duration<double, std::nano>(stop - start).count() / repeat;
    total += ns[i];
  }
  if (!ns.empty()) {
    std::nth_element(ns.begin(), ns.begin() + static_cast<long>(ns.size() / 2), ns.end());
    s.median_ns = ns[ns.size() / 2];
    s.mean_ns = total / static_cast<double>(ns.size());
  }
  return s;
}

void* make_instance(const tacta::LoadedDescriptor& d, int method) {
  // The plugin's defaults, with `method` (a CHOICE) set to the method under test.
  tacta::ParamSet values;
  for (uint32_t i = 0; i < d.descriptor->param_count; ++i) {
    const tacta_param_spec& spec = d.descriptor->params[i];
    if (std::string(spec.name) == "method")
      values.add_text(spec.name, tacta::choice_name(spec, static_cast<size_t>(method)), method);
    else
      tacta::add_default(values, spec);
  }
  const tacta_collision_setup setup{sizeof(tacta_collision_setup), values.data(), values.size(),
                                    0.001};
  void* instance = nullptr;
  char message[512] = {0};
  const auto& api = *static_cast<const tacta_collision_api*>(d.descriptor->api);
  if (api.create(&setup, &instance, message, sizeof message) != TACTA_OK)
    throw tacta::InputError(at(d.file), std::string("ccd plugin refused to create: ") + message);
  return instance;
}

int run_bench(const std::vector<std::string>& paths, int repeat) {
  const std::vector<tacta::CcdQuery> queries = tacta::read_ccd_paths({paths.begin(), paths.end()});
  tacta::PluginRegistry registry;
  registry.load();
  const tacta::LoadedDescriptor& d = registry.require(TACTA_KIND_COLLISION, "ccd");
  const auto& api = *static_cast<const tacta_collision_api*>(d.descriptor->api);
  if (api.vertex_face == nullptr || api.edge_edge == nullptr)
    throw tacta::InputError(at(d.file), "the 'ccd' plugin has no vertex_face/edge_edge entries");
  void* ours = make_instance(d, 0);
  void* plain = make_instance(d, 1);
  const Score a = score(api, ours, queries, repeat);
  const Score b = score(api, plain, queries, repeat);
  api.destroy(ours);
  api.destroy(plain);
  long vertex_face = 0, positives = 0;
  for (const tacta::CcdQuery& q : queries) {
    vertex_face += q.vertex_face;
    positives += q.truth;
  }
  const auto scored = [](const Score& s) {
    return nlohmann::ordered_json{{"false_negatives", s.false_negatives},
                                  {"false_positives", s.false_positives},
                                  {"ns_per_query_median", s.median_ns},
                                  {"ns_per_query_mean", s.mean_ns}};
  };
  nlohmann::ordered_json json = {{"queries", queries.size()},
                                 {"vertex_face", vertex_face},
                                 {"edge_edge", static_cast<long>(queries.size()) - vertex_face},
                                 {"positives", positives},
                                 {"method", "inclusion"}};
  json.update(scored(a));
  nlohmann::ordered_json baseline = {{"method", "plain Moore-Wilhelms (cubic roots, inside test)"}};
  baseline.update(scored(b));
  json["baseline"] = baseline;
  std::cout << json.dump() << std::endl;
  return a.false_negatives == 0 ? tacta::cli::kExitOk : tacta::cli::kExitFault;
}

void add_ccd_bench_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("ccd-bench",
                                 "Run the CCD plugin on query files with ground truth; print JSON");
  static std::vector<std::string> paths;
  static int repeat = 5;
  cmd->add_option("paths", paths, "query files (.csv) or folders, searched recursively")
      ->required();
  cmd->add_option("--repeat", repeat, "timed passes per query (ns per query is their mean)")
      ->check(CLI::Range(1, 100000));
  cmd->callback([&exit_code] {
    try {
      exit_code = run_bench(paths, repeat);
    } catch (const std::exception& e) {
      tacta::log_error(std::string("tacta ccd-bench: ") + e.what());
      exit_code = tacta::cli::kExitBadInput;
    }
  });
}

const bool registered = tacta::cli::register_command(&add_ccd_bench_command);

}  // namespace
