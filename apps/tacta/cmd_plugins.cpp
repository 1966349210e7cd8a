// `tacta plugins [--json] [--path DIR]...`: what the loader found, each descriptor with its
// parameter schema, and every refused file with the reason. Exit 0 even when files were refused
// (they are listed), 2 when a --path is not a folder.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "command.hpp"
#include "tacta/collision_api.h"
#include "tacta/error.hpp"
#include "tacta/live_params.hpp"
#include "tacta/log.hpp"
#include "tacta/model_api.h"
#include "tacta/param_defaults.hpp"
#include "tacta/plugin_registry.hpp"

namespace {

const char* type_name(tacta_param_type type) {
  switch (type) {
    case TACTA_PARAM_REAL: return "real";
    case TACTA_PARAM_INT: return "int";
    case TACTA_PARAM_BOOL: return "bool";
    case TACTA_PARAM_CHOICE: return "choice";
    case TACTA_PARAM_TEXT: return "text";
    case TACTA_PARAM_VECTOR: return "vector";
    default: return "unknown";
  }
}

// major*10000 + minor*100 + patch -> "major.minor.patch"
std::string version_text(uint32_t v) {
  return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." +
         std::to_string(v % 100);
}

// "broad_phase, proxy" for a collision descriptor, "(guessed from its entries)" when it declares none.
std::string collision_roles_text(const tacta_descriptor& d) {
  int guessed = 0;
  const uint32_t roles = tacta_collision_roles(&d, &guessed);
  std::string text;
  for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r)
    if (roles & (1u << r))
      text += (text.empty() ? "" : ", ") + std::string(tacta_collision_role_name(1u << r));
  return (text.empty() ? std::string("none") : text) +
         (guessed ? " (guessed from its entries)" : "");
}

uint32_t model_claims(const tacta_descriptor& d) {
  return tacta_model_claims(static_cast<const tacta_model_api*>(d.api), d.api_size);
}

// The TACTA_MODEL_CLAIM_* bits a model descriptor sets, by name ("topology_edits": it takes cuts).
std::vector<std::string> model_claim_names(const tacta_descriptor& d) {
  static constexpr std::pair<uint32_t, const char*> kNames[] = {
      {TACTA_MODEL_CLAIM_ROTATION_INVARIANT, "rotation_invariant"},
      {TACTA_MODEL_CLAIM_MOMENTUM, "momentum"},
      {TACTA_MODEL_CLAIM_NO_HISTORY, "no_history"},
      {TACTA_MODEL_CLAIM_TOPOLOGY_EDITS, "topology_edits"},
  };
  std::vector<std::string> names;
  for (const auto& [bit, name] : kNames)
    if (model_claims(d) & bit) names.emplace_back(name);
  return names;
}

bool takes_cuts(const tacta_descriptor& d) {
  return (model_claims(d) & TACTA_MODEL_CLAIM_TOPOLOGY_EDITS) != 0;
}

// "momentum, topology_edits (takes cuts)"; "none (takes no cuts)" without any claim.
std::string model_claims_text(const tacta_descriptor& d) {
  std::string text;
  for (const auto& name : model_claim_names(d)) text += (text.empty() ? "" : ", ") + name;
  return (text.empty() ? std::string("none") : text) +
         (takes_cuts(d) ? " (takes cuts)" : " (takes no cuts)");
}

std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// One line per parameter: name, type, unit, default, range or choices, help.
std::string describe_param(const tacta_param_spec& p, bool live) {
  std::string line = std::string(p.name) + " (" + type_name(p.type);
  if (p.unit && p.unit[0]) line += std::string(", ") + p.unit;
  if (live) line += ", live";
  line += ")";
  switch (p.type) {
    case TACTA_PARAM_REAL:
    case TACTA_PARAM_INT:
      line += " default " + short_number(p.default_value) + ", range [" +
              short_number(p.min_value) + ", " + short_number(p.max_value) + "]";
      break;
    case TACTA_PARAM_BOOL: line += p.default_value != 0 ? " default true" : " default false"; break;
    case TACTA_PARAM_CHOICE: {
      const auto choices = tacta::choice_names(p);
      const auto index = static_cast<size_t>(p.default_value);
      line += " default " + (index < choices.size() ? choices[index] : std::string("?")) +
              ", one of " + (p.choices ? p.choices : "");
      break;
    }
    case TACTA_PARAM_TEXT:
      line += std::string(" default '") + (p.default_text ? p.default_text : "") + "'";
      break;
    case TACTA_PARAM_VECTOR:
      line += " default [" + std::string(p.default_text ? p.default_text : "") + "], groups of " +
              std::to_string(p.vector_stride) + ", each in [" + short_number(p.min_value) + ", " +
              short_number(p.max_value) + "]";
      break;
    default: break;
  }
  if (p.help && p.help[0]) line += std::string(": ") + p.help;
  return line;
}

void print_text(const tacta::PluginRegistry& registry) {
  std::cout << "Search paths (in order):\n";
  for (const auto& p : registry.search_paths()) std::cout << "  " << p << "\n";
  const auto loaded = registry.list();
  std::cout << "\n" << loaded.size() << " plugin descriptor(s):\n";
  for (const auto& e : loaded) {
    const tacta_descriptor& d = *e.descriptor;
    std::cout << "\n"
              << tacta_kind_name(d.kind) << " " << d.name << " " << version_text(d.version) << ": "
              << (d.description ? d.description : "") << "\n  file: " << e.file << "\n";
    if (d.kind == TACTA_KIND_COLLISION) std::cout << "  roles: " << collision_roles_text(d) << "\n";
    if (d.kind == TACTA_KIND_MODEL) std::cout << "  claims: " << model_claims_text(d) << "\n";
    if (d.param_count == 0) std::cout << "  parameters: none\n";
    for (uint32_t i = 0; i < d.param_count; ++i)
      std::cout << "  - " << describe_param(d.params[i], tacta::is_live_param(d, d.params[i].name))
                << "\n";
  }
  const auto& refused = registry.refused();
  if (!refused.empty()) {
    std::cout << "\n" << refused.size() << " refused file(s):\n";
    for (const auto& r : refused) std::cout << "  " << r.file << ": " << r.reason << "\n";
  }
}

using Json = nlohmann::ordered_json;

// A plugin's C string; a null one (a careless plugin) is null, as it was absent.
Json text(const char* s) { return s ? Json(s) : Json(nullptr); }

Json param_json(const tacta_param_spec& p, bool live) {
  Json json = {{"name", text(p.name)},
               {"type", type_name(p.type)},
               {"unit", p.unit ? p.unit : ""},
               {"live", live}};
  switch (p.type) {
    case TACTA_PARAM_REAL:
    case TACTA_PARAM_INT:
      json["default"] = p.default_value;
      json["min"] = p.min_value;
      json["max"] = p.max_value;
      break;
    case TACTA_PARAM_BOOL: json["default"] = p.default_value != 0; break;
    case TACTA_PARAM_CHOICE: {
      const auto choices = tacta::choice_names(p);
      const auto index = static_cast<size_t>(p.default_value);
      json["default"] = index < choices.size() ? choices[index] : std::string();
      json["choices"] = choices;
      break;
    }
    case TACTA_PARAM_TEXT: json["default"] = text(p.default_text); break;
    case TACTA_PARAM_VECTOR:
      json["default"] = text(p.default_text);
      json["stride"] = p.vector_stride;
      json["min"] = p.min_value;
      json["max"] = p.max_value;
      break;
    default: break;
  }
  json["help"] = p.help ? p.help : "";
  return json;
}

void print_json(const tacta::PluginRegistry& registry) {
  Json plugins = Json::array();
  for (const auto& e : registry.list()) {
    const tacta_descriptor& d = *e.descriptor;
    Json plugin = {{"kind", tacta_kind_name(d.kind)},
                   {"name", text(d.name)},
                   {"version", version_text(d.version)},
                   {"description", text(d.description)},
                   {"file", e.file}};
    if (d.kind == TACTA_KIND_COLLISION) {
      int guessed = 0;
      const uint32_t roles = tacta_collision_roles(&d, &guessed);
      Json& names = plugin["roles"] = Json::array();
      for (uint32_t r = 0; r < TACTA_COLLISION_ROLE_COUNT; ++r)
        if (roles & (1u << r)) names.push_back(tacta_collision_role_name(1u << r));
      plugin["roles_guessed"] = guessed != 0;
    }
    if (d.kind == TACTA_KIND_MODEL) {
      plugin["claims"] = model_claim_names(d);
      plugin["takes_cuts"] = takes_cuts(d);
    }
    Json& params = plugin["parameters"] = Json::array();
    for (uint32_t i = 0; i < d.param_count; ++i)
      params.push_back(param_json(d.params[i], tacta::is_live_param(d, d.params[i].name)));
    plugins.push_back(plugin);
  }
  Json refused = Json::array();
  for (const auto& r : registry.refused())
    refused.push_back({{"file", r.file}, {"reason", r.reason}});
  const Json json = {
      {"search_paths", registry.search_paths()}, {"plugins", plugins}, {"refused", refused}};
  // Bytes that are not UTF-8 (a plugin's strings) become U+FFFD rather than failing the listing.
  std::cout << json.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
}

void add_plugins_command(CLI::App& app, int& exit_code) {
  struct Options {
    bool json = false;
    std::vector<std::string> paths;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "plugins",
      "List the plugins found (build tree, install prefix, TACTA_PLUGIN_PATH, --path) "
      "with their parameters, and every refused file with the reason");
  cmd->add_flag("--json", options->json, "Print the same as JSON");
  cmd->add_option("--path", options->paths, "Also search this folder (repeatable)");
  cmd->callback([options, &exit_code] {
    tacta::PluginRegistry registry;
    try {
      for (const auto& p : options->paths) registry.add_path(p);
    } catch (const tacta::InputError& e) {
      tacta::log_error(std::string("tacta plugins: ") + e.what());
      exit_code = tacta::cli::kExitBadInput;
      return;
    }
    registry.load();
    if (options->json)
      print_json(registry);
    else
      print_text(registry);
    exit_code = tacta::cli::kExitOk;
  });
}

const bool registered = tacta::cli::register_command(&add_plugins_command);

}  // namespace
