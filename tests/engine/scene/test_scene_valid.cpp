// A complete, valid scene loads into exactly the SceneDesc it describes.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>

#include "fake_schemas.hpp"

namespace tacta::testing {
namespace {

const char* kFullScene = R"(
name: full_scene
gravity: [0, 0, -9.81]
seed: 42
clock: {mode: realtime, haptic_rate_hz: 2000, render_rate_hz: 30, duration_s: 2.5}
bodies:
  - name: liver
    mesh: {file: meshes/liver.msh, scale: 0.001, translate: [0, 0.1, 0], voxel_size: 0.005, surface: meshes/smooth.obj}
    material: {youngs_modulus: 3.0e3, poisson_ratio: 0.45, density: 1060,
               rayleigh_mass: 0.1, rayleigh_stiffness: 0.01}
    model: {name: corotational_fem, solver: jacobi, iterations: 20, gains: [1, 1, 1, 2, 2, 2],
            cache_file: cache/liver.bin}
    fixed:
      - box: {min: [-1, -1, -1], max: [1, 0, 1]}
      - nodes: [0, 5, 7]
    initial:
      displacement: [{node: 3, value: [0, 0.01, 0]}]
      velocity: [{node: 4, value: [1, 0, 0]}]
      uniform_velocity: [0, 0, -0.5]
    probe_node: 12
    step_rate_hz: 500
    collide: false
  - name: square
    mesh: unit_square
    material: {lame_lambda: 1.0, lame_mu: 1.0}
    model: mass_spring
  - name: ball
    mesh: {sphere: {radius: 0.02, centre: [0, 0.5, 0], subdivisions: 3}}
    material: {youngs_modulus: 1e5, poisson_ratio: 0.0}
    model: tensor_mass
devices:
  - name: stylus
    plugin: {name: sim_stylus, trajectory: circle}
    params: {depth: 0.02}
    tool: {capsule: {radius: 0.003, half_length: 0.02, position: [0, 0.3, 0]}}
    coupling: {stiffness: 800, damping: 2}
    touches: liver
  - name: playback
    plugin: replay
    params: {file: traces/run1.csv}
obstacles:
  - name: floor
    shape: {plane: {normal: [0, 0, 2], offset: -0.1}}
  - name: block
    shape: {box: {half_extents: [0.1, 0.2, 0.3], position: [1, 2, 3]}}
collision:
  broad_phase: {name: bvh, volume: obb}
  narrow_phase: ccd
  friction: 0.2
  self_collision: true
  thickness: 0.0005
swaps:
  - {time: 1.0, body: "*", model: tensor_mass}
  - {time: 2.0, body: liver, model: {name: mass_spring, spring_stiffness: 50}}
output:
  frames: true
  frame_times: [0.5, 1.0]
  frame_size: [640, 480]
  vtk: true
  vtk_interval_s: 0.1
  trace: false
  trajectory: true
  record_interval_s: 0.01
  plots: [phase_portrait, energy]
  plot_nodes: [0, 1, 2, 3]
)";

TEST(SceneLoader, FullSceneRoundTrip) {
  const SceneDesc s = load(yaml(kFullScene));
  EXPECT_EQ(s.path, "/scenes/test.yaml");
  EXPECT_EQ(s.directory, "/scenes");
  EXPECT_EQ(s.name, "full_scene");
  EXPECT_EQ(s.gravity, (Vec3{0, 0, -9.81}));
  EXPECT_EQ(s.seed, 42u);
  EXPECT_EQ(s.clock.mode, ClockDesc::Mode::Realtime);
  EXPECT_DOUBLE_EQ(s.clock.haptic_rate_hz, 2000);
  EXPECT_DOUBLE_EQ(s.clock.render_rate_hz, 30);
  EXPECT_DOUBLE_EQ(s.clock.duration_s, 2.5);

  ASSERT_EQ(s.bodies.size(), 3u);
  const BodyDesc& liver = s.bodies[0];
  EXPECT_EQ(liver.name, "liver");
  EXPECT_EQ(liver.where.line, 6);
  EXPECT_EQ(liver.mesh.kind, MeshSourceDesc::Kind::File);
  EXPECT_EQ(liver.mesh.path, "/scenes/meshes/liver.msh");
  EXPECT_EQ(liver.mesh.scale, (Vec3{0.001, 0.001, 0.001}));
  EXPECT_EQ(liver.mesh.translate, (Vec3{0, 0.1, 0}));
  EXPECT_DOUBLE_EQ(liver.mesh.voxel_size, 0.005);
  EXPECT_EQ(liver.mesh.surface_path, "/scenes/meshes/smooth.obj");
  EXPECT_FALSE(liver.mesh.surface_tet_boundary);
  EXPECT_DOUBLE_EQ(liver.material.youngs_modulus, 3.0e3);
  EXPECT_DOUBLE_EQ(liver.material.poisson_ratio, 0.45);
  EXPECT_DOUBLE_EQ(liver.material.density, 1060);
  EXPECT_DOUBLE_EQ(liver.material.rayleigh_mass, 0.1);
  EXPECT_DOUBLE_EQ(liver.material.rayleigh_stiffness, 0.01);
  EXPECT_EQ(liver.model, "corotational_fem");
  ASSERT_EQ(liver.model_params.size(), 6u);
  EXPECT_EQ(std::string(liver.model_params.find("solver")->text), "jacobi");
  EXPECT_EQ(liver.model_params.find("solver")->number, 2);
  EXPECT_EQ(liver.model_params.find("iterations")->number, 20);
  const tacta_param_value* gains = liver.model_params.find("gains");
  ASSERT_EQ(gains->count, 6u);
  EXPECT_EQ(gains->values[3], 2);
  EXPECT_EQ(std::string(liver.model_params.find("cache_file")->text), "/scenes/cache/liver.bin");
  ASSERT_EQ(liver.fixed.size(), 2u);
  ASSERT_TRUE(liver.fixed[0].box.has_value());
  EXPECT_EQ((*liver.fixed[0].box)[1], (Vec3{1, 0, 1}));
  EXPECT_EQ(liver.fixed[1].indices, (std::vector<uint32_t>{0, 5, 7}));
  ASSERT_EQ(liver.initial_displacement.size(), 1u);
  EXPECT_EQ(liver.initial_displacement[0].node, 3u);
  EXPECT_EQ(liver.initial_displacement[0].value, (Vec3{0, 0.01, 0}));
  ASSERT_EQ(liver.initial_velocity.size(), 1u);
  EXPECT_EQ(liver.initial_velocity[0].value, (Vec3{1, 0, 0}));
  EXPECT_EQ(liver.uniform_velocity, (Vec3{0, 0, -0.5}));
  EXPECT_EQ(liver.probe_node, 12u);
  EXPECT_DOUBLE_EQ(liver.step_rate_hz, 500);
  EXPECT_FALSE(liver.collide);

  const BodyDesc& square = s.bodies[1];
  EXPECT_EQ(square.mesh.kind, MeshSourceDesc::Kind::QuadGrid);
  EXPECT_EQ(square.mesh.size[0], 1.0);
  EXPECT_EQ(square.mesh.cells[0], 1);
  EXPECT_EQ(square.mesh.cells[1], 1);
  EXPECT_TRUE(square.collide);
  EXPECT_EQ(square.model_params.size(), 2u);

  const BodyDesc& ball = s.bodies[2];
  EXPECT_EQ(ball.mesh.kind, MeshSourceDesc::Kind::Sphere);
  EXPECT_DOUBLE_EQ(ball.mesh.radius, 0.02);
  EXPECT_EQ(ball.mesh.origin, (Vec3{0, 0.5, 0}));
  EXPECT_EQ(ball.mesh.subdivisions, 3);

  ASSERT_EQ(s.devices.size(), 2u);
  const DeviceDesc& stylus = s.devices[0];
  EXPECT_EQ(stylus.plugin, "sim_stylus");
  EXPECT_EQ(std::string(stylus.params.find("trajectory")->text), "circle");
  EXPECT_DOUBLE_EQ(stylus.params.find("depth")->number, 0.02);
  EXPECT_DOUBLE_EQ(stylus.params.find("max_force")->number, 3.3);  // default
  EXPECT_EQ(stylus.tool.kind, ShapeDesc::Kind::Capsule);
  EXPECT_DOUBLE_EQ(stylus.tool.half_length, 0.02);
  EXPECT_EQ(stylus.tool.position, (Vec3{0, 0.3, 0}));
  EXPECT_DOUBLE_EQ(stylus.coupling_stiffness, 800);
  EXPECT_DOUBLE_EQ(stylus.coupling_damping, 2);
  EXPECT_EQ(stylus.touches, "liver");
  EXPECT_EQ(std::string(s.devices[1].params.find("file")->text), "/scenes/traces/run1.csv");
  EXPECT_EQ(s.devices[1].tool.kind, ShapeDesc::Kind::Sphere);

  ASSERT_EQ(s.obstacles.size(), 2u);
  EXPECT_EQ(s.obstacles[0].shape.kind, ShapeDesc::Kind::Plane);
  EXPECT_EQ(s.obstacles[0].shape.normal, (Vec3{0, 0, 1}));  // normalised
  EXPECT_DOUBLE_EQ(s.obstacles[0].shape.offset, -0.1);
  EXPECT_EQ(s.obstacles[1].shape.half_extents, (Vec3{0.1, 0.2, 0.3}));

  EXPECT_TRUE(s.collision.enabled);
  EXPECT_EQ(s.collision.broad_phase, "bvh");
  EXPECT_EQ(std::string(s.collision.broad_params.find("volume")->text), "obb");
  EXPECT_EQ(s.collision.broad_params.find("leaf_size")->number, 4);
  EXPECT_EQ(s.collision.narrow_phase, "ccd");
  EXPECT_EQ(s.collision.convex, "convex");
  EXPECT_DOUBLE_EQ(s.collision.friction, 0.2);
  EXPECT_TRUE(s.collision.self_collision);
  EXPECT_DOUBLE_EQ(s.collision.thickness, 0.0005);

  ASSERT_EQ(s.swaps.size(), 2u);
  EXPECT_EQ(s.swaps[0].body, "*");
  EXPECT_EQ(s.swaps[0].model, "tensor_mass");
  EXPECT_EQ(s.swaps[1].body, "liver");
  EXPECT_DOUBLE_EQ(s.swaps[1].params.find("spring_stiffness")->number, 50);

  EXPECT_TRUE(s.output.frames);
  EXPECT_EQ(s.output.frame_times, (std::vector<double>{0.5, 1.0}));
  EXPECT_EQ(s.output.frame_width, 640);
  EXPECT_EQ(s.output.frame_height, 480);
  EXPECT_TRUE(s.output.vtk);
  EXPECT_DOUBLE_EQ(s.output.vtk_interval_s, 0.1);
  EXPECT_FALSE(s.output.trace);
  EXPECT_TRUE(s.output.trajectory);
  EXPECT_DOUBLE_EQ(s.output.record_interval_s, 0.01);
  EXPECT_EQ(s.output.plots, (std::vector<std::string>{"phase_portrait", "energy"}));
  EXPECT_EQ(s.output.plot_nodes, (std::vector<uint32_t>{0, 1, 2, 3}));
}

TEST(SceneLoader, DefaultsWhenKeysAreAbsent) {
  const SceneDesc s = load(yaml(kMinimalScene));
  EXPECT_EQ(s.name, "test");  // the file's stem
  EXPECT_EQ(s.gravity, (Vec3{0, -9.81, 0}));
  EXPECT_EQ(s.clock.mode, ClockDesc::Mode::Lockstep);
  EXPECT_DOUBLE_EQ(s.clock.haptic_rate_hz, 1000);
  EXPECT_FALSE(s.collision.enabled);
  EXPECT_TRUE(s.output.trace);
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(s.bodies[0].material.density, 1000);
  EXPECT_EQ(s.bodies[0].mesh.kind, MeshSourceDesc::Kind::BoxGrid);
  EXPECT_EQ(s.bodies[0].mesh.cells, (std::array<int, 3>{2, 2, 2}));
  EXPECT_DOUBLE_EQ(s.bodies[0].model_params.find("time_step")->number, 1e-3);
}

TEST(SceneLoader, ModelDefaultsFilledInSchemaOrder) {
  const SceneDesc s = load(yaml(kMinimalScene), {"bodies.0.model={name: corotational_fem, "
                                                 "lumped_mass: false, solver: cg}"});
  const ParamSet& p = s.bodies[0].model_params;
  ASSERT_EQ(p.size(), 6u);
  const std::vector<std::string> order{"solver",      "iterations", "tolerance",
                                       "lumped_mass", "gains",      "cache_file"};
  EXPECT_EQ(p.names(), order);
  EXPECT_EQ(std::string(p.data()[0].text), "cg");  // given
  EXPECT_EQ(p.data()[0].number, 0);
  EXPECT_EQ(p.data()[1].number, 50);    // default
  EXPECT_EQ(p.data()[2].number, 1e-6);  // default
  EXPECT_EQ(p.data()[3].number, 0);     // given false
  ASSERT_EQ(p.data()[4].count, 3u);     // default parsed from "1 2 3"
  EXPECT_EQ(p.data()[4].values[2], 3);
  EXPECT_EQ(std::string(p.data()[5].text), "cache.bin");  // default text as the plugin gave it
  // A default CHOICE carries both its index and its name.
  const SceneDesc d = load(yaml(kMinimalScene), {"bodies.0.model=corotational_fem"});
  EXPECT_EQ(std::string(d.bodies[0].model_params.data()[0].text), "cholesky");
  EXPECT_EQ(d.bodies[0].model_params.data()[0].number, 1);
}

TEST(SceneLoader, ParamSetCopyKeepsViewsValid) {
  SceneDesc s = load(yaml(kFullScene));
  const ParamSet copy = s.bodies[0].model_params;
  s.bodies.clear();  // the original storage is gone; the copy must own its text and vectors
  EXPECT_EQ(std::string(copy.find("solver")->text), "jacobi");
  EXPECT_EQ(copy.find("gains")->values[5], 2);
}

TEST(SceneLoader, LoadsFromFileAndResolvesAgainstItsFolder) {
  const std::string path = std::string(TACTA_BINARY_DIR) + "/scene_loader_test_scene.yaml";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string text =
        yaml(kMinimalScene) + "devices: [{name: d, plugin: replay, params: {file: ../x.csv}}]\n";
    std::fputs(text.c_str(), f);
    std::fclose(f);
  }
  const SceneDesc s = load_scene(path, fake_schemas());
  EXPECT_EQ(s.directory, std::string(TACTA_BINARY_DIR));
  const std::string expected =
      std::filesystem::path(std::string(TACTA_BINARY_DIR) + "/../x.csv").lexically_normal();
  EXPECT_EQ(std::string(s.devices[0].params.find("file")->text), expected);
  EXPECT_THROW(load_scene(path + ".missing", fake_schemas()), InputError);
}

}  // namespace
}  // namespace tacta::testing
