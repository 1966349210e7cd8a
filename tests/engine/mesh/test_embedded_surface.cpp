// The embedded surface: its weights give back the rest surface, a rigid motion of the tets moves it
// rigidly (normals included), a force spread to the nodes keeps its total force and moment, and
// updating it allocates nothing.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <gtest/gtest.h>
#include <random>

#include "allocation_counter.hpp"  // counts malloc and friends; off under sanitizers
#include "tacta/embedded_surface.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

const std::string kMeshes = std::string(TACTA_SOURCE_DIR) + "/assets/meshes/";

// The two ways a body gets one: a voxelised surface file, and a tet mesh given a finer surface.
VolumeMesh voxelised_sphere() {
  MeshSourceDesc d;
  d.path = kMeshes + "sphere.obj";
  d.voxel_size = 0.4;  // m: a 5-cell-wide ball for a sphere of radius 1 m
  return load_body_mesh(d);
}
VolumeMesh liver_with_smooth_surface() {
  MeshSourceDesc d;
  d.path = kMeshes + "liver.msh";
  d.surface_path = kMeshes + "liver-smooth.obj";
  return load_body_mesh(d);
}

// Largest |a - b| over two flat arrays.
double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
  return worst;
}

// x -> R x + t with R a rotation by `angle` (rad) about the unit axis (1, 2, 2) / 3.
std::array<double, 3> rigid(const double* x, double angle, const std::array<double, 3>& t) {
  const double k[3] = {1.0 / 3, 2.0 / 3, 2.0 / 3};
  const double c = std::cos(angle), s = std::sin(angle);
  const double kx = k[0] * x[0] + k[1] * x[1] + k[2] * x[2];
  const double cross[3] = {k[1] * x[2] - k[2] * x[1], k[2] * x[0] - k[0] * x[2],
                           k[0] * x[1] - k[1] * x[0]};
  std::array<double, 3> out{};
  for (size_t a = 0; a < 3; ++a) out[a] = x[a] * c + cross[a] * s + k[a] * kx * (1 - c) + t[a];
  return out;
}

class EmbeddedSurfaceBoth : public ::testing::TestWithParam<int> {
 protected:
  VolumeMesh mesh() const {
    return GetParam() == 0 ? voxelised_sphere() : liver_with_smooth_surface();
  }
};

TEST_P(EmbeddedSurfaceBoth, WeightsReproduceTheRestSurface) {
  const VolumeMesh m = mesh();
  ASSERT_TRUE(m.embedding.has_value());
  const EmbeddedSurface s = make_embedded_surface(m);
  ASSERT_EQ(s.vertex_count(), m.embedding->surface.vertex_count());
  // Weights sum to one and give back every vertex to round-off (metres-sized meshes).
  for (size_t v = 0; v < s.vertex_count(); ++v)
    EXPECT_NEAR(
        s.weights[4 * v] + s.weights[4 * v + 1] + s.weights[4 * v + 2] + s.weights[4 * v + 3], 1.0,
        1e-12);
  EXPECT_LT(max_difference(s.positions, s.rest_positions), 1e-12);
  RecordProperty("extrapolated_vertices", std::to_string(s.extrapolated_vertices));
  RecordProperty("lowest_weight",
                 std::to_string(*std::min_element(s.weights.begin(), s.weights.end())));
}

TEST_P(EmbeddedSurfaceBoth, ARigidMotionOfTheTetsMovesTheSurfaceRigidly) {
  const VolumeMesh m = mesh();
  EmbeddedSurface s = make_embedded_surface(m);
  const std::vector<double> rest_normals = s.normals;
  const double angle = 0.7;
  const std::array<double, 3> shift{0.3, -1.2, 2.5};
  std::vector<double> moved(m.positions.size());
  for (size_t n = 0; n < m.node_count(); ++n) {
    const auto p = rigid(&m.positions[3 * n], angle, shift);
    for (size_t a = 0; a < 3; ++a) moved[3 * n + a] = p[a];
  }
  update_embedded_surface(s, moved.data());
  double worst_position = 0, worst_normal = 0;
  for (size_t v = 0; v < s.vertex_count(); ++v) {
    const auto p = rigid(&s.rest_positions[3 * v], angle, shift);
    const auto n = rigid(&rest_normals[3 * v], angle, {0, 0, 0});
    for (size_t a = 0; a < 3; ++a) {
      worst_position = std::max(worst_position, std::fabs(s.positions[3 * v + a] - p[a]));
      worst_normal = std::max(worst_normal, std::fabs(s.normals[3 * v + a] - n[a]));
    }
  }
  EXPECT_LT(worst_position, 1e-12);
  EXPECT_LT(worst_normal, 1e-10);
}

TEST_P(EmbeddedSurfaceBoth, SpreadForcesKeepTotalForceAndMoment) {
  const VolumeMesh m = mesh();
  EmbeddedSurface s = make_embedded_surface(m);
  // A deformed state, so the moment is taken about points that are not the rest ones.
  std::vector<double> x = m.positions;
  for (size_t i = 0; i < x.size(); ++i) x[i] += 0.05 * std::sin(3.0 * static_cast<double>(i));
  update_embedded_surface(s, x.data());
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<double> node_forces(x.size(), 0.0);
  double force[3] = {0, 0, 0}, moment[3] = {0, 0, 0};
  auto add_moment = [](double* total, const double* at, const double* f) {
    total[0] += at[1] * f[2] - at[2] * f[1];
    total[1] += at[2] * f[0] - at[0] * f[2];
    total[2] += at[0] * f[1] - at[1] * f[0];
  };
  for (int k = 0; k < 200; ++k) {
    const auto v = static_cast<uint32_t>(random() % s.vertex_count());
    const double f[3] = {unit(random), unit(random), unit(random)};  // N
    spread_to_nodes(s, v, f, node_forces.data());
    for (size_t a = 0; a < 3; ++a) force[a] += f[a];
    add_moment(moment, &s.positions[3 * size_t{v}], f);
  }
  double node_force[3] = {0, 0, 0}, node_moment[3] = {0, 0, 0};
  for (size_t n = 0; n < m.node_count(); ++n) {
    for (size_t a = 0; a < 3; ++a) node_force[a] += node_forces[3 * n + a];
    add_moment(node_moment, &x[3 * n], &node_forces[3 * n]);
  }
  for (size_t a = 0; a < 3; ++a) {
    EXPECT_NEAR(node_force[a], force[a], 1e-11);
    EXPECT_NEAR(node_moment[a], moment[a], 1e-10);
  }
}

TEST_P(EmbeddedSurfaceBoth, UpdatingAllocatesNothing) {
  const VolumeMesh m = mesh();
  EmbeddedSurface s = make_embedded_surface(m);
  std::vector<double> x = m.positions, forces(x.size(), 0.0), out(s.positions.size());
  const double f[3] = {0, 1, 0}, b[3] = {0.2, 0.3, 0.5};
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  g_allocations = 0;
  g_counting = true;
  for (int k = 0; k < 10; ++k) {
    x[0] += 1e-3;
    update_embedded_surface(s, x.data());
    interpolate_to_surface(s, x.data(), out.data());
    spread_to_nodes(s, 0, f, forces.data());
    (void)surface_point(s, 0, b, x.data());
  }
  g_counting = false;
  EXPECT_EQ(g_allocations, 0);
}

INSTANTIATE_TEST_SUITE_P(VoxelisedAndGiven, EmbeddedSurfaceBoth, ::testing::Values(0, 1),
                         [](const ::testing::TestParamInfo<int>& p) {
                           return p.param == 0 ? "VoxelisedSphere" : "LiverSmooth";
                         });

TEST(EmbeddedSurface, TetBoundaryKeepsTheVoxelSurface) {
  MeshSourceDesc d;
  d.path = kMeshes + "sphere.obj";
  d.voxel_size = 0.4;
  d.surface_tet_boundary = true;
  EXPECT_FALSE(load_body_mesh(d).embedding.has_value());
}

TEST(EmbeddedSurface, BindingALiverSurfaceOutsideItsTetsIsReported) {
  // liver-smooth.obj bulges past liver.msh in places: those vertices are bound by extrapolation.
  MeshSourceDesc d;
  d.path = kMeshes + "liver.msh";
  d.surface_path = kMeshes + "liver-smooth.obj";
  LoadReport report;
  const VolumeMesh m = load_body_mesh(d, &report);
  const EmbeddedSurface s = make_embedded_surface(m);
  EXPECT_GT(s.extrapolated_vertices, 0u);
  bool warned = false;
  for (const std::string& w : report.warnings)
    warned = warned || w.find("extrapolation") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(EmbeddedSurface, TextureCoordinatesFollowTheTrianglesThroughAMirror) {
  // A unit cube, each face with its own (u, v) square: the corners are welded to 8 vertices, the
  // coordinates stay per triangle corner (a seam keeps both sides).
  const std::string path = ::testing::TempDir() + "/tacta_uv_cube.obj";
  {
    std::ofstream out(path);
    out << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    const int faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                             {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}};
    for (const auto& f : faces)
      out << "f " << f[0] << "/1 " << f[1] << "/2 " << f[2] << "/3\nf " << f[0] << "/1 " << f[2]
          << "/3 " << f[3] << "/4\n";
  }
  MeshSourceDesc d;
  d.path = path;
  d.voxel_size = 0.5;
  d.scale = {-1, 1, 1};  // a mirror: the winding flips, and the corners' coordinates with it
  const VolumeMesh m = load_body_mesh(d);
  const EmbeddedSurface s = make_embedded_surface(m);
  ASSERT_EQ(s.vertex_count(), 8u);
  ASSERT_EQ(s.corner_uvs.size(), 6 * s.triangle_count());
  // Every corner keeps the coordinate written for it: the cube corner (x, y, z) of face f.
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    double sum = 0;
    for (size_t k = 0; k < 6; ++k) sum += s.corner_uvs[6 * t + k];
    EXPECT_DOUBLE_EQ(sum, 3.0) << "triangle " << t;  // (0,0)+(1,0)+(1,1) or (0,0)+(1,1)+(0,1)
  }
  // Triangle 0 was written (v1 vt1, v4 vt2, v3 vt3); mirrored it is stored (v1, v3, v4).
  EXPECT_EQ(s.corner_uvs[2], 1.0);  // v3's (1, 1)
  EXPECT_EQ(s.corner_uvs[3], 1.0);
  EXPECT_EQ(s.corner_uvs[4], 1.0);  // v4's (1, 0)
  EXPECT_EQ(s.corner_uvs[5], 0.0);
}

TEST(EmbeddedSurface, AMissingSurfaceFileIsAClearError) {
  MeshSourceDesc d;
  d.path = kMeshes + "liver.msh";
  d.surface_path = kMeshes + "no_such_surface.obj";
  try {
    (void)load_body_mesh(d);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_surface.obj"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tacta
