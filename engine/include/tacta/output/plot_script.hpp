// Running the plot scripts of scripts/plots (matplotlib) as child processes, for apps that draw
// their own plots (tacta compare). No shell is involved; a plot that fails is the caller's
// warning, never a crash.
#pragma once

#include <string>
#include <vector>

namespace tacta {

// The interpreter: TACTA_PYTHON, else Debian's /usr/bin/python3 (a python3 earlier on PATH, such
// as a pyenv, may lack matplotlib), else python3 on PATH.
std::string plot_python();

// The folder of the plot scripts: TACTA_PLOT_SCRIPTS, else the source tree's scripts/plots, else
// the install prefix's share/tacta/plots.
std::string plot_scripts_dir();

// Runs argv (argv[0] a path or a name looked up on PATH), waits, returns the exit status, or -1
// when the program could not be started or did not exit normally.
int run_plot_process(const std::vector<std::string>& argv);

// Runs `plot_python() plot_scripts_dir()/script args...`; returns its exit status (-1 as above).
int run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace tacta
