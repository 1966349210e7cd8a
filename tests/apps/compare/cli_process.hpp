// Runs the `tacta` executable (TACTA_CLI) from the tests, with stdout and stderr kept in files.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tacta::test {

struct CliResult {
  int exit_code = -1;  // -1: did not start or did not exit normally
  std::string out, err;
};

// Runs `tacta args...` in TACTA_SOURCE_DIR (scene paths are relative to it); output files go
// under `scratch`.
CliResult run_tacta(const std::vector<std::string>& args, const std::filesystem::path& scratch);

// A fresh, empty folder under the build tree for one test case.
std::filesystem::path fresh_dir(const std::string& name);

std::string read_text(const std::filesystem::path& file);

}  // namespace tacta::test
