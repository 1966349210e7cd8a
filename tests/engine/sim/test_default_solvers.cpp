// The corotational FEM's default solver (CG with its fallbacks) against the direct solve on the
// project's scenes: SOFA's beams benchmark and the liver demo. Each body's largest displacement
// over the run must agree within 0.5%, with no solve left unconverged.
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sanitizer_skip.hpp"
#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

double counter(const BodyResult& body, const std::string& name) {
  for (const auto& [key, value] : body.model_counters)
    if (key == name) return value;
  ADD_FAILURE() << body.name << " has no counter " << name;
  return -1.0;
}

// direct_overrides: --set strings that put the bodies listed on the sparse Cholesky solver.
void expect_default_follows_direct(const std::string& scene_file, const std::vector<size_t>& bodies,
                                   const std::vector<std::string>& direct_overrides,
                                   const RunOptions& options) {
  const std::string path = std::string(TACTA_SOURCE_DIR) + "/scenes/" + scene_file;
  const RunResult safe = run_scene(load_scene(path, schemas(), {}), options);
  const RunResult direct = run_scene(load_scene(path, schemas(), direct_overrides), options);
  ASSERT_EQ(safe.exit_code, 0);
  ASSERT_EQ(direct.exit_code, 0);
  for (const size_t b : bodies) {
    const BodyResult& s = safe.bodies[b];
    const BodyResult& d = direct.bodies[b];
    EXPECT_NEAR(s.max_displacement_m / d.max_displacement_m, 1.0, 0.005)
        << scene_file << " " << s.name;
    EXPECT_EQ(counter(s, "unconverged_solves"), 0.0) << s.name;
    EXPECT_GT(counter(s, "solves"), 0.0) << s.name;
  }
}

TEST(DefaultSolvers, SofaBeamsFollowTheDirectSolve) {
  // Bodies 1-3 are corotational (0 is tensor_mass); 1 s of the scene's 2 s.
  RunOptions options;
  options.duration_s = 1.0;
  expect_default_follows_direct(
      "bench/sofa_beams.yaml", {1, 2, 3},
      {"bodies.1.model={name: corotational_fem, solver: cholesky}",
       "bodies.2.model={name: corotational_fem, solver: cholesky}",
       "bodies.3.model={name: corotational_fem, solver: cholesky, rotation: svd}"},
      options);
}

TEST(DefaultSolvers, LiverDemoFollowsTheDirectSolve) {
  TACTA_HEAVY_RUN();
  // The first palpation: the stylus presses during the scene's first 1.5 s.
  RunOptions options;
  options.duration_s = 1.5;
  options.out_dir = fresh_dir("default_solvers_liver");
  expect_default_follows_direct("liver_palpation.yaml", {0},
                                {"bodies.0.model={name: corotational_fem, solver: cholesky}"},
                                options);
  // The counters reach report.json (the direct run wrote last; its CG counters are zero).
  std::ifstream in(options.out_dir + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& counters = report["bodies"][0]["model_counters"];
  for (const char* key :
       {"solves", "cg_iterations", "warm_starts_rejected", "cg_restarts", "direct_fallbacks",
        "direct_solves_held", "unconverged_solves", "max_relative_residual"})
    EXPECT_TRUE(counters.contains(key)) << key;
  EXPECT_EQ(counters["solves"].get<double>(), 1500.0);
}

}  // namespace
}  // namespace tacta::simtest
