// Reads the CCD query files of tests/data/ccd (see its README): 8 rows per query, rationals
// with power-of-two denominators, each exactly a double (so strtod of numerator and
// denominator is exact and so is their quotient).
#pragma once

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace tacta::testing {

struct CcdQuery {
  double points[24];
  bool truth;
  bool vertex_face;
  std::string origin;  // file:first line, for failure messages
};

inline std::vector<CcdQuery> read_ccd_queries(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot open " + file.string());
  const bool vertex_face = file.parent_path().filename() == "vertex-face";
  std::vector<CcdQuery> queries;
  std::string line;
  int row = 0, line_number = 0;
  CcdQuery q{};
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    std::stringstream fields(line);
    std::string field[7];
    for (auto& f : field)
      if (!std::getline(fields, f, ','))
        throw std::runtime_error(file.string() + ":" + std::to_string(line_number) +
                                 ": expected 7 comma-separated integers");
    for (int k = 0; k < 3; ++k)
      q.points[3 * row + k] = std::strtod(field[2 * k].c_str(), nullptr) /
                              std::strtod(field[2 * k + 1].c_str(), nullptr);
    if (row == 0) {
      q.truth = field[6] == "1";
      q.vertex_face = vertex_face;
      q.origin = file.string() + ":" + std::to_string(line_number);
    }
    if (++row == 8) {
      queries.push_back(q);
      row = 0;
    }
  }
  return queries;
}

inline std::vector<CcdQuery> read_ccd_folder(const std::filesystem::path& root) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
    if (entry.is_regular_file() && entry.path().extension() == ".csv")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<CcdQuery> all;
  for (const auto& f : files) {
    auto part = read_ccd_queries(f);
    all.insert(all.end(), part.begin(), part.end());
  }
  return all;
}

}  // namespace tacta::testing
