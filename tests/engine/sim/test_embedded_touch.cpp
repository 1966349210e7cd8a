// Touching an embedded surface: the simulated stylus strokes over the top of a held sphere that
// was loaded from a surface file (an icosphere of 5,120 triangles, so its facets tilt the normal
// by under 2 degrees) and voxelised coarsely (5 cells across). Through its embedded
// surface the force stays along the sphere's analytic normal and changes smoothly; through the
// boundary of its voxel tets (`surface: tet_boundary`) the same stroke feels the staircase: the
// force tilts towards the voxel faces' axes and jumps where the proxy crosses a voxel edge.
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

constexpr double kRadius = 0.05;   // m, sphere.obj (unit radius) scaled by 0.05
constexpr double kCentreY = 0.06;  // m

// A unit icosphere (the icosahedron split `levels` times, vertices pushed onto the sphere) as OBJ.
std::string write_icosphere(int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                          {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                          {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (auto it = middle.find(key); it != middle.end()) return it->second;
      v.push_back({(v[a][0] + v[b][0]) / 2, (v[a][1] + v[b][1]) / 2, (v[a][2] + v[b][2]) / 2});
      return middle[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    f = std::move(finer);
  }
  // A folder per level: each test uses its own level, and ctest runs tests as parallel processes.
  const std::string path = fresh_dir("icosphere_" + std::to_string(levels)) + "/icosphere.obj";
  std::ofstream out(path);
  for (const auto& p : v) {
    const double r = std::hypot(p[0], p[1], p[2]);
    out << "v " << p[0] / r << " " << p[1] / r << " " << p[2] / r << "\n";
  }
  for (const auto& t : f) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  return path;
}

// The stylus comes down on the sphere at 50 degrees left of its top, strokes 10 mm below its
// surface over the top to 50 degrees right (2 s), and lifts off.
std::string stroke_scene(const std::string& sphere, const std::string& surface) {
  std::string waypoints = "0, -0.0766, 0.135, 0";
  constexpr int kPoints = 41;
  for (int i = 0; i < kPoints; ++i) {
    const double angle = (-50.0 + 100.0 * i / (kPoints - 1)) * M_PI / 180.0;
    const double r = kRadius - 0.010;
    char point[96];
    std::snprintf(point, sizeof point, ",  %.4f, %.6f, %.6f, 0", 0.3 + 2.0 * i / (kPoints - 1),
                  r * std::sin(angle), kCentreY + r * std::cos(angle));
    waypoints += point;
  }
  return R"(
name: embedded_stroke
gravity: [0, 0, 0]
seed: 5
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 2.4}
bodies:
  - name: ball
    mesh:
      file: )" +
         sphere + R"(
      scale: 0.05
      translate: [0, 0.06, 0]
      voxel_size: 0.02
      surface: )" +
         surface + R"(
    material: {youngs_modulus: 1.0e5, poisson_ratio: 0.3, density: 1000}
    model: corotational_fem
    fixed: [{box: {min: [-1, -1, -1], max: [1, 1, 1]}}]   # held: the analytic sphere stays exact
devices:
  - name: stylus
    plugin: sim_stylus
    params: {workspace_origin: [0, 0.1, 0], pattern: waypoints, waypoints: [)" +
         waypoints + R"(]}
    tool: {sphere: {radius: 0.002}}
    coupling: {stiffness: 200, damping: 0.1}
    touches: ball
collision: {broad_phase: bvh}
)";
}

struct StrokeFeel {
  double worst_angle_deg = 0;  // force direction against the analytic normal at the proxy
  double mean_angle_deg = 0;
  double largest_step_N = 0;  // largest change of |F| from one tick to the next
  int samples = 0;
  int contact_lost = 0;               // sampled ticks out of contact
  double worst_reaction_error_N = 0;  // |sum of node reactions + device force|, any tick
};

// Runs the stroke; samples the ticks between 0.6 s and 2.1 s (in steady contact).
StrokeFeel feel_stroke(const std::string& sphere, const std::string& surface) {
  const SceneDesc scene = scene_from_text(stroke_scene(sphere, surface), "embedded_stroke");
  LoopHarness h(scene, 2400);
  StrokeFeel feel;
  double previous = -1, angle_sum = 0;
  for (int k = 0; k < 2400; ++k) {
    h.tick();
    const DeviceComponents dev = h.world.device(0);
    // Newton's third law through the embedding: the nodes get exactly minus the device force.
    const SoftBody body = h.world.body(0);
    for (size_t a = 0; a < 3; ++a) {
      double sum = 0;
      for (size_t n = 0; n < body.node_count(); ++n) sum += body.loads.contact_forces[3 * n + a];
      feel.worst_reaction_error_N =
          std::max(feel.worst_reaction_error_N,
                   std::fabs(sum + (dev.contact.in_contact ? dev.contact.force[a] : 0.0)));
    }
    const double t = static_cast<double>(k + 1) * h.dt;
    if (t < 0.6 || t > 2.1) continue;
    const double magnitude =
        std::hypot(dev.contact.force[0], dev.contact.force[1], dev.contact.force[2]);
    if (previous >= 0)
      feel.largest_step_N = std::max(feel.largest_step_N, std::fabs(magnitude - previous));
    previous = magnitude;
    if (!dev.contact.in_contact || !(magnitude > 0)) {
      ++feel.contact_lost;
      continue;
    }
    const double normal[3] = {dev.contact.proxy[0], dev.contact.proxy[1] - kCentreY,
                              dev.contact.proxy[2]};
    const double length = std::hypot(normal[0], normal[1], normal[2]);
    const double cosine = (dev.contact.force[0] * normal[0] + dev.contact.force[1] * normal[1] +
                           dev.contact.force[2] * normal[2]) /
                          (magnitude * length);
    const double angle = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI;
    feel.worst_angle_deg = std::max(feel.worst_angle_deg, angle);
    angle_sum += angle;
    ++feel.samples;
  }
  feel.mean_angle_deg = angle_sum / std::max(feel.samples, 1);
  return feel;
}

TEST(EmbeddedTouch, StrokingAnEmbeddedSphereFollowsItsNormalWithoutSteps) {
  const std::string sphere = write_icosphere(4);
  const StrokeFeel smooth = feel_stroke(sphere, sphere);
  const StrokeFeel voxels = feel_stroke(sphere, "tet_boundary");
  RecordProperty("embedded_worst_angle_deg", std::to_string(smooth.worst_angle_deg));
  RecordProperty("embedded_mean_angle_deg", std::to_string(smooth.mean_angle_deg));
  RecordProperty("embedded_largest_step_N", std::to_string(smooth.largest_step_N));
  RecordProperty("voxel_worst_angle_deg", std::to_string(voxels.worst_angle_deg));
  RecordProperty("voxel_mean_angle_deg", std::to_string(voxels.mean_angle_deg));
  RecordProperty("voxel_largest_step_N", std::to_string(voxels.largest_step_N));
  std::printf("embedded: worst %.2f deg, mean %.2f deg, largest |F| step %.4f N (%d ticks)\n",
              smooth.worst_angle_deg, smooth.mean_angle_deg, smooth.largest_step_N, smooth.samples);
  std::printf(
      "voxel boundary: worst %.2f deg, mean %.2f deg, largest |F| step %.4f N (%d ticks, %d out of "
      "contact)\n",
      voxels.worst_angle_deg, voxels.mean_angle_deg, voxels.largest_step_N, voxels.samples,
      voxels.contact_lost);
  ASSERT_EQ(smooth.samples, 1501);  // in contact all along
  EXPECT_EQ(smooth.contact_lost, 0);
  EXPECT_LT(smooth.worst_angle_deg, 5.0);
  EXPECT_LT(smooth.largest_step_N, 0.02);
  EXPECT_LT(smooth.worst_reaction_error_N, 1e-12);
  // The staircase, for contrast: the voxel boundary tilts the force far off the normal and steps.
  EXPECT_GT(voxels.worst_angle_deg, 3 * smooth.worst_angle_deg);
  EXPECT_GT(voxels.largest_step_N, 3 * smooth.largest_step_N);
}

// A ball dropped 2 cm onto a table with contact response on: what rests on the table is the
// embedded sphere (its lowest vertex at the table, within the contact margin and the tick's
// motion), not its voxel staircase (whose lowest voxel face lies up to a cell above or below).
// A 10 cm ball loaded from a surface file (voxelised, 2 cm cells) 2 cm above a table.
std::string drop_scene(const std::string& sphere) {
  return R"(
name: embedded_drop
gravity: [0, -9.81, 0]
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 1.0}
bodies:
  - name: ball
    mesh: {file: )" +
         sphere + R"(, scale: 0.05, translate: [0, 0.07, 0], voxel_size: 0.02}
    material: {youngs_modulus: 3.0e4, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 5.0}
    model: corotational_fem
obstacles:
  - name: table
    shape: {plane: {normal: [0, 1, 0], offset: 0}}
collision: {enabled: true, broad_phase: bvh, narrow_phase: ccd, convex: convex, friction: 0.4}
)";
}

TEST(EmbeddedTouch, ADroppedEmbeddedBallRestsOnItsSmoothSurface) {
  const SceneDesc scene = scene_from_text(drop_scene(write_icosphere(3)), "embedded_drop");
  World world(scene, plugins());
  CollisionContext collision(world, plugins());
  CollisionResponse response(collision);
  TripleBuffer<Snapshot> snapshots(HapticLoop::make_prototype(world));
  HapticLoop loop(world, snapshots, 1000);
  loop.set_response(&response);
  const SoftBody ball = world.body(0);
  ASSERT_TRUE(ball.surface.mesh != nullptr);
  const double dt = 1e-3;
  ball.model.instance->begin(ball.state_view(0.0), dt);
  double lowest_ever = 1;
  for (uint64_t k = 0; k < 1000; ++k) {
    loop.tick(k, static_cast<double>(k) * dt, dt);
    update_embedded_surface(*ball.surface.mesh, ball.nodes.positions.data());
    for (size_t v = 0; v < ball.surface.mesh->vertex_count(); ++v)
      lowest_ever = std::min(lowest_ever, ball.surface.mesh->positions[3 * v + 1]);
  }
  ASSERT_FALSE(ball.fault.frozen) << ball.fault.reason.data();
  double lowest_surface = 1, lowest_node = 1;
  for (size_t v = 0; v < ball.surface.mesh->vertex_count(); ++v)
    lowest_surface = std::min(lowest_surface, ball.surface.mesh->positions[3 * v + 1]);
  for (size_t n = 0; n < ball.node_count(); ++n)
    lowest_node = std::min(lowest_node, ball.nodes.positions[3 * n + 1]);
  std::printf("lowest surface vertex %.4f m (ever %.4f m), lowest node %.4f m\n", lowest_surface,
              lowest_ever, lowest_node);
  RecordProperty("lowest_surface_m", std::to_string(lowest_surface));
  RecordProperty("lowest_surface_ever_m", std::to_string(lowest_ever));
  EXPECT_GT(lowest_ever, -2e-3);           // never sank more than 2 mm into the table
  EXPECT_NEAR(lowest_surface, 0.0, 1e-3);  // and rests on it (a 10 cm ball, 2 cm voxels)
  EXPECT_GT(response.contacts_total(), 0u);
}

// The demo with contact response on: the tool's collision shape starts at the proxy, not at the
// origin (from there its first sweep cut through the liver's embedded surface and froze the body).
TEST(EmbeddedTouch, TheDemoWithCollisionOnStartsWithoutAFault) {
  std::ifstream in(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const SceneDesc scene = scene_from_text(text, "liver_palpation",
                                          {"collision.enabled=true", "clock.duration_s=0.02",
                                           "output.frames=false", "output.vtk=false"});
  const RunResult result = run_scene(scene);
  EXPECT_EQ(result.faults, 0u);
  EXPECT_EQ(result.exit_code, 0);
}

TEST(EmbeddedTouch, TheVtkSeriesAndTheReportHoldTheEmbeddedSurface) {
  const std::string dir = fresh_dir("embedded_vtk");
  const SceneDesc scene = scene_from_text(drop_scene(write_icosphere(2)), "embedded_vtk",
                                          {"clock.duration_s=0.05", "output.vtk=true"});
  RunOptions options;
  options.out_dir = dir;
  const RunResult result = run_scene(scene, options);
  ASSERT_EQ(result.exit_code, 0);
  ASSERT_TRUE(std::filesystem::exists(dir + "/vtk/ball_surface.pvd"));
  std::ifstream in(dir + "/vtk/ball_surface_000000.vtu");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The icosphere split twice: 162 vertices, 320 triangles.
  EXPECT_NE(text.find("NumberOfPoints=\"162\" NumberOfCells=\"320\""), std::string::npos)
      << text.substr(0, 400);
  EXPECT_NE(text.find("Name=\"displacement\""), std::string::npos);
  // report.json says what the body was shown and touched through.
  std::ifstream report_file(dir + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(report_file);
  const nlohmann::json& surface = report.at("bodies").at(0).at("surface");
  EXPECT_EQ(surface.at("vertices").get<int>(), 162);
  EXPECT_EQ(surface.at("triangles").get<int>(), 320);
  EXPECT_NE(surface.at("source").get<std::string>().find("icosphere.obj"), std::string::npos);
}

}  // namespace
}  // namespace tacta::simtest
