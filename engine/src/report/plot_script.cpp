// The public plot-script runner (tacta/output/plot_script.hpp): child processes by posix_spawn.
#include "tacta/output/plot_script.hpp"

#include <cstdlib>
#include <filesystem>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace tacta {

std::string plot_python() {
  if (const char* p = std::getenv("TACTA_PYTHON")) return p;
  return access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
}

std::string plot_scripts_dir() {
  if (const char* d = std::getenv("TACTA_PLOT_SCRIPTS")) return d;
#ifdef TACTA_SOURCE_DIR
  if (std::filesystem::exists(TACTA_SOURCE_DIR "/scripts/plots"))
    return TACTA_SOURCE_DIR "/scripts/plots";
#endif
#ifdef TACTA_INSTALL_PLUGIN_DIR
  return TACTA_INSTALL_PLUGIN_DIR "/../../../share/tacta/plots";
#else
  return {};  // the pip package sets TACTA_PLOT_SCRIPTS to the scripts it carries (tacta/plots)
#endif
}

int run_plot_process(const std::vector<std::string>& args) {
  if (args.empty()) return -1;
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const std::string& program = args.front();
  const int rc = program.find('/') != std::string::npos
                     ? posix_spawn(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ)
                     : posix_spawnp(&pid, program.c_str(), nullptr, nullptr, argv.data(), environ);
  if (rc != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

int run_plot_script(const std::string& script, const std::vector<std::string>& args) {
  std::vector<std::string> argv{plot_python(), plot_scripts_dir() + "/" + script};
  argv.insert(argv.end(), args.begin(), args.end());
  return run_plot_process(argv);
}

}  // namespace tacta
