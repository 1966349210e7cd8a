// Topology-edit check: a model claiming TACTA_MODEL_CLAIM_TOPOLOGY_EDITS is rebuilt on a cut cube
// the way the engine rebuilds it (create() on the new mesh, begin() with the carried positions and
// velocities) and must then push nothing at the new rest shape, stay finite, and gain no energy
// with no load. One separation and one removal, each cut into the cube as a load has left it.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "conformance/checks.hpp"
#include "conformance/test_body.hpp"
#include "topology/cut_mesh.hpp"

namespace tacta::conformance {

namespace {

constexpr int kLoadedSteps = 20;  // under gravity and a corner pull, before the cut
// After the cut, no load: about 2.5 periods of the cube's lowest mode (near 25 Hz: a 10 m/s
// wave speed over 0.1 m), so a model that leaks energy in at any phase shows it.
constexpr int kFreeSteps = 100;
// How much the kinetic + elastic energy may rise above its value at the cut, as a fraction of
// it. Every claiming in-tree model dissipates at the tick (implicit Euler loses energy each step)
// or conserves a nearby shadow energy (central differences, symplectic Euler), whose measured
// energy, with the velocity half a step off the positions, swings by O((omega dt)^2): about 4 %
// for the cube's stiffest mode at 1 ms. A stale history (a previous position from the old mesh, a
// warm start of the wrong size) injects a step's worth of strain, tens of percent or more.
constexpr double kEnergyGrowth = 0.1;

// A blade quad (p0, p1, p2), (p0, p2, p3): 18 doubles, m.
std::vector<double> quad(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  std::vector<double> blade;
  for (const Vec3* p : {&p0, &p1, &p2, &p0, &p2, &p3})
    blade.insert(blade.end(), {(*p)[0], (*p)[1], (*p)[2]});
  return blade;
}

struct Cut {
  const char* what;
  CutMode mode;
  std::vector<double> blade;
};

// The cube spans [0, 0.1] m on each axis, cells of 0.05 m; the blades stay clear of its nodes.
std::vector<Cut> cuts() {
  return {
      // Upright through the whole cube at x = 0.055: two halves, each still clamped at z = 0.
      {"separation at x = 0.055 m", CutMode::kSeparate,
       quad({0.055, -0.05, -0.05}, {0.055, 0.15, -0.05}, {0.055, 0.15, 0.15},
            {0.055, -0.05, 0.15})},
      // A level notch at z = 0.075 from the x = 0 face to x = 0.045: the top cells there go,
      // with the nodes of the top edge that no other tet holds.
      {"removal at z = 0.075 m, x < 0.045 m", CutMode::kRemove,
       quad({-0.05, -0.05, 0.075}, {0.045, -0.05, 0.075}, {0.045, 0.15, 0.075},
            {-0.05, 0.15, 0.075})},
  };
}

// The clamped cube after kLoadedSteps under gravity and a pull on its free top corner.
NodeState loaded_state(ModelInstance& model, const TestBody& body) {
  NodeState s(body.mesh.positions);
  const size_t corner = 3 * (body.mesh.node_count() - 1);
  model.begin(s.view(), body.dt);
  for (int k = 0; k < kLoadedSteps; ++k) {
    for (size_t i = 2; i < s.f.size(); i += 3) s.f[i] = -9.81 * body.masses[i / 3];
    s.f[corner] = 0.02 * body.force_scale();
    tacta_body_state view = s.view(k * body.dt);
    model.step(view, body.dt);
  }
  return s;
}

bool finite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}

// Kinetic (lumped masses) plus elastic energy, J.
double energy(ModelInstance& model, const TestBody& body, const NodeState& s) {
  double kinetic = 0;
  for (size_t i = 0; i < s.v.size(); ++i) kinetic += 0.5 * body.masses[i / 3] * s.v[i] * s.v[i];
  return kinetic + model.elastic_energy(s.x.data());
}

// One cut of the loaded cube. Appends its figures to `text`; false when the model fails it.
bool after_cut(const tacta_descriptor& model, const TestBody& body, const NodeState& loaded,
               const Cut& cut, std::string& text) {
  text += std::string(text.empty() ? "" : "; ") + cut.what + ": ";
  const CutResult result = cut_mesh(body.mesh, {}, loaded.x, cut.blade, cut.mode);
  if (!result.refused.empty() || !result.edit.changed()) {
    text += "the blade did not cut the test cube" +
            (result.refused.empty() ? std::string() : " (" + result.refused + ")");
    return false;
  }
  const TopologyEdit& edit = result.edit;
  const auto edited = edited_test_body(body, edit.mesh, edit.node_source);
  text += std::to_string(edited->mesh.tet_count()) + " tets, " +
          std::to_string(edited->mesh.node_count()) + " nodes";

  // At rest on the new mesh: a fresh instance, measured as the force-at-rest check does.
  std::string how;
  const auto probe = create_model(model, *edited);
  const double rest_force =
      largest_node_force(elastic_forces(*probe, *edited, edited->mesh.positions, how));
  const double force_limit = kForceRoundOff * edited->force_scale();
  text += ", max |f| at rest " + figure(rest_force) + " N (limit " + figure(force_limit) + " N)";
  if (!(rest_force <= force_limit)) return false;

  // The engine's rebuild: the old nodes' positions and velocities, begin(), no load.
  const auto rebuilt = create_model(model, *edited);
  NodeState s(edited->mesh.positions);
  for (size_t n = 0; n < edit.node_source.size(); ++n)
    for (size_t a = 0; a < 3; ++a) {
      s.x[3 * n + a] = loaded.x[3 * size_t{edit.node_source[n]} + a];
      s.v[3 * n + a] = loaded.v[3 * size_t{edit.node_source[n]} + a];
    }
  rebuilt->begin(s.view(), body.dt);
  const double at_cut = energy(*rebuilt, *edited, s);
  double most = at_cut;
  for (int k = 0; k < kFreeSteps; ++k) {
    tacta_body_state view = s.view(k * body.dt);
    const uint32_t bits = rebuilt->step(view, body.dt);
    if ((bits & TACTA_STEP_FAULT_MASK) || !finite(s.x) || !finite(s.v)) {
      text += ", step " + std::to_string(k + 1) + " after the cut " +
              (bits & TACTA_STEP_FAULT_MASK ? "returned fault bits" : "left a non-finite state");
      return false;
    }
    most = std::max(most, energy(*rebuilt, *edited, s));
  }
  const double growth = at_cut > 0 ? (most - at_cut) / at_cut : 0.0;
  text += ", energy " + figure(at_cut) + " J at the cut, at most " + figure(most) + " J over " +
          std::to_string(kFreeSteps) + " free steps (+" + figure(100.0 * growth) + " %, limit " +
          figure(100.0 * kEnergyGrowth) + " %)";
  return growth <= kEnergyGrowth;
}

}  // namespace

CheckResult check_topology_edits(const tacta_descriptor& model) {
  const char* name = "topology edits";
  if (!(claims_of(model) & TACTA_MODEL_CLAIM_TOPOLOGY_EDITS))
    return {name, "not claimed (TACTA_MODEL_CLAIM_TOPOLOGY_EDITS unset)", Verdict::Skip};
  if (!static_cast<const tacta_model_api*>(model.api)->elastic_energy)
    return {name, "claimed, but the model has no elastic_energy entry to weigh the energy with",
            Verdict::Fail};
  const auto body = make_test_body(model, true);
  const auto original = create_model(model, *body);
  const NodeState loaded = loaded_state(*original, *body);
  std::string text;
  bool pass = true;
  for (const Cut& cut : cuts()) pass = after_cut(model, *body, loaded, cut, text) && pass;
  return {name, text, pass ? Verdict::Pass : Verdict::Fail};
}

}  // namespace tacta::conformance
