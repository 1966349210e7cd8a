// A minimal reader of the .vtu files our writer makes (inline ascii or base64 arrays), enough
// for tests to check the structure and values that ParaView will see.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace tacta::output::testing {

struct VtuArray {
  std::string type;  // Float64, Int64, UInt8
  int components = 1;
  std::vector<double> values;
};

struct VtuFile {
  std::string text;
  size_t point_count = 0;
  size_t cell_count = 0;
  std::map<std::string, VtuArray> arrays;  // by Name: fields, "Points", "connectivity", ...
};

VtuFile read_vtu(const std::filesystem::path& file);
std::vector<uint8_t> decode_base64(const std::string& text);

}  // namespace tacta::output::testing
