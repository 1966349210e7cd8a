// The body every conformance check runs on: a 0.1 m cube of 2 x 2 x 2 cells (27 nodes, 48 tets,
// one interior node), soft-tissue-like material, the model's parameters at their defaults, and a
// model instance with its node state.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "plugin/plugin_instance.hpp"
#include "tacta/mesh.hpp"
#include "tacta/model_api.h"
#include "tacta/scene.hpp"

namespace tacta::conformance {

struct TestBody {
  VolumeMesh mesh;
  std::vector<double> masses;  // kg per node, lumped
  std::vector<uint8_t> fixed;  // 1 per node
  tacta_mesh_view view{};
  tacta_material material{};
  ParamSet params;            // the schema's defaults
  double dt = 1e-3;           // s, the haptic tick
  double cell = 0.05;         // m, edge of one grid cell
  uint32_t centre_node = 13;  // the interior node

  // A force figure: E h^2 (N), what a unit strain puts on a node; limits are fractions of it.
  double force_scale() const { return material.youngs_modulus * cell * cell; }
  tacta_model_setup setup() const;
};

// clamped: the nodes of the z = 0 face are held (a cantilever under gravity, for the step checks).
std::unique_ptr<TestBody> make_test_body(const tacta_descriptor& model, bool clamped);

// `body` on an edited mesh (a cut): the same material, parameters and dt, masses lumped from
// `mesh`, and each new node fixed when the old node it continues (node_source) was.
std::unique_ptr<TestBody> edited_test_body(const TestBody& body, VolumeMesh mesh,
                                           const std::vector<uint32_t>& node_source);

// A model instance for the body; throws InputError naming the test cube when create() refuses.
std::unique_ptr<ModelInstance> create_model(const tacta_descriptor& model, const TestBody& body);

// Node state for one instance: positions, velocities, external forces (all 3 per node).
struct NodeState {
  std::vector<double> x, v, f;
  explicit NodeState(const std::vector<double>& positions)
      : x(positions), v(positions.size(), 0.0), f(positions.size(), 0.0) {}
  tacta_body_state view(double time = 0.0) {
    return {static_cast<uint32_t>(x.size() / 3), x.data(), v.data(), f.data(), time};
  }
};

// Elastic forces at positions (3 per node, N): the model's internal_forces when it has one, else
// measured through one step from rest with no load, as m dx / dt^2. `how` names which was used.
std::vector<double> elastic_forces(ModelInstance& model, const TestBody& body,
                                   const std::vector<double>& positions, std::string& how);

// The largest per-node force magnitude in `forces` (3 per node), N.
double largest_node_force(const std::vector<double>& forces);

// "%.2g" of a number, for figures.
std::string figure(double value);

}  // namespace tacta::conformance
