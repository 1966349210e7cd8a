// tacta: the command line. Subcommands register themselves (command.hpp), one file each.
#include <iostream>

#include "command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Tacta: real-time elastic bodies with force feedback"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tacta 0.1.0");
  int exit_code = tacta::cli::kExitOk;
  for (auto& factory : tacta::cli::command_factories()) factory(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : tacta::cli::kExitBadInput;
  }
  return exit_code;
}
