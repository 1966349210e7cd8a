#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/surface_readers.hpp"
#include "mesh/text_reader.hpp"
#include "tacta/error.hpp"

namespace tacta::mesh_detail {

namespace {

constexpr int64_t kMaxIndex = 4'000'000'000;  // what a uint32_t vertex index holds

// OBJ indices of one kind (1-based, or negative: relative to the count so far). Vertex indices
// are geometry and strict; a bad texture-coordinate or normal index is noted in `ignored`.
struct IndexCheck {
  const char* kind;                     // "vertex", "texture coordinate", "normal"
  IgnoredAttribute* ignored = nullptr;  // null: errors are fatal
  int64_t count = 0;                    // defined so far
  int64_t largest = 0;  // largest positive index used, checked against the final count
  int largest_line = 0;
  void bad(const LineWords& lines, const std::string& message) const {
    if (ignored == nullptr) lines.fail(message);
    ignored->note(lines.line(), message);
  }
  // The 0-based index token refers to (-1 when it is bad and ignored); a positive one may refer
  // ahead and is checked at the end.
  int64_t use(const LineWords& lines, std::string_view token) {
    int64_t index = 0;
    if (!parse_int(token, index) || index == 0 || index > kMaxIndex || index < -kMaxIndex) {
      bad(lines, std::string("expected a ") + kind + " index (a non-zero integer), found '" +
                     std::string(token.substr(0, 40)) + "'");
      return -1;
    }
    if (index < 0) {
      if (-index > count) {
        bad(lines, std::string(kind) + " index " + std::to_string(index) +
                       " reaches before the first " + kind + " (" + std::to_string(count) +
                       " so far)");
        return -1;
      }
      return count + index;
    }
    if (index > largest) {
      largest = index;
      largest_line = lines.line();
    }
    return index - 1;
  }
  void check_final(const std::string& path) const {
    if (largest <= count) return;
    const std::string message = std::string(kind) + " index " + std::to_string(largest) +
                                " is out of range: the file has " + std::to_string(count);
    if (ignored == nullptr) throw InputError({path, largest_line, 0, ""}, message);
    ignored->note(largest_line, message);
  }
};

}  // namespace

PolygonSoup read_obj(const std::string& path, const std::string& bytes) {
  PolygonSoup out;
  out.face_starts.push_back(0);
  LineWords lines(path, bytes);
  IgnoredAttribute bad_uvs{"texture coordinates"}, bad_normals{"normals"},
      bad_colours{"vertex colours (values after x y z on 'v' lines)"};
  IndexCheck vertices{"vertex"}, texture{"texture coordinate", &bad_uvs},
      normals{"normal", &bad_normals};
  std::vector<double> uvs;              // u v of every vt line
  std::vector<int64_t> corner_texture;  // vt index of every face corner, -1 when it has none
  auto numbers = [&](size_t first, double* values, IgnoredAttribute& ignored, const char* what) {
    const auto& w = lines.words();
    for (size_t i = first; i < w.size(); ++i) {
      double v = 0;
      if (!parse_double(w[i], v) || !std::isfinite(v)) {
        ignored.note(lines.line(), std::string("expected ") + what + " (a finite number), found '" +
                                       std::string(w[i].substr(0, 40)) + "'");
        return;
      }
      if (values != nullptr) values[i - first] = v;
    }
  };
  while (lines.next()) {
    const auto& w = lines.words();
    if (w.empty()) continue;
    const std::string_view keyword = w[0];
    if (keyword == "v") {
      if (w.size() < 4) lines.fail("expected 'v x y z' (with w, or r g b, optional)");
      double xyz[3];
      lines.expect_numbers(1, 4, "a vertex coordinate", xyz);
      out.positions.insert(out.positions.end(), xyz, xyz + 3);
      numbers(4, nullptr, bad_colours, "a vertex colour or weight");
      ++vertices.count;
    } else if (keyword == "vt") {
      double uvw[3] = {0, 0, 0};
      if (w.size() < 2 || w.size() > 4) {
        bad_uvs.note(lines.line(), "expected 'vt u [v [w]]'");
      } else {
        numbers(1, uvw, bad_uvs, "a texture coordinate");
      }
      uvs.insert(uvs.end(), uvw, uvw + 2);
      ++texture.count;
    } else if (keyword == "vn") {
      if (w.size() != 4) bad_normals.note(lines.line(), "expected 'vn x y z'");
      numbers(1, nullptr, bad_normals, "a normal component");
      ++normals.count;
    } else if (keyword == "f" || keyword == "l" || keyword == "p") {
      const size_t least = keyword == "f" ? 3 : keyword == "l" ? 2 : 1;
      if (w.size() < least + 1) {
        lines.fail("'" + std::string(keyword) + "' needs at least " + std::to_string(least) +
                   " vertices, found " + std::to_string(w.size() - 1));
      }
      for (size_t i = 1; i < w.size(); ++i) {
        std::string_view ref = w[i];  // v, v/vt, v//vn or v/vt/vn
        IndexCheck* parts[3] = {&vertices, &texture, &normals};
        if (keyword == "f") corner_texture.push_back(-1);
        for (int part = 0; part < 3; ++part) {
          const size_t slash = ref.find('/');
          const std::string_view token = ref.substr(0, slash);
          if (part == 0 || !token.empty()) {
            const int64_t index = parts[part]->use(lines, token);
            if (part == 0 && keyword == "f") out.indices.push_back(static_cast<uint32_t>(index));
            if (part == 1 && keyword == "f") corner_texture.back() = index;
          }
          if (slash == std::string_view::npos) break;
          if (part == 2)
            lines.fail("expected v, v/vt, v//vn or v/vt/vn, found '" +
                       std::string(w[i].substr(0, 40)) + "'");
          ref.remove_prefix(slash + 1);
        }
      }
      if (keyword == "f") out.face_starts.push_back(static_cast<uint32_t>(out.indices.size()));
    }
  }
  vertices.check_final(path);
  texture.check_final(path);
  normals.check_final(path);
  if (texture.count > 0 && bad_uvs.count == 0) {
    out.corner_uvs.reserve(2 * corner_texture.size());
    for (int64_t t : corner_texture) {
      out.corner_uvs.push_back(t < 0 ? 0.0 : uvs[2 * static_cast<size_t>(t)]);
      out.corner_uvs.push_back(t < 0 ? 0.0 : uvs[2 * static_cast<size_t>(t) + 1]);
    }
  }
  warn_ignored(path, {&bad_uvs, &bad_normals, &bad_colours}, out.warnings);
  return out;
}

}  // namespace tacta::mesh_detail
