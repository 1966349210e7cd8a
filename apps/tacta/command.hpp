// Subcommands of `tacta`: each lives in its own file and registers itself at start-up, so adding
// a command touches no shared list. Exit codes: 0 ok, 1 runtime fault, 2 bad input.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <functional>
#include <vector>

#include "tacta/error.hpp"
#include "tacta/log.hpp"

namespace tacta::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFault = 1;
inline constexpr int kExitBadInput = 2;

// Adds a subcommand to app; its callback stores the exit code in exit_code.
using CommandFactory = std::function<void(CLI::App& app, int& exit_code)>;

inline std::vector<CommandFactory>& command_factories() {
  static std::vector<CommandFactory> factories;
  return factories;
}

// Use at namespace scope in a command's file:
//   static const bool registered = tacta::cli::register_command(&add_plugins_command);
inline bool register_command(CommandFactory factory) {
  command_factories().push_back(std::move(factory));
  return true;
}

// -q: notes off, warnings and errors still on stderr (TACTA_LOG_LEVEL=error keeps warnings off).
inline constexpr const char* kQuietHelp = "Print only warnings and errors";
inline void apply_quiet(bool quiet) {
  if (quiet && log_level() < LogLevel::warning) set_log_level(LogLevel::warning);
}

// Runs a command body and turns what it throws into the exit code: bad input (InputError: scene,
// mesh, plugin) is 2, anything else at run time is 1; the message goes to stderr.
template <class Fn>
int run_guarded(Fn&& body) {
  try {
    return body();
  } catch (const InputError& e) {
    log_error(e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    log_error(e.what());
    return kExitFault;
  }
}

}  // namespace tacta::cli
