#include <cstdint>
#include <cstring>
#include <string_view>

#include "mesh/surface_readers.hpp"
#include "mesh/text_reader.hpp"
#include "tacta/error.hpp"

namespace tacta::mesh_detail {

void check_stl(const std::string& path, const std::string& bytes) {
  if (bytes.size() >= 84) {
    uint32_t facets = 0;
    std::memcpy(&facets, bytes.data() + 80, sizeof facets);
    if (84 + 50 * static_cast<uint64_t>(facets) == bytes.size())
      return;  // binary; values checked after import
    if (static_cast<uint32_t>(84 + 50 * facets) == bytes.size()) {
      throw InputError({path, 0, 0, ""}, "binary STL with " + std::to_string(facets) +
                                             " facets cannot be " + std::to_string(bytes.size()) +
                                             " bytes long");
    }
  }
  LineWords lines(path, bytes);
  enum class Place { BeforeSolid, InSolid, InFacet, InLoop, AfterLoop } place = Place::BeforeSolid;
  int loop_vertices = 0;
  while (lines.next()) {
    const auto& w = lines.words();
    if (w.empty()) continue;
    const std::string_view keyword = w[0];
    auto expect = [&](Place where) {
      static constexpr const char* kExpected[] = {"'solid'", "'facet normal' or 'endsolid'",
                                                  "'outer loop'", "'vertex' or 'endloop'",
                                                  "'endfacet'"};
      if (place != where) {
        lines.fail("unexpected '" + std::string(keyword.substr(0, 40)) + "', expected " +
                   kExpected[static_cast<int>(place)]);
      }
    };
    if (keyword == "solid") {
      expect(Place::BeforeSolid);
      place = Place::InSolid;
    } else if (keyword == "facet") {
      expect(Place::InSolid);
      if (w.size() != 5 || w[1] != "normal") lines.fail("expected 'facet normal nx ny nz'");
      lines.expect_numbers(2, 5, "a normal component");
      place = Place::InFacet;
    } else if (keyword == "outer") {
      expect(Place::InFacet);
      if (w.size() != 2 || w[1] != "loop") lines.fail("expected 'outer loop'");
      place = Place::InLoop;
      loop_vertices = 0;
    } else if (keyword == "vertex") {
      expect(Place::InLoop);
      if (w.size() != 4) lines.fail("expected 'vertex x y z'");
      lines.expect_numbers(1, 4, "a vertex coordinate");
      ++loop_vertices;
    } else if (keyword == "endloop") {
      expect(Place::InLoop);
      if (loop_vertices != 3)
        lines.fail("a facet needs 3 vertices, found " + std::to_string(loop_vertices));
      place = Place::AfterLoop;
    } else if (keyword == "endfacet") {
      expect(Place::AfterLoop);
      place = Place::InSolid;
    } else if (keyword == "endsolid") {
      expect(Place::InSolid);
      place = Place::BeforeSolid;
    } else {
      lines.fail(place == Place::BeforeSolid && !bytes.starts_with("solid")
                     ? "neither a binary STL (84 + 50 bytes per facet) nor an ASCII STL (starting "
                       "with 'solid')"
                     : "expected an ASCII STL keyword (solid, facet, outer, vertex, endloop, "
                       "endfacet, endsolid), found '" +
                           std::string(keyword.substr(0, 40)) + "'");
    }
  }
  if (place != Place::BeforeSolid) {
    throw InputError({path, 0, 0, ""}, "the ASCII STL ends before 'endsolid' (truncated?)");
  }
}

}  // namespace tacta::mesh_detail
