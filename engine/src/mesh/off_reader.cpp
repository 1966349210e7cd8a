// OFF, Geomview's Object File Format (ASCII), from its documentation: a header keyword
// [ST][C][N]OFF, "vertices faces edges", the vertices (x y z, then normal, colour and texture
// values per the prefixes) and the faces (n i1 .. in, then an optional colour to the line's end).
// Read a line at a time: x y z and the face indices are strict; what follows them on a line is
// not needed by a simulation and is ignored (one warning when it is not numbers).
#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/surface_readers.hpp"
#include "mesh/text_reader.hpp"
#include "tacta/error.hpp"

namespace tacta::mesh_detail {

namespace {

constexpr int64_t kMaxFaceSize = 1024;  // vertex indices of one face, as for PLY

// Next line with words, '#' comments removed; false at the end of the file.
bool next_content(LineWords& lines, std::vector<std::string_view>& words) {
  while (lines.next()) {
    words.clear();
    for (std::string_view w : lines.words()) {
      const size_t hash = w.find('#');
      if (hash != std::string_view::npos) {
        if (hash > 0) words.push_back(w.substr(0, hash));
        break;
      }
      words.push_back(w);
    }
    if (!words.empty()) return true;
  }
  return false;
}

// Values after the geometry on a vertex or face line (normals, colours, texture coordinates)
// must be numbers, else they are ignored with a warning.
void check_extras(const LineWords& lines, const std::vector<std::string_view>& words, size_t from,
                  IgnoredAttribute& ignored) {
  for (size_t i = from; i < words.size(); ++i) {
    double v = 0;
    if (parse_double(words[i], v)) continue;
    ignored.note(lines.line(),
                 "expected a number, found '" + std::string(words[i].substr(0, 40)) + "'");
    return;
  }
}

// The header keyword: [ST][C][N]OFF, possibly with the counts on the same line ("OFF 8 6 0", or
// "OFF8 6 0" as some public sets have it). Returns the index of the first count word.
size_t read_keyword(const LineWords& lines, std::vector<std::string_view>& words) {
  std::string_view keyword = words[0];
  const size_t off = keyword.find("OFF");
  if (off == std::string_view::npos) lines.fail("expected an OFF header keyword ([ST][C][N]OFF)");
  const std::string_view prefix = keyword.substr(0, off);
  if (prefix.find('4') != std::string_view::npos || prefix.find('n') != std::string_view::npos)
    lines.fail("4OFF and nOFF (homogeneous or n-dimensional vertices) are not supported");
  for (char c : prefix) {
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N')
      lines.fail("expected an OFF header keyword ([ST][C][N]OFF), found '" +
                 std::string(keyword.substr(0, 40)) + "'");
  }
  std::string_view after = keyword.substr(off + 3);
  if (words.size() > 1 && words[1] == "BINARY") lines.fail("binary OFF is not supported");
  if (!after.empty()) {
    words[0] = after;  // "OFF8 6 0": the counts start inside the keyword
    return 0;
  }
  return 1;
}

}  // namespace

PolygonSoup read_off(const std::string& path, const std::string& bytes) {
  PolygonSoup out;
  out.face_starts.push_back(0);
  LineWords lines(path, bytes);
  std::vector<std::string_view> words;
  if (!next_content(lines, words)) throw InputError({path, 0, 0, ""}, "the file is empty");
  size_t first = read_keyword(lines, words);
  if (first >= words.size()) {
    if (!next_content(lines, words))
      lines.fail("unexpected end of file (truncated?), expected 'vertices faces edges'");
    first = 0;
  }
  const size_t given = words.size() - first;
  if (given != 2 && given != 3) lines.fail("expected 'vertices faces edges' (three integers)");
  int64_t counts[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    if (!parse_int(words[first + static_cast<size_t>(k)], counts[k]) || counts[k] < 0)
      lines.fail("expected the vertex and face counts as non-negative integers");
  }
  // Each vertex and face takes a line: a count the file cannot hold is refused before anything
  // is allocated for it.
  const int64_t lines_left = static_cast<int64_t>(std::count(bytes.begin(), bytes.end(), '\n')) + 1;
  if (counts[0] > lines_left || counts[1] > lines_left || counts[0] + counts[1] > lines_left) {
    lines.fail("the header declares " + std::to_string(counts[0]) + " vertices and " +
               std::to_string(counts[1]) + " faces, more lines than the file has (truncated?)");
  }
  const int64_t vertices = counts[0];
  IgnoredAttribute extras(
      "colours, normals or texture coordinates (after x y z, or after a "
      "face's indices)");
  out.positions.reserve(3 * static_cast<size_t>(vertices));
  for (int64_t v = 0; v < vertices; ++v) {
    if (!next_content(lines, words))
      lines.fail("the file ends after " + std::to_string(v) + " of its " +
                 std::to_string(vertices) + " vertices (truncated?)");
    if (words.size() < 3) lines.fail("expected a vertex 'x y z'");
    double xyz[3];
    lines.expect_numbers(0, 3, "a vertex coordinate", xyz);
    out.positions.insert(out.positions.end(), xyz, xyz + 3);
    check_extras(lines, words, 3, extras);
  }
  for (int64_t f = 0; f < counts[1]; ++f) {
    if (!next_content(lines, words))
      lines.fail("the file ends after " + std::to_string(f) + " of its " +
                 std::to_string(counts[1]) + " faces (truncated?)");
    int64_t n = 0;
    if (!parse_int(words[0], n) || n < 3 || n > kMaxFaceSize)
      lines.fail("expected a face's vertex count in [3, " + std::to_string(kMaxFaceSize) +
                 "], found '" + std::string(words[0].substr(0, 40)) + "'");
    if (words.size() < static_cast<size_t>(n) + 1)
      lines.fail("the face has " + std::to_string(words.size() - 1) + " indices, not " +
                 std::to_string(n));
    for (size_t k = 1; k <= static_cast<size_t>(n); ++k) {
      int64_t index = -1;
      if (!parse_int(words[k], index) || index < 0 || index >= vertices)
        lines.fail("vertex index '" + std::string(words[k].substr(0, 40)) +
                   "' is out of range: the file has " + std::to_string(vertices) +
                   " vertices (0 to " + std::to_string(vertices - 1) + ")");
      out.indices.push_back(static_cast<uint32_t>(index));
    }
    out.face_starts.push_back(static_cast<uint32_t>(out.indices.size()));
    check_extras(lines, words, static_cast<size_t>(n) + 1, extras);
  }
  if (next_content(lines, words))
    lines.fail("more lines than the header's " + std::to_string(vertices) + " vertices and " +
               std::to_string(counts[1]) + " faces");
  warn_ignored(path, {&extras}, out.warnings);
  return out;
}

}  // namespace tacta::mesh_detail
