// A golden image of an embedded body: SOFA's liver tets carrying the smooth liver surface, dented
// by an analytic displacement of the tet nodes, drawn through make_render_frame as a run's frames
// are. The picture shows the smooth surface following the tets (no tet facets), coloured by the
// surface's own displacement. TACTA_REGEN_GOLDENS=1 (scripts/regen-goldens) rewrites it.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>

#include "headless_fixture.hpp"
#include "tacta/embedded_surface.hpp"
#include "tacta/mesh_io.hpp"
#include "tacta/render/snapshot_frame.hpp"

namespace tacta::render::testing {
namespace {

const std::filesystem::path kGoldenDir =
    std::filesystem::path(TACTA_SOURCE_DIR) / "tests" / "golden";
const std::filesystem::path kOutDir =
    std::filesystem::path(TACTA_BINARY_DIR) / "test-output" / "golden";
const std::string kMeshes = std::string(TACTA_SOURCE_DIR) + "/assets/meshes/";

class EmbeddedBodyGolden : public HeadlessTest {};

TEST_F(EmbeddedBodyGolden, SmoothLiverSurfaceFollowsItsDentedTets) {
  MeshSourceDesc desc;
  desc.path = kMeshes + "liver.msh";
  desc.surface_path = kMeshes + "liver-smooth.obj";
  desc.scale = {0.03, 0.03, 0.03};  // m, as in scenes/liver_palpation.yaml
  const VolumeMesh mesh = load_body_mesh(desc);
  EmbeddedSurface surface = make_embedded_surface(mesh);

  // A Gaussian dent, 12 mm deep and 30 mm wide, pressed down into the liver's upper surface.
  std::vector<double> nodes = mesh.positions;
  const double centre[3] = {-0.05, 0.15, 0.03};
  for (size_t n = 0; n < mesh.node_count(); ++n) {
    const double dx = nodes[3 * n] - centre[0], dz = nodes[3 * n + 2] - centre[2];
    const double height = std::max(0.0, nodes[3 * n + 1] - 0.06) / 0.09;  // 0 low, 1 at the top
    nodes[3 * n + 1] -= 0.012 * height * std::exp(-(dx * dx + dz * dz) / (0.03 * 0.03));
  }
  update_embedded_surface(surface, nodes.data());

  SceneStatic scene;
  BodyStatic body;
  body.name = "liver";
  body.rest_positions = mesh.positions;
  body.triangles = mesh.triangles;
  body.tets = mesh.tets;
  body.surface_rest_positions = surface.rest_positions;
  body.surface_triangles = surface.triangles;
  scene.bodies.push_back(body);
  Snapshot snapshot;
  snapshot.time_s = 1.0;
  BodySnapshot state;
  state.positions = nodes;
  state.velocities.assign(nodes.size(), 0.0);
  state.surface_positions = surface.positions;
  state.model = "analytic dent";
  state.max_displacement_m = 0.012;
  snapshot.bodies.push_back(state);

  const Image actual = renderer().render(make_render_frame(scene, snapshot));
  const auto golden = kGoldenDir / "embedded_liver.png";
  const char* flag = std::getenv("TACTA_REGEN_GOLDENS");
  if (flag != nullptr && std::string(flag) == "1") {
    write_png(golden, actual);
    GTEST_SKIP() << "regenerated " << golden;
  }
  const GoldenResult result = compare_with_golden(actual, golden, kOutDir);
  EXPECT_TRUE(result.comparison.matches) << result.message;
}

}  // namespace
}  // namespace tacta::render::testing
