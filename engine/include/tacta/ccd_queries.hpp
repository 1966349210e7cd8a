// The CCD query files of tests/data/ccd (format: its README): 8 rows per query of 7 integers,
// x_num,x_den,y_num,y_den,z_num,z_den,truth. The denominators are powers of two, so each quotient
// is exactly a double. One reader for the CCD tests, the benchmark, `tacta ccd-bench` and the
// fuzz harness. The text is untrusted: a bad row is an InputError naming file, line and column.
#pragma once

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

namespace tacta {

struct CcdQuery {
  // vertex-face: v, f0, f1, f2 at t0 then at t1; edge-edge: a0, a1, b0, b1 at t0 then at t1 (m).
  double points[24] = {};
  bool truth = false;        // the exact answer: the primitives meet within the step
  bool vertex_face = false;  // else edge-edge
  std::string origin;        // "file:line" of the query's first row, for failure messages
};

// Queries of one file's text; `source` names it in errors and in CcdQuery::origin.
std::vector<CcdQuery> read_ccd_queries(std::istream& in, const std::string& source,
                                       bool vertex_face);
// One file; its kind is its folder's name, "vertex-face" or "edge-edge" (else an InputError).
std::vector<CcdQuery> read_ccd_file(const std::filesystem::path& file);
// Files, or folders searched recursively for .csv files; all files read in sorted path order.
std::vector<CcdQuery> read_ccd_paths(const std::vector<std::filesystem::path>& paths);

}  // namespace tacta
