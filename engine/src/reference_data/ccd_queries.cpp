#include "tacta/ccd_queries.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "tacta/error.hpp"

namespace tacta {

namespace {

constexpr size_t kMaxLine = 1024;  // 7 fields of the longest reference integers (33 digits) fit
constexpr size_t kMaxDigits = 64;  // a longer integer is no coordinate of a real query

// An optional '-' and 1..kMaxDigits decimal digits, nothing else.
bool is_integer(const std::string& s) {
  const size_t digits = s.size() - (s.empty() || s[0] != '-' ? 0 : 1);
  if (digits == 0 || digits > kMaxDigits) return false;
  return std::all_of(s.end() - static_cast<long>(digits), s.end(),
                     [](char c) { return c >= '0' && c <= '9'; });
}

bool is_power_of_two(double d) {
  int exponent = 0;
  return d > 0 && std::isfinite(d) && std::frexp(d, &exponent) == 0.5;
}

}  // namespace

std::vector<CcdQuery> read_ccd_queries(std::istream& in, const std::string& source,
                                       bool vertex_face) {
  std::vector<CcdQuery> queries;
  std::string line;
  int line_number = 0, row = 0;
  CcdQuery q;
  auto fail = [&](int column, const std::string& what) {
    throw InputError({source, line_number, column, ""}, what);
  };
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line.size() > kMaxLine)
      fail(0, "line longer than " + std::to_string(kMaxLine) + " characters");
    std::string field[7];
    size_t start = 0, count = 0;
    for (; count < 7 && start <= line.size(); ++count) {
      const size_t comma = std::min(line.find(',', start), line.size());
      field[count] = line.substr(start, comma - start);
      start = comma + 1;
    }
    if (count != 7 || start <= line.size())
      fail(0, "expected 7 comma-separated integers x_num,x_den,y_num,y_den,z_num,z_den,truth");
    for (int k = 0; k < 7; ++k)
      if (!is_integer(field[k]))
        fail(k + 1, "expected an integer of at most " + std::to_string(kMaxDigits) +
                        " digits, found '" + field[k] + "'");
    for (int k = 0; k < 3; ++k) {
      const double num = std::strtod(field[2 * k].c_str(), nullptr);
      const double den = std::strtod(field[2 * k + 1].c_str(), nullptr);
      if (!is_power_of_two(den))
        fail(2 * k + 2, "expected a power-of-two denominator, found '" + field[2 * k + 1] + "'");
      q.points[3 * row + k] = num / den;  // exact: den is a power of two
      if (!std::isfinite(q.points[3 * row + k]))
        fail(2 * k + 1, "the coordinate is not a finite double");
    }
    if (field[6] != "0" && field[6] != "1")
      fail(7, "expected the truth column 0 or 1, found '" + field[6] + "'");
    if (row == 0) {
      q.truth = field[6] == "1";
      q.vertex_face = vertex_face;
      q.origin = source + ":" + std::to_string(line_number);
    }
    if (++row == 8) {
      queries.push_back(q);
      row = 0;
    }
  }
  if (row != 0) fail(0, "the row count is not a multiple of 8 (one query is 8 rows)");
  return queries;
}

std::vector<CcdQuery> read_ccd_file(const std::filesystem::path& file) {
  const std::string kind = file.parent_path().filename().string();
  if (kind != "vertex-face" && kind != "edge-edge")
    throw InputError({file.string(), 0, 0, ""},
                     "expected the file inside a 'vertex-face' or 'edge-edge' folder");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError({file.string(), 0, 0, ""}, "cannot open the file");
  return read_ccd_queries(in, file.string(), kind == "vertex-face");
}

std::vector<CcdQuery> read_ccd_paths(const std::vector<std::filesystem::path>& paths) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const fs::path& p : paths) {
    if (fs::is_directory(p)) {
      for (const auto& entry : fs::recursive_directory_iterator(p))
        if (entry.is_regular_file() && entry.path().extension() == ".csv")
          files.push_back(entry.path());
    } else if (fs::is_regular_file(p)) {
      files.push_back(p);
    } else {
      throw InputError({p.string(), 0, 0, ""}, "no such file or folder");
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<CcdQuery> all;
  for (const fs::path& f : files) {
    std::vector<CcdQuery> part = read_ccd_file(f);
    all.insert(all.end(), part.begin(), part.end());
  }
  return all;
}

}  // namespace tacta
