// tacta sweep: the Python sweep on Dask (python/tacta/sweep.py), reached from the command line.
// Every argument goes to `python3 -m tacta.sweep`, run by the interpreter the module was built
// for (TACTA_PYTHON overrides it) with this build's or install's package first on PYTHONPATH.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "command.hpp"

namespace tacta::cli {
namespace {

namespace fs = std::filesystem;

int exec_sweep(const std::vector<std::string>& args) {
#ifdef TACTA_PYTHON
  const char* chosen = std::getenv("TACTA_PYTHON");
  const std::string python = chosen && *chosen ? chosen : TACTA_PYTHON;
  // The build tree's bin/tacta takes the build tree's module; an installed one the install's.
  std::error_code ec;
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  const bool in_build = !ec && fs::equivalent(exe_dir, TACTA_BUILD_BIN_DIR, ec);
  std::string path = in_build ? TACTA_PYTHON_BUILD_DIR : TACTA_PYTHON_INSTALL_DIR;
  if (const char* old = std::getenv("PYTHONPATH"); old && *old) path += std::string(":") + old;
  setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> words{python, "-m", "tacta.sweep"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  execvp(argv[0], argv.data());
  log_error("tacta sweep: cannot run " + python + " (" + std::strerror(errno) +
            "); set TACTA_PYTHON");
  return kExitFault;
#else
  (void)args;
  log_error("tacta sweep needs the Python module: build with TACTA_BUILD_PYTHON=ON");
  return kExitBadInput;
#endif
}

void add_sweep_command(CLI::App& app, int& exit_code) {
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Run a scene over a grid of parameter sets on Dask: tacta sweep SCENE --grid "
      "grid.yaml --out runs.csv [--scheduler ADDRESS] (python3 -m tacta.sweep; docs/SWEEPS.md)");
  cmd->prefix_command();  // every argument, --help included, is the Python command's
  cmd->set_help_flag();
  cmd->callback([cmd, &exit_code] { exit_code = exec_sweep(cmd->remaining()); });
}

const bool registered = register_command(&add_sweep_command);

}  // namespace
}  // namespace tacta::cli
