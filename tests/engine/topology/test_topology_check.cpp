// topology_problems finds each broken invariant it names, and none in a finalized mesh.
#include <algorithm>
#include <gtest/gtest.h>

#include "cut_test_support.hpp"

namespace tacta {
namespace {

// True when one of the problems mentions `words`.
bool mentions(const std::vector<std::string>& problems, const std::string& words) {
  return std::any_of(problems.begin(), problems.end(),
                     [&](const std::string& p) { return p.find(words) != std::string::npos; });
}

TEST(TopologyProblems, NoneInFinalizedMeshes) {
  EXPECT_TRUE(topology_problems(test::box_4x2x2()).empty());
  EXPECT_TRUE(topology_problems(make_sphere(1.0, {0, 0, 0}, 2)).empty());
}

TEST(TopologyProblems, EachBrokenInvariantIsNamed) {
  const VolumeMesh good = test::box_4x2x2();
  {
    VolumeMesh m = good;  // an inverted tet: no positive volume, and its faces wound inward
    std::swap(m.tets[2], m.tets[3]);
    const auto p = topology_problems(m);
    EXPECT_TRUE(mentions(p, "no positive volume")) << p.size();
    EXPECT_TRUE(mentions(p, "wound outward"));
  }
  {
    VolumeMesh m = good;  // a boundary triangle lost
    m.triangles.resize(m.triangles.size() - 3);
    EXPECT_TRUE(mentions(topology_problems(m), "missing from the boundary"));
  }
  {
    VolumeMesh m = good;  // one listed twice
    m.triangles.insert(m.triangles.end(), good.triangles.begin(), good.triangles.begin() + 3);
    EXPECT_TRUE(mentions(topology_problems(m), "repeat a face"));
  }
  {
    VolumeMesh m = good;  // a boundary triangle wound inward
    std::swap(m.triangles[0], m.triangles[1]);
    EXPECT_TRUE(mentions(topology_problems(m), "wound outward"));
  }
  {
    VolumeMesh m = good;  // an interior face listed as boundary
    const uint32_t* t = &m.tets[0];
    m.triangles.insert(m.triangles.end(), {t[1], t[2], t[3]});
    const auto p = topology_problems(m);
    EXPECT_TRUE(mentions(p, "not a face of exactly one tet") || mentions(p, "repeat a face"));
  }
  {
    VolumeMesh m = good;  // a node in no tet
    m.positions.insert(m.positions.end(), {9, 9, 9});
    EXPECT_TRUE(mentions(topology_problems(m), "in no tet"));
  }
  {
    VolumeMesh m = good;  // an edge lost, one made up, one reversed
    m.edges.resize(m.edges.size() - 2);
    EXPECT_TRUE(mentions(topology_problems(m), "missing from the edge list"));
    m.edges.insert(m.edges.end(), {0, 44});
    EXPECT_TRUE(mentions(topology_problems(m), "no tet's edge"));
    m = good;
    std::swap(m.edges[0], m.edges[1]);
    EXPECT_TRUE(mentions(topology_problems(m), "smaller node first"));
  }
  {
    VolumeMesh m = good;  // a third tet on a face: a copy of tet 0
    m.tets.insert(m.tets.end(), good.tets.begin(), good.tets.begin() + 4);
    EXPECT_TRUE(mentions(topology_problems(m), "more than two tets"));
  }
  {
    VolumeMesh m = good;  // sizes and indices
    m.tets.push_back(0);
    EXPECT_TRUE(mentions(topology_problems(m), "4 per tet"));
    m = good;
    m.tets[5] = 4000;
    EXPECT_TRUE(mentions(topology_problems(m), "past the mesh's"));
    m = good;
    m.dimension = 2;
    EXPECT_TRUE(mentions(topology_problems(m), "dimension"));
  }
}

}  // namespace
}  // namespace tacta
