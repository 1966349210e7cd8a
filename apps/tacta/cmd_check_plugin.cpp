// `tacta check-plugin PATH_OR_NAME [--path DIR]...`: the conformance suite (tacta/conformance.hpp)
// on a model plugin, given as a shared library path (anything with a '/' or ending in .so) or
// as the name of a model the loader finds. One line per check: verdict, name, figure. Exit 0
// when every check passes or is skipped, 1 when one fails, 2 when there is no such model plugin.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "tacta/conformance.hpp"
#include "tacta/plugin_registry.hpp"

// The allocation check counts malloc in this executable (the same interposer the tests use).
#include "allocation_counter.hpp"

namespace {

tacta::conformance::AllocationProbe allocation_probe() {
  tacta::conformance::AllocationProbe probe;
#if TACTA_COUNT_ALLOCATIONS
  probe.start = [] {
    g_allocations = 0;
    g_counting = true;
  };
  probe.stop = [] {
    g_counting = false;
    return g_allocations;
  };
#else
  probe.unavailable = "this tacta is built with a sanitizer, which owns malloc";
#endif
  return probe;
}

tacta::SourceLocation at_file(const std::string& path) {
  tacta::SourceLocation where;
  where.file = path;
  return where;
}

bool looks_like_path(const std::string& text) {
  return text.find('/') != std::string::npos ||
         (text.size() > 3 && text.compare(text.size() - 3, 3, ".so") == 0);
}

// The model descriptors to check; throws InputError (exit 2) when there are none.
std::vector<tacta::LoadedDescriptor> resolve(tacta::PluginRegistry& registry,
                                             const std::string& what) {
  std::vector<tacta::LoadedDescriptor> models;
  if (looks_like_path(what)) {
    if (!std::filesystem::is_regular_file(what))
      throw tacta::InputError(at_file(what), "no such plugin file");
    registry.load_file(what);
    if (!registry.refused().empty())
      throw tacta::InputError(at_file(what),
                              "the loader refused it: " + registry.refused().front().reason);
    std::string others;
    for (const auto& entry : registry.list()) {
      if (entry.descriptor->kind == TACTA_KIND_MODEL)
        models.push_back(entry);
      else
        others += std::string(" ") + tacta_kind_name(entry.descriptor->kind) + " " +
                  entry.descriptor->name;
    }
    if (models.empty())
      throw tacta::InputError(at_file(what),
                              "not a model plugin (it registers" +
                                  (others.empty() ? std::string(" nothing") : others) + ")");
    return models;
  }
  registry.load();
  if (const auto* found = registry.find(TACTA_KIND_MODEL, what)) return {*found};
  for (const tacta_kind kind : {TACTA_KIND_COLLISION, TACTA_KIND_DEVICE})
    if (registry.find(kind, what) != nullptr)
      throw tacta::InputError(
          at_file("tacta check-plugin"),
          "'" + what + "' is a " + tacta_kind_name(kind) + " plugin, not a model plugin");
  throw tacta::InputError(at_file("tacta check-plugin"),
                          registry.unknown_name_message(TACTA_KIND_MODEL, what));
}

// Prints one model's checks; true when none failed.
bool run_suite(const tacta::LoadedDescriptor& model,
               const tacta::conformance::AllocationProbe& probe) {
  std::cout << "model " << model.descriptor->name << " (" << model.file << ")\n";
  int failed = 0, skipped = 0;
  const auto results = tacta::conformance::check_model(*model.descriptor, probe);
  for (const auto& r : results) {
    std::cout << "  " << tacta::conformance::verdict_name(r.verdict) << "  " << r.name << ": "
              << r.figure << "\n";
    failed += r.verdict == tacta::conformance::Verdict::Fail;
    skipped += r.verdict == tacta::conformance::Verdict::Skip;
  }
  std::cout << "  " << results.size() << " checks: " << results.size() - failed - skipped
            << " passed, " << failed << " failed, " << skipped << " skipped\n";
  return failed == 0;
}

void add_check_plugin_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string plugin;
    std::vector<std::string> paths;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "check-plugin",
      "Run the conformance suite on a model plugin (a .so path or a model name): "
      "forces at rest and under rigid motion, momentum, no allocation in step, "
      "NaN reported, parameter schema, stepping from a worker thread");
  cmd->add_option("plugin", options->plugin, "Path of a plugin library, or a model name")
      ->required();
  cmd->add_option("--path", options->paths,
                  "Also search this folder for a named model (repeatable)");
  cmd->callback([options, &exit_code] {
    exit_code = tacta::cli::run_guarded([&] {
      tacta::PluginRegistry registry(looks_like_path(options->plugin)
                                         ? tacta::PluginRegistry::DefaultPaths::Skip
                                         : tacta::PluginRegistry::DefaultPaths::Search);
      for (const auto& p : options->paths) registry.add_path(p);
      const auto models = resolve(registry, options->plugin);
      const auto probe = allocation_probe();
      bool all_passed = true;
      for (const auto& model : models) all_passed = run_suite(model, probe) && all_passed;
      return all_passed ? tacta::cli::kExitOk : tacta::cli::kExitFault;
    });
  });
}

const bool registered = tacta::cli::register_command(&add_check_plugin_command);

}  // namespace
