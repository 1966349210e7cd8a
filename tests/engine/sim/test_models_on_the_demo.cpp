// Every model on the default demo (the liver palpation) with its default parameters, as
// `tacta compare` and a swap in tacta-view put it there: none may fault at the scene's 1 ms
// tick. tensor_mass's central differences froze the liver at 7 ms before its integrator became
// `auto` (implicit Euler where central differences are unstable at dt).
#include <gtest/gtest.h>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

TEST(ModelsOnTheDemo, EveryModelRunsTheLiverWithoutAFault) {
  for (const char* model :
       {"corotational_fem", "tensor_mass", "mass_spring", "fd_debunne", "bullet_softbody"}) {
    if (!plugins().find(TACTA_KIND_MODEL, model))
      continue;  // bullet_softbody is optional in a build
    SCOPED_TRACE(model);
    const SceneDesc scene =
        load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml", schemas(),
                   {std::string("bodies.*.model=") + model, "output.plots=[]"});
    RunOptions options;
    options.duration_s = 0.6;  // the stylus reaches the liver at about 0.4 s
    const RunResult r = run_scene(scene, options);
    EXPECT_EQ(r.faults, 0u);
    EXPECT_EQ(r.exit_code, 0);
    ASSERT_EQ(r.bodies.size(), 1u);
    EXPECT_FALSE(r.bodies[0].frozen) << r.bodies[0].fault;
    EXPECT_GT(r.bodies[0].max_displacement_m, 0.0);
  }
}

// A swap in the middle of the run (what tacta-view does) builds the incoming model for the
// scene's dt, so tensor_mass's auto integrator is chosen there too.
TEST(ModelsOnTheDemo, SwappingTensorMassInKeepsTheLiverRunning) {
  const SceneDesc scene =
      load_scene(std::string(TACTA_SOURCE_DIR) + "/scenes/liver_palpation.yaml", schemas(),
                 {"swaps=[{time: 0.3, body: liver, model: tensor_mass}]", "output.plots=[]"});
  RunOptions options;
  options.duration_s = 0.6;
  const RunResult r = run_scene(scene, options);
  EXPECT_EQ(r.faults, 0u);
  EXPECT_EQ(r.bodies[0].model, "tensor_mass");
  EXPECT_FALSE(r.bodies[0].frozen) << r.bodies[0].fault;
}

}  // namespace
}  // namespace tacta::simtest
