// The loaders take file paths, as the engine calls them: each harness writes its input to one
// file per process (under TMPDIR, named with the pid and the format's extension) and loads it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace tacta::fuzz {

inline std::string input_path(const char* extension) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && dir[0] ? dir : "/tmp") + "/tacta-fuzz-" + std::to_string(getpid()) +
         extension;
}

// Writes data to path (replacing it); aborts when it cannot, since every later run would be void.
inline const std::string& write_input(const std::string& path, const uint8_t* data, size_t size) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr || (size > 0 && std::fwrite(data, 1, size, file) != size) ||
      std::fclose(file) != 0) {
    std::perror(path.c_str());
    std::abort();
  }
  return path;
}

}  // namespace tacta::fuzz
