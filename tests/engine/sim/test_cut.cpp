// Cutting through whole simulations (Simulation::cut, scene cut events): the mass a cut keeps or
// removes, a cantilever cut at its root falling freely, every model that claims topology edits
// stepping on after a cut, the refusals, the demo's liver cut in contact, and the outputs that
// follow the new mesh (report.json, VTK, snapshots).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <numeric>
#include <vector>

#include "cut_beam_scene.hpp"
#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

double total_mass(Simulation& sim, BodyHandle body) {
  const BodyArrays a = sim.body_arrays(body);
  return std::accumulate(a.masses, a.masses + a.nodes, 0.0);
}

TEST(Cut, SeparationKeepsTheMassAndRemovalLosesTheRemovedTets) {
  Simulation sim(scene_from_text(beam_scene("corotational_fem"), "cut_beam"), plugins());
  const BodyHandle beam = sim.body("beam");
  const double mass = total_mass(sim, beam);
  const double density = 1000, cell_volume = 0.01 * 0.01 * 0.01;
  ASSERT_NEAR(mass, density * 0.1 * 0.02 * 0.02, 1e-12 * mass);

  const BodyArrays before = sim.body_arrays(beam);
  const std::vector<double> positions_before(before.positions, before.positions + 3 * before.nodes);
  const CutSummary split = sim.cut(beam, plane_x(0.05), CutMode::kSeparate);
  // Arrays handed out before the cut stay readable, holding the state at the cut.
  EXPECT_TRUE(std::equal(positions_before.begin(), positions_before.end(), before.positions));
  EXPECT_NE(sim.body_arrays(beam).positions, before.positions);
  EXPECT_TRUE(split.changed);
  EXPECT_EQ(split.revision, 1u);
  EXPECT_EQ(split.faces_separated, 2u * 2 * 2);  // two triangles per cell face, 2 x 2 cells
  EXPECT_EQ(split.nodes_added, 3u * 3);          // the 3 x 3 nodes of the plane, copied once
  EXPECT_NEAR(total_mass(sim, beam), mass, 1e-12 * mass);

  // A plane through the middle of the cells at x = 0.025 takes the 2 x 2 cells it passes through.
  const CutSummary carve = sim.cut(beam, plane_x(0.025), CutMode::kRemove);
  EXPECT_EQ(carve.tets_removed, 2u * 2 * 6);
  EXPECT_EQ(carve.revision, 2u);
  EXPECT_NEAR(total_mass(sim, beam), mass - 4 * density * cell_volume, 1e-12 * mass);
  EXPECT_EQ(sim.body_revision(beam), 2u);

  // A blade that misses the body changes nothing.
  const CutSummary miss = sim.cut(beam, plane_x(0.5), CutMode::kRemove);
  EXPECT_FALSE(miss.changed);
  EXPECT_EQ(miss.revision, 2u);
}

// Probes follow their tets through cuts: one in a tet a separation keeps stays at its material
// point; one whose tet a removal takes is bound to the nearest remaining tet at its rest point
// (extrapolated weights), so at rest it still reads its rest position.
TEST(Cut, ProbesFollowTheirTetsThroughCuts) {
  const std::string probes = R"(
    probes: [{name: kept, position: [0.073, 0.007, 0.013]}, {name: carved, position: [0.025, 0.01, 0.01]}]
)";
  Simulation sim(scene_from_text(beam_scene("corotational_fem") + probes, "cut_beam"), plugins());
  const BodyHandle beam = sim.body("beam");
  sim.cut(beam, plane_x(0.07), CutMode::kSeparate);
  sim.cut(beam, plane_x(0.025), CutMode::kRemove);
  const std::string out = fresh_dir("cut_probes");
  sim.write_report(out);
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  for (const nlohmann::json& probe : report["bodies"][0]["probes"]) {
    SCOPED_TRACE(probe["name"].get<std::string>());
    for (int a = 0; a < 3; ++a)  // nothing moved yet: every probe reads its rest point
      EXPECT_NEAR(probe["position"][a].get<double>(), probe["rest"][a].get<double>(), 1e-12);
  }
  sim.advance_to(0.05);  // and they follow the body as it sags
  const RunResult r = sim.report();
  EXPECT_EQ(r.faults, 0u);
}

// The piece cut off at the clamp is free: no internal force moves its centre of mass, so it falls
// by g t^2 / 2 (1 % is the issue's bound; the discrete fall of an implicit Euler step differs
// from g t^2 / 2 by g t dt / 2, 0.5 % at t = 0.2 s with dt = 1 ms).
TEST(Cut, CantileverCutAtItsRootFallsFreely) {
  Simulation sim(scene_from_text(beam_scene("corotational_fem"), "cut_beam"), plugins());
  const BodyHandle beam = sim.body("beam");
  sim.cut(beam, plane_x(0.01), CutMode::kSeparate);
  // The free piece: the nodes joined through tets to the tip (the clamp's piece shares none).
  const Pieces pieces(sim.body_mesh(beam));
  ASSERT_TRUE(pieces.in_two()) << "the cut left the beam in one piece";
  auto free_centre_z = [&] {
    const BodyArrays a = sim.body_arrays(beam);
    double m = 0, mz = 0;
    for (uint32_t n = 0; n < a.nodes; ++n)
      if (pieces.piece[n] == pieces.piece[pieces.tip]) {
        m += a.masses[n];
        mz += a.masses[n] * a.positions[3 * n + 2];
      }
    return mz / m;
  };
  const double z0 = free_centre_z();
  sim.advance_to(0.2);
  const double fall = z0 - free_centre_z();
  EXPECT_NEAR(fall, 0.5 * 9.81 * 0.2 * 0.2, 0.01 * 0.5 * 9.81 * 0.2 * 0.2);
  EXPECT_EQ(sim.report().faults, 0u);
}

// Every model that claims TACTA_MODEL_CLAIM_TOPOLOGY_EDITS steps on after a cut made while the
// beam swings; the others are refused with the reason.
TEST(Cut, EveryClaimingModelStepsOnAfterACut) {
  for (const char* model :
       {"corotational_fem", "hyperelastic", "tensor_mass", "mass_spring", "vbd"}) {
    if (plugins().find(TACTA_KIND_MODEL, model) == nullptr) continue;
    SCOPED_TRACE(model);
    Simulation sim(scene_from_text(beam_scene(model), "cut_beam"), plugins());
    const BodyHandle beam = sim.body("beam");
    sim.advance_to(0.05);
    EXPECT_TRUE(sim.cut(beam, plane_x(0.055), CutMode::kSeparate).changed);
    EXPECT_TRUE(sim.cut(beam, plane_x(0.025), CutMode::kRemove).changed);
    sim.advance_to(0.15);
    const RunResult r = sim.report();
    EXPECT_EQ(r.faults, 0u);
    const BodyArrays a = sim.body_arrays(beam);
    for (size_t k = 0; k < 3 * a.nodes; ++k) ASSERT_TRUE(std::isfinite(a.positions[k]));
  }
  for (const char* model : {"fd_debunne", "bullet_softbody"}) {
    if (plugins().find(TACTA_KIND_MODEL, model) == nullptr) continue;
    Simulation sim(scene_from_text(beam_scene(model), "cut_beam"), plugins());
    try {
      sim.cut(sim.body("beam"), plane_x(0.05), CutMode::kSeparate);
      ADD_FAILURE() << model << " was cut";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("does not take topology edits"), std::string::npos)
          << e.what();
    }
  }
}

// A separation through nodes the scene moves: each copy is moved as its node was. The cell face
// x = 0.05 (y held, x and z sliding) is split by the cut; the lifted tip face is not.
TEST(Cut, PrescribedAndSlidingNodesKeepTheirMotionThroughACut) {
  Simulation sim(scene_from_text(beam_scene("corotational_fem", kPrescribedBeam), "cut_beam"),
                 plugins());
  const BodyHandle beam = sim.body("beam");
  sim.advance_to(0.05);
  const size_t nodes_before = sim.body_arrays(beam).nodes;
  ASSERT_EQ(sim.cut(beam, plane_x(0.05), CutMode::kSeparate).nodes_added, 9u);
  sim.advance_to(0.15);
  EXPECT_EQ(sim.report().faults, 0u);
  const BodyArrays a = sim.body_arrays(beam);
  const std::vector<double>& rest = sim.body_mesh(beam).positions;
  ASSERT_EQ(a.nodes, nodes_before + 9);
  size_t sliding = 0, tip = 0;
  double slid = 0;  // the sliding nodes' largest motion along x and z, m
  for (size_t n = 0; n < a.nodes; ++n) {
    if (std::abs(rest[3 * n] - 0.05) < 1e-9) {
      ++sliding;
      EXPECT_NEAR(a.positions[3 * n + 1], rest[3 * n + 1], 1e-12) << "node " << n;
      slid = std::max({slid, std::abs(a.positions[3 * n] - rest[3 * n]),
                       std::abs(a.positions[3 * n + 2] - rest[3 * n + 2])});
    }
    if (std::abs(rest[3 * n] - 0.1) < 1e-9) {
      ++tip;
      const double lift = 0.005 * sim.time() / 0.2;  // the ramp at this time, m
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(a.positions[3 * n + k], rest[3 * n + k] + (k == 2 ? lift : 0.0), 1e-12)
            << "node " << n << " axis " << k;
    }
  }
  EXPECT_EQ(sliding, 18u) << "the face's 9 nodes and their 9 copies";
  EXPECT_EQ(tip, 9u);
  EXPECT_GT(slid, 1e-5) << "the sliding nodes move on their free axes";
}

TEST(Cut, RefusesWhatItCannotDo) {
  Simulation sim(scene_from_text(beam_scene("corotational_fem"), "cut_beam"), plugins());
  const BodyHandle beam = sim.body("beam");
  const std::vector<double> eight(8, 0.0);
  EXPECT_THROW(sim.cut(beam, eight, CutMode::kRemove), InputError);
  // Two planes along the beam through both rows of cells pass through every tet (each of a cell's
  // six tets spans its diagonal): the removal would leave nothing, so it is refused.
  std::vector<double> along;
  for (double y : {0.005, 0.015})
    along.insert(along.end(), {-1, y, -1, 1, y, -1, 1, y, 1, -1, y, -1, 1, y, 1, -1, y, 1});
  EXPECT_THROW(sim.cut(beam, along, CutMode::kRemove), InputError);
  EXPECT_EQ(sim.body_revision(beam), 0u);
}

// A scene's cut event runs between lockstep ticks: report.json counts it, VTK writes the new mesh.
TEST(Cut, SceneEventCutsTheBeamAndTheOutputsFollow) {
  const std::string events = R"(
events:
  - {time: 0.05, cut: {body: beam, mode: separate, quad: [[0.05, -1, -1], [0.05, 1, -1], [0.05, 1, 1], [0.05, -1, 1]]}}
)";
  SceneDesc scene = scene_from_text(beam_scene("corotational_fem", events), "cut_beam");
  scene.output.vtk = true;
  const std::string out = fresh_dir("cut_event");
  Simulation sim(scene, plugins());
  RunOptions options;
  options.out_dir = out;
  options.duration_s = 0.1;
  sim.run(options);
  EXPECT_EQ(sim.body_revision(sim.body("beam")), 1u);
  std::ifstream in(out + "/report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const nlohmann::json& cuts = report["bodies"][0]["cuts"];
  EXPECT_EQ(cuts["revision"], 1);
  EXPECT_EQ(cuts["nodes_added"], 9);
  EXPECT_EQ(sim.scene_static().bodies[0].revision, 1u);
  EXPECT_EQ(sim.scene_static().bodies[0].rest_positions.size() / 3,
            sim.body_arrays(sim.body("beam")).nodes);
  // The last VTK frame has the cut mesh's nodes.
  std::vector<std::filesystem::path> frames;
  for (const auto& f : std::filesystem::directory_iterator(out + "/vtk"))
    if (f.path().extension() == ".vtu") frames.push_back(f.path());
  ASSERT_FALSE(frames.empty());
  std::sort(frames.begin(), frames.end());
  std::ifstream last(frames.back());
  const std::string text((std::istreambuf_iterator<char>(last)), std::istreambuf_iterator<char>());
  const size_t nodes = sim.body_arrays(sim.body("beam")).nodes;
  EXPECT_NE(text.find("NumberOfPoints=\"" + std::to_string(nodes) + "\""), std::string::npos);
}

}  // namespace
}  // namespace tacta::simtest

namespace tacta::simtest {
namespace {

// The scalpel (cut_beam_scene.hpp) parts the beam at x = 0.05.
TEST(Cut, ABladeHeldByADeviceCutsTheBeamInTwoAndRunsRepeatably) {
  const std::string device = kScalpelDevice;
  auto run = [&](const std::string& out) {
    Simulation sim(scene_from_text(beam_scene("corotational_fem", device), "cut_beam"), plugins());
    RunOptions options;
    options.out_dir = out;
    options.duration_s = 0.25;
    const RunResult r = sim.run(options);
    EXPECT_EQ(r.faults, 0u);
    EXPECT_GT(sim.body_revision(sim.body("beam")), 0u);
    // In two: no tet joins a node of the clamped end to one of the tip.
    EXPECT_TRUE(Pieces(sim.body_mesh(sim.body("beam"))).in_two());
    std::ifstream in(out + "/report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_GT(report["devices"][0]["blade"]["cuts"].get<int>(), 0);
    EXPECT_EQ(report["devices"][0]["blade"]["cuts_refused"], 0);
    return r.state_hash;
  };
  EXPECT_EQ(run(fresh_dir("blade_a")), run(fresh_dir("blade_b")));
  // The same blade in a realtime run: test_realtime_cuts.cpp.
}

}  // namespace
}  // namespace tacta::simtest
