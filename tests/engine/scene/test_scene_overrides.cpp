// --set overrides: wildcard, index, body name, created keys, and their errors.
#include <filesystem>
#include <gtest/gtest.h>

#include "fake_schemas.hpp"

namespace tacta::testing {
namespace {

const char* kTwoBodies = R"(
bodies:
  - name: liver
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [1, 1, 1]}}
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
    model: tensor_mass
  - name: kidney
    mesh: unit_square
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.25}
    model: {name: mass_spring, spring_stiffness: 10}
)";

void expect_override_error(const std::vector<std::string>& overrides, const std::string& key_path,
                           std::initializer_list<std::string> fragments) {
  const InputError e = load_error(yaml(kTwoBodies), overrides);
  EXPECT_EQ(e.where().file, "--set " + overrides.back()) << e.what();
  EXPECT_EQ(e.where().line, 0);
  EXPECT_EQ(e.where().key_path, key_path) << e.what();
  const std::string message = e.what();
  EXPECT_EQ(message.rfind("--set " + overrides.back() + ": ", 0), 0u) << message;
  for (const std::string& fragment : fragments)
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "'" << fragment << "' not in: " << message;
}

TEST(SceneOverrides, WildcardAppliesToEveryBody) {
  const SceneDesc s = load(yaml(kTwoBodies), {"bodies.*.model=corotational_fem"});
  ASSERT_EQ(s.bodies.size(), 2u);
  for (const BodyDesc& body : s.bodies) {
    EXPECT_EQ(body.model, "corotational_fem");
    EXPECT_EQ(body.model_params.size(), 6u);  // the new plugin's schema, defaults filled
  }
}

TEST(SceneOverrides, ByIndexAndByNameWithDerivedValuesRecomputed) {
  const SceneDesc s = load(yaml(kTwoBodies), {"bodies.0.material.youngs_modulus=5e3",
                                              "bodies.kidney.material.density=1100",
                                              "bodies.kidney.model.spring_stiffness=20"});
  EXPECT_DOUBLE_EQ(s.bodies[0].material.youngs_modulus, 5e3);
  // mu = E / (2 (1 + nu)) follows the overridden E.
  EXPECT_DOUBLE_EQ(s.bodies[0].material.lame_mu, 5e3 / 2.6);
  EXPECT_DOUBLE_EQ(s.bodies[0].material.density, 1000);
  EXPECT_DOUBLE_EQ(s.bodies[1].material.density, 1100);
  EXPECT_DOUBLE_EQ(s.bodies[1].model_params.find("spring_stiffness")->number, 20);
}

TEST(SceneOverrides, CreatesMissingKeysAndParsesValuesAsYaml) {
  const SceneDesc s =
      load(yaml(kTwoBodies), {"clock.mode=realtime", "gravity=[0, 0, -1]", "output.plots=[force]",
                              "name=from_cli", "bodies.liver.initial.uniform_velocity=[1,2,3]"});
  EXPECT_EQ(s.clock.mode, ClockDesc::Mode::Realtime);
  EXPECT_EQ(s.gravity, (Vec3{0, 0, -1}));
  EXPECT_EQ(s.output.plots, (std::vector<std::string>{"force"}));
  EXPECT_EQ(s.name, "from_cli");
  EXPECT_EQ(s.bodies[0].uniform_velocity, (Vec3{1, 2, 3}));
  // Later overrides win.
  EXPECT_EQ(load(yaml(kTwoBodies), {"seed=3", "seed=4"}).seed, 4u);
}

TEST(SceneOverrides, RelativePathsFromTheCommandLineUseTheWorkingDirectory) {
  const std::string scene =
      yaml(kTwoBodies) + "devices: [{name: d, plugin: replay, params: {file: a.csv}}]\n";
  EXPECT_EQ(std::string(load(scene).devices[0].params.find("file")->text), "/scenes/a.csv");
  const SceneDesc s = load(scene, {"devices.*.params={file: logs/b.csv}"});
  EXPECT_EQ(std::string(s.devices[0].params.find("file")->text),
            (std::filesystem::current_path() / "logs/b.csv").lexically_normal().string());
}

TEST(SceneOverrides, MalformedOverrides) {
  expect_override_error({"bodies.0.model"}, "", {"expected key.path=value"});
  expect_override_error({"=3"}, "", {"expected key.path=value"});
  expect_override_error({"bodies..model=x"}, "", {"empty segment"});
  expect_override_error({"gravity=[0, 0"}, "", {"not valid YAML"});
  expect_override_error({"bodies.5.model=x"}, "bodies[5]", {"out of range", "has 2 items"});
  expect_override_error({"bodies.spleen.model=x"}, "bodies",
                        {"no element named 'spleen'", "liver, kidney"});
  expect_override_error({"bodies.0.name.first=x"}, "bodies[0].name", {"holds a value"});
  // A key the override creates is reported at the override even when the error is about it.
  expect_override_error({"names.first=x"}, "names", {"did you mean 'name'?"});
  expect_override_error({"devices.*.plugin=replay"}, "devices", {"selects nothing"});
}

TEST(SceneOverrides, UnknownKeysAndBadValuesPointAtTheOverride) {
  expect_override_error({"bodies.0.materia.density=3"}, "bodies[0].materia",
                        {"unknown key 'materia'", "did you mean 'material'?"});
  expect_override_error({"bodies.*.modle=corotational_fem"}, "bodies[0].modle",
                        {"did you mean 'model'?"});
  expect_override_error({"bodies.kidney.material.poisson_ratio=0.7"},
                        "bodies[1].material.poisson_ratio", {"in (-1, 0.5)", "found '0.7'"});
  expect_override_error({"bodies.*.model=corotatonal_fem"}, "bodies[0].model",
                        {"did you mean 'corotational_fem'?"});
  expect_override_error({"bodies.0.model.solver=qr"}, "bodies[0].model", {"holds a value"});
}

}  // namespace
}  // namespace tacta::testing
