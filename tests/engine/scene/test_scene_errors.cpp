// Every class of scene error names file:line:column, the key path, the expectation and the find.
#include <gtest/gtest.h>

#include "fake_schemas.hpp"

namespace tacta::testing {
namespace {

// Checks the location fields and that the message carries them and every fragment.
void expect_error(const InputError& e, int line, int column, const std::string& key_path,
                  std::initializer_list<std::string> fragments) {
  EXPECT_EQ(e.where().file, "/scenes/test.yaml");
  EXPECT_EQ(e.where().line, line) << e.what();
  EXPECT_EQ(e.where().column, column) << e.what();
  EXPECT_EQ(e.where().key_path, key_path) << e.what();
  const std::string message = e.what();
  const std::string prefix = "/scenes/test.yaml:" + std::to_string(line) + ":" +
                             std::to_string(column) + ": " +
                             (key_path.empty() ? "" : key_path + ": ");
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
  for (const std::string& fragment : fragments)
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "'" << fragment << "' not in: " << message;
}

// kMinimalScene with its material line replaced.
std::string with_material(const std::string& material) {
  std::string text = yaml(kMinimalScene);
  const std::string old = "material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}";
  text.replace(text.find(old), old.size(), "material: " + material);
  return text;
}

TEST(SceneErrors, YamlSyntax) {
  const InputError e = load_error(yaml(R"(
name: x
bodies: [a, b
gravity: [0, 0, 0]
)"));
  EXPECT_EQ(e.where().file, "/scenes/test.yaml");
  EXPECT_GE(e.where().line, 3);
  EXPECT_GT(e.where().column, 0);
  EXPECT_NE(std::string(e.what()).find("YAML syntax error"), std::string::npos) << e.what();
}

TEST(SceneErrors, UnknownKeyWithHintAtEveryLevel) {
  expect_error(
      load_error(with_material("{youngs_modulos: 1.0e4, poisson_ratio: 0.3}")), 4, 16,
      "bodies[0].material.youngs_modulos",
      {"unknown key 'youngs_modulos'", "did you mean 'youngs_modulus'?", "expected one of"});
  expect_error(load_error("gravty: [0, 0, 0]\n" + yaml(kMinimalScene)), 1, 1, "gravty",
               {"did you mean 'gravity'?"});
  expect_error(load_error(yaml(kMinimalScene) + "clock: {mode: lockstep, duraton_s: 1}\n"), 6, 25,
               "clock.duraton_s", {"did you mean 'duration_s'?"});
  // Far from every key: no hint, but the list.
  const InputError far = load_error(yaml(kMinimalScene) + "zzzzzz: 1\n");
  EXPECT_EQ(std::string(far.what()).find("did you mean"), std::string::npos) << far.what();
  EXPECT_NE(std::string(far.what()).find("expected one of: name, gravity"), std::string::npos);
}

TEST(SceneErrors, WrongType) {
  expect_error(load_error(with_material("{youngs_modulus: soft, poisson_ratio: 0.3}")), 4, 32,
               "bodies[0].material.youngs_modulus", {"expected a number > 0", "found 'soft'"});
  expect_error(load_error("gravity: 9.81\n" + yaml(kMinimalScene)), 1, 10, "gravity",
               {"expected a list of 3 numbers", "found '9.81'"});
  expect_error(load_error(yaml(kMinimalScene) + "output: {frames: maybe}\n"), 6, 18,
               "output.frames", {"expected true or false", "found 'maybe'"});
  expect_error(load_error(yaml(kMinimalScene) + "devices: {name: d}\n"), 6, 10, "devices",
               {"expected a list of devices", "found a map (keys: name)"});
}

TEST(SceneErrors, EmbeddedSurfaceNeedsTets) {
  std::string text = yaml(kMinimalScene);
  const std::string old = "mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2]}}";
  text.replace(text.find(old), old.size(),
               "mesh: {quad_grid: {size: [1, 1], cells: [2, 2]}, surface: s.obj}");
  const InputError e = load_error(text);
  EXPECT_EQ(e.where().key_path, "bodies[0].mesh.surface") << e.what();
  EXPECT_NE(std::string(e.what()).find("only be embedded in tetrahedra"), std::string::npos)
      << e.what();
}

TEST(SceneErrors, OutOfRange) {
  expect_error(load_error(with_material("{youngs_modulus: 1.0e4, poisson_ratio: 0.5}")), 4, 54,
               "bodies[0].material.poisson_ratio",
               {"expected a number in (-1, 0.5)", "found '0.5'"});
  expect_error(load_error(with_material("{youngs_modulus: 0, poisson_ratio: 0.3}")), 4, 32,
               "bodies[0].material.youngs_modulus", {"> 0", "found '0'"});
  expect_error(load_error(with_material("{lame_lambda: 1, lame_mu: -2}")), 4, 41,
               "bodies[0].material.lame_mu", {"> 0", "found '-2'"});
  // lambda <= -2 mu / 3 would make the bulk modulus, hence E, non-positive.
  expect_error(load_error(with_material("{lame_lambda: -1, lame_mu: 1.5}")), 4, 29,
               "bodies[0].material.lame_lambda", {"> -1", "found '-1'"});
  // Node indices are checked against a grid's node count: 3 x 3 x 3 = 27 nodes.
  expect_error(load_error(yaml(kMinimalScene) + "    probe_node: 27\n"), 6, 17,
               "bodies[0].probe_node", {"expected an integer in [0, 26]", "found '27'"});
  const InputError corner = load_error(
      yaml(kMinimalScene), {"bodies.0.mesh=unit_square", "bodies.0.fixed=[{nodes: [1, 4]}]"});
  EXPECT_EQ(corner.where().key_path, "bodies[0].fixed[0].nodes[1]");
  EXPECT_NE(std::string(corner.what()).find("expected an integer in [0, 3], found '4'"),
            std::string::npos)
      << corner.what();
  expect_error(load_error(yaml(kMinimalScene) + "clock: {duration_s: -1}\n"), 6, 21,
               "clock.duration_s", {"expected a number > 0"});
}

TEST(SceneErrors, MissingRequired) {
  const std::string text = yaml(R"(
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2]}}
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
)");
  expect_error(load_error(text), 2, 5, "bodies[0].model", {"missing required key 'model'"});
  expect_error(load_error(with_material("{youngs_modulus: 1.0e4}")), 4, 15,
               "bodies[0].material.poisson_ratio", {"missing required key 'poisson_ratio'"});
  expect_error(load_error("name: x\n"), 1, 1, "bodies", {"missing required key 'bodies'"});
  expect_error(load_error(with_material("{density: 5}")), 4, 15, "bodies[0].material",
               {"exactly one of the pairs", "found neither"});
  expect_error(load_error(with_material("{youngs_modulus: 1, lame_mu: 1}")), 4, 15,
               "bodies[0].material", {"found keys of both"});
}

TEST(SceneErrors, BadPluginParameter) {
  std::string text = yaml(kMinimalScene);
  text.replace(text.find("model: tensor_mass"), 18, "model: {name: tensor_mass, time_stp: 1e-3}");
  expect_error(load_error(text), 5, 32, "bodies[0].model.time_stp",
               {"unknown parameter 'time_stp' for plugin 'tensor_mass'",
                "did you mean 'time_step'?", "its parameters: time_step"});
  text = yaml(kMinimalScene);
  text.replace(text.find("model: tensor_mass"), 18, "model: {name: tensor_mass, time_step: 1}");
  expect_error(load_error(text), 5, 43, "bodies[0].model.time_step",
               {"expected a number in [1e-06, 0.01]", "found '1'"});
  // CHOICE, INT, VECTOR stride and element range.
  const auto model_error = [](const std::string& model) {
    return load_error(yaml(kMinimalScene), {"bodies.0.model=" + model});
  };
  EXPECT_NE(std::string(model_error("{name: corotational_fem, solver: jacobbi}").what())
                .find("did you mean 'jacobi'?"),
            std::string::npos);
  EXPECT_NE(std::string(model_error("{name: corotational_fem, iterations: 2.5}").what())
                .find("expected an integer in [1, 1000]"),
            std::string::npos);
  EXPECT_NE(std::string(model_error("{name: corotational_fem, gains: [1, 2]}").what())
                .find("multiple of 3"),
            std::string::npos);
  const InputError element = model_error("{name: corotational_fem, gains: [1, 2, 30]}");
  EXPECT_EQ(element.where().key_path, "bodies[0].model.gains[2]");
  EXPECT_NE(std::string(element.what()).find("in [-10, 10]"), std::string::npos);
}

TEST(SceneErrors, UnknownPluginListsAvailableOnes) {
  std::string text = yaml(kMinimalScene);
  text.replace(text.find("model: tensor_mass"), 18, "model: corotational");
  expect_error(load_error(text), 5, 12, "bodies[0].model",
               {"unknown model plugin 'corotational'", "did you mean 'corotational_fem'?",
                "available: corotational_fem, mass_spring, tensor_mass"});
  expect_error(load_error(yaml(kMinimalScene) + "devices: [{name: d, plugin: phantom}]\n"), 6, 29,
               "devices[0].plugin",
               {"unknown device plugin 'phantom'", "available: replay, sim_stylus"});
}

TEST(SceneErrors, CollisionPluginsCheckedOnlyWhenEnabled) {
  const std::string off =
      yaml(kMinimalScene) + "collision: {enabled: false, broad_phase: kdtree}\n";
  EXPECT_EQ(load(off).collision.broad_phase, "kdtree");
  expect_error(load_error(yaml(kMinimalScene) + "collision: {broad_phase: kdtree}\n"), 6, 26,
               "collision.broad_phase", {"unknown collision plugin 'kdtree'", "available: bvh"});
}

TEST(SceneErrors, DuplicateNamesAndDanglingReferences) {
  const std::string body =
      "  - name: cube\n    mesh: unit_square\n"
      "    material: {youngs_modulus: 1, poisson_ratio: 0}\n"
      "    model: tensor_mass\n";
  expect_error(load_error(yaml(kMinimalScene) + body), 6, 11, "bodies[1].name",
               {"duplicate body name 'cube'", "first used by bodies[0]"});
  expect_error(
      load_error(yaml(kMinimalScene) + "devices: [{name: d, plugin: replay, touches: cub}]\n"), 6,
      46, "devices[0].touches", {"unknown body 'cub'", "did you mean 'cube'?"});
  expect_error(
      load_error(yaml(kMinimalScene) + "swaps: [{time: 1, body: liver, model: mass_spring}]\n"), 6,
      25, "swaps[0].body", {"unknown body 'liver'", "expected one of: *, cube"});
}

TEST(SceneErrors, ShapesAndPrimitivesNeedExactlyOneKind) {
  std::string text = yaml(kMinimalScene);
  text.replace(text.find("mesh: {box_grid"), 15, "mesh: {sphere: {}, box_grid");
  expect_error(load_error(text), 3, 11, "bodies[0].mesh", {"exactly one of", "found several"});
  expect_error(load_error(yaml(kMinimalScene) + "obstacles: [{name: o, shape: {}}]\n"), 6, 30,
               "obstacles[0].shape", {"exactly one of: sphere, capsule, box, plane, mesh", "none"});
  expect_error(load_error(yaml(kMinimalScene) + "output: {plots: [energi]}\n"), 6, 18,
               "output.plots[0]", {"did you mean 'energy'?"});
}

// One tensor_mass body whose `mesh:` value is `mesh` (line 3 of the scene).
std::string with_mesh(const std::string& mesh) {
  return "bodies:\n  - name: b\n    mesh: " + mesh +
         "\n    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}\n    model: tensor_mass\n";
}

// mesh.tetrahedralize: a map of known keys in range, on a mesh file only, not with voxel_size.
TEST(SceneErrors, TetrahedralizeKeys) {
  const SceneDesc ok = load(with_mesh(
      "{file: organ.stl, tetrahedralize: {max_volume: 1.0e-6, min_dihedral: 5, optimize: false}}"));
  ASSERT_TRUE(ok.bodies[0].mesh.tetrahedralize.has_value());
  EXPECT_DOUBLE_EQ(ok.bodies[0].mesh.tetrahedralize->max_volume, 1e-6);
  EXPECT_DOUBLE_EQ(ok.bodies[0].mesh.tetrahedralize->min_dihedral_deg, 5.0);
  EXPECT_FALSE(ok.bodies[0].mesh.tetrahedralize->optimize);
  EXPECT_TRUE(load(with_mesh("{file: organ.stl, tetrahedralize: true}"))
                  .bodies[0]
                  .mesh.tetrahedralize.has_value());
  EXPECT_FALSE(load(with_mesh("{file: organ.stl}")).bodies[0].mesh.tetrahedralize.has_value());
  expect_error(load_error(with_mesh("{file: organ.stl, tetrahedralize: {min_dihedral: 80}}")), 3,
               60, "bodies[0].mesh.tetrahedralize.min_dihedral", {"in [0, 60]"});
  expect_error(load_error(with_mesh("{file: organ.stl, tetrahedralize: {max_volum: 1}}")), 3, 46,
               "bodies[0].mesh.tetrahedralize.max_volum", {"did you mean 'max_volume'?"});
  expect_error(load_error(with_mesh("{file: organ.stl, voxel_size: 0.01, tetrahedralize: true}")),
               3, 63, "bodies[0].mesh.tetrahedralize", {"not both"});
  expect_error(load_error(with_mesh(
                   "{box_grid: {size: [1, 1, 1], cells: [1, 1, 1]}, tetrahedralize: true}")),
               3, 75, "bodies[0].mesh.tetrahedralize", {"mesh `file` only"});
}

// mesh.max_tets: an integer in range, on a mesh file only, not with a size that fixes the tets.
TEST(SceneErrors, MaxTetsKeys) {
  EXPECT_EQ(load(with_mesh("{file: organ.stl, max_tets: 4000}")).bodies[0].mesh.max_tets, 4000);
  EXPECT_EQ(load(with_mesh("{file: organ.stl, tetrahedralize: true, max_tets: 800}"))
                .bodies[0]
                .mesh.max_tets,
            800);
  expect_error(load_error(with_mesh("{file: organ.stl, voxel_size: 0.01, max_tets: 500}")), 3, 57,
               "bodies[0].mesh.max_tets", {"give one"});
  expect_error(
      load_error(with_mesh("{file: organ.stl, tetrahedralize: {max_volume: 1}, max_tets: 500}")), 3,
      72, "bodies[0].mesh.max_tets", {"give one"});
  expect_error(
      load_error(with_mesh("{box_grid: {size: [1, 1, 1], cells: [1, 1, 1]}, max_tets: 5}")), 3, 69,
      "bodies[0].mesh.max_tets", {"mesh `file` only"});
  expect_error(load_error(with_mesh("{file: organ.stl, max_tets: 0}")), 3, 39,
               "bodies[0].mesh.max_tets", {"12000000"});
}

TEST(SceneErrors, DuplicateKey) {
  expect_error(load_error(yaml(kMinimalScene) + "seed: 1\nseed: 2\n"), 7, 1, "seed",
               {"duplicate key 'seed'"});
}

}  // namespace
}  // namespace tacta::testing
