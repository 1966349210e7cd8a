// Every shipped model's checkpoint through the C ABI, in the configurations `tacta check-plugin`
// (one default setup) does not reach: each solver, preconditioner, integrator, static solves and
// hyperelastic's lagged tangents. A run saves after some steps under a changing load; a fresh
// instance loads the blob (no begin, as a restore does) and its next steps must give the same
// doubles as the original's, counters included. A NO_HISTORY model continues from a fresh
// instance. Blobs from another mesh or another model are refused with a reason.
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "plugin_fixture.hpp"
#include "tacta/model_api.h"
#include "tacta/models/test_meshes.hpp"

namespace {

using tacta::testing::LoadedPlugin;

struct Setting {
  const char* name;
  double number;
  const char* text;  // a CHOICE's name, else null
};

struct Case {
  const char* model;
  std::vector<Setting> settings;
  const char* growing_counter;  // a counter that must grow after the save (the path is taken)
  double youngs_modulus = 3e4;  // Pa: soft enough for the explicit models at 1 ms
};

// e.g. "corotational_fem_preconditioner_incomplete_cholesky_refactor_interval_3": a test name.
std::string label(const Case& c) {
  std::string text = c.model;
  for (const Setting& s : c.settings)
    text += std::string("_") + s.name + "_" +
            (s.text ? s.text : std::to_string(static_cast<long>(s.number)));
  return text;
}

void PrintTo(const Case& c, std::ostream* out) { *out << label(c); }

constexpr double kDt = 1e-3;  // s
constexpr int kBefore = 15, kAfter = 25;

class Instance {
 public:
  Instance(const LoadedPlugin& plugin, const Case& c, const tacta::models::TestMesh& mesh,
           const tacta_material& material)
      : descriptor_(plugin.descriptor(c.model)),
        api_(plugin.api<tacta_model_api>(c.model)),
        params_(tacta::testing::default_params(descriptor_)) {
    for (const Setting& s : c.settings) {
      uint32_t i = 0;
      while (i < descriptor_.param_count && std::string(descriptor_.params[i].name) != s.name) ++i;
      if (i == descriptor_.param_count) throw std::runtime_error(std::string("no ") + s.name);
      params_[i].number = s.number;
      if (s.text) params_[i].text = s.text;
    }
    view_ = mesh.view();
    const tacta_model_setup setup =
        mesh.setup(view_, material, params_.data(), descriptor_.param_count, kDt);
    char message[256] = {};
    if (api_.create(&setup, &instance_, message, sizeof message) != TACTA_OK)
      throw std::runtime_error(std::string("create: ") + message);
  }
  ~Instance() { api_.destroy(instance_); }
  const tacta_model_api& api() const { return api_; }
  bool has_entries() const { return tacta_model_has_state_entries(&api_, descriptor_.api_size); }
  bool no_history() const {
    return tacta_model_claims(&api_, descriptor_.api_size) & TACTA_MODEL_CLAIM_NO_HISTORY;
  }
  void* handle() { return instance_; }
  std::vector<unsigned char> save() {
    std::vector<unsigned char> blob(api_.save_state(instance_, nullptr, 0));
    EXPECT_EQ(api_.save_state(instance_, blob.data(), blob.size()), blob.size());
    return blob;
  }
  std::string load(const std::vector<unsigned char>& blob) {
    char message[256] = {};
    if (api_.load_state(instance_, blob.data(), blob.size(), message, sizeof message) == TACTA_OK)
      return {};
    return message[0] ? message : "(refused with no message)";
  }
  std::vector<std::pair<std::string, double>> counters() {
    std::vector<std::pair<std::string, double>> out;
    if (!api_.counters) return out;
    std::vector<tacta_model_counter> all(api_.counters(instance_, nullptr, 0));
    api_.counters(instance_, all.data(), static_cast<uint32_t>(all.size()));
    for (const tacta_model_counter& c : all) out.emplace_back(c.name, c.value);
    return out;
  }

 private:
  const tacta_descriptor& descriptor_;
  const tacta_model_api& api_;
  tacta::testing::DefaultParams params_;
  tacta_mesh_view view_{};
  void* instance_ = nullptr;
};

// A clamped beam's state under gravity and a tip load that swings at 5 Hz.
struct Motion {
  std::vector<double> x, v, f;
  double time = 0;
  explicit Motion(const tacta::models::TestMesh& mesh)
      : x(mesh.positions), v(x.size(), 0.0), f(x.size(), 0.0) {}
  void steps(Instance& model, const tacta::models::TestMesh& mesh, int count) {
    const uint32_t n = mesh.node_count();
    for (int k = 0; k < count; ++k, time += kDt) {
      for (uint32_t i = 0; i < n; ++i) {
        f[3 * i] = 0.0;
        f[3 * i + 1] = -9.81 * mesh.masses[i];
        f[3 * i + 2] = 0.0;
      }
      f[3 * (n - 1)] = 0.05 * std::sin(2 * M_PI * 5.0 * time);  // N
      tacta_body_state state{n, x.data(), v.data(), f.data(), time};
      const uint32_t bits = model.api().step(model.handle(), &state, kDt);
      ASSERT_EQ(bits & TACTA_STEP_FAULT_MASK, 0u) << "step " << k;
    }
  }
};

tacta::models::TestMesh beam(uint32_t cells_along) {
  tacta::models::TestMesh mesh =
      tacta::models::box_tet_mesh({2, 2, cells_along}, {0.02, 0.02, 0.2}, 1000);
  mesh.fix_plane(2, 0.0);
  return mesh;
}

tacta_material material_of(const Case& c) {
  tacta_material m = tacta::models::make_material(c.youngs_modulus, 0.3, 1000);
  m.rayleigh_mass = 0.5;         // 1/s
  m.rayleigh_stiffness = 0.005;  // s
  return m;
}

std::string plugin_file(const char* model) { return std::string("tacta_") + model + ".so"; }

class ModelCheckpoint : public ::testing::TestWithParam<Case> {};

TEST_P(ModelCheckpoint, RestoredInstanceContinuesBitForBit) {
  const Case& c = GetParam();
  SCOPED_TRACE(label(c));
  const LoadedPlugin plugin(plugin_file(c.model));
  const tacta::models::TestMesh mesh = beam(6);
  const tacta_material material = material_of(c);
  Instance original(plugin, c, mesh, material);
  ASSERT_TRUE(original.has_entries() || original.no_history()) << "not checkpointable";
  Motion run(mesh);
  tacta_body_state start{mesh.node_count(), run.x.data(), run.v.data(), run.f.data(), 0.0};
  if (original.api().begin) original.api().begin(original.handle(), &start, kDt);
  run.steps(original, mesh, kBefore);
  const Motion at_save = run;
  std::vector<unsigned char> blob;
  if (original.has_entries()) blob = original.save();
  const auto counters_at_save = original.counters();
  run.steps(original, mesh, kAfter);

  Instance restored(plugin, c, mesh, material);
  if (restored.has_entries()) {
    ASSERT_EQ(restored.load(blob), "");
  }
  Motion again = at_save;
  again.steps(restored, mesh, kAfter);
  ASSERT_EQ(run.x.size(), again.x.size());
  EXPECT_EQ(std::memcmp(run.x.data(), again.x.data(), run.x.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(run.v.data(), again.v.data(), run.v.size() * sizeof(double)), 0);
  if (original.has_entries()) {
    EXPECT_EQ(original.counters(), restored.counters());
  }
  if (c.growing_counter) {
    double before = -1, after = -1;
    for (const auto& [name, value] : counters_at_save)
      if (name == c.growing_counter) before = value;
    for (const auto& [name, value] : original.counters())
      if (name == c.growing_counter) after = value;
    EXPECT_GT(after, before) << c.growing_counter << " did not grow after the save: the run does "
                             << "not take the path this case is for";
  }
}

TEST_P(ModelCheckpoint, BlobsOfAnotherMeshOrModelAreRefused) {
  const Case& c = GetParam();
  SCOPED_TRACE(label(c));
  const LoadedPlugin plugin(plugin_file(c.model));
  const tacta_material material = material_of(c);
  const tacta::models::TestMesh mesh = beam(6), shorter = beam(5);
  Instance saved(plugin, c, mesh, material);
  if (!saved.has_entries()) GTEST_SKIP() << "NO_HISTORY: nothing to load";
  Instance other_mesh(plugin, c, shorter, material);
  const std::string why = other_mesh.load(saved.save());
  EXPECT_NE(why.find("nodes"), std::string::npos) << why;
  // corotational_fem's blob into any other model, and hyperelastic's into corotational_fem.
  const char* other_model =
      std::string(c.model) == "corotational_fem" ? "hyperelastic" : "corotational_fem";
  const LoadedPlugin other_plugin(plugin_file(other_model));
  Instance foreign(other_plugin, {other_model, {}, nullptr}, mesh, material);
  const std::string foreign_why = saved.load(foreign.save());
  EXPECT_NE(foreign_why.find(other_model), std::string::npos) << foreign_why;
  std::vector<unsigned char> cut = saved.save();
  cut.pop_back();
  EXPECT_NE(saved.load(cut), "");
}

const Case kCases[] = {
    {"corotational_fem", {}, "solves"},
    {"corotational_fem", {{"rotation", 1, "svd"}}, nullptr},
    {"corotational_fem",
     {{"preconditioner", 2, "incomplete_cholesky"}, {"refactor_interval", 3, nullptr}},
     "cg_iterations"},
    {"corotational_fem", {{"preconditioner", 0, "jacobi"}}, nullptr},
    {"corotational_fem", {{"solver", 1, "cholesky"}}, nullptr},
    {"corotational_fem", {{"solve", 1, "static"}}, "static_solves", 3e6},  // small deflection
    {"hyperelastic", {}, "lagged_tangents"},
    {"hyperelastic",
     {{"preconditioner", 2, "incomplete_cholesky"}, {"refactor_interval", 4, nullptr}},
     "lagged_tangents"},
    {"hyperelastic", {{"solver", 1, "cholesky"}}, "lagged_tangents"},
    {"hyperelastic", {{"volumetric", 2, "nodal_average"}}, nullptr},
    {"hyperelastic", {{"material", 1, "stvk"}}, nullptr},
    {"hyperelastic", {{"solve", 1, "static"}}, "static_solves", 3e6},
    {"tensor_mass", {{"integrator", 0, "central_difference"}}, nullptr},
    {"tensor_mass", {{"integrator", 1, "implicit_euler"}}, nullptr},
    {"vbd", {}, nullptr},
    {"vbd", {{"energy", 1, "neo_hookean"}, {"initial_guess", 0, "adaptive"}}, nullptr},
    {"mass_spring", {{"integrator", 0, "symplectic_euler"}}, nullptr},
    {"mass_spring", {{"integrator", 1, "implicit_euler"}}, nullptr},
    {"mass_spring", {{"integrator", 2, "desbrun"}}, nullptr},
    {"fd_debunne", {}, nullptr},
#ifdef TACTA_HAVE_BULLET_PLUGIN
    {"bullet_softbody", {}, nullptr},
#endif
};

INSTANTIATE_TEST_SUITE_P(EveryModel, ModelCheckpoint, ::testing::ValuesIn(kCases),
                         [](const auto& param_info) { return label(param_info.param); });

}  // namespace
