// A test mesh with its material and a mass-spring model built on it.
#pragma once

#include <memory>

#include "mass_spring_model.hpp"
#include "tacta/models/test_meshes.hpp"

namespace tacta::models::testing {

struct MsBody {
  TestMesh mesh;
  tacta_mesh_view view;
  tacta_material material;
  std::unique_ptr<MassSpringModel> model;

  MsBody(TestMesh m, const tacta_material& mat, const MassSpringOptions& options = {}, double dt = 1e-3)
      : mesh(std::move(m)), view(mesh.view()), material(mat) {
    tacta_model_setup setup{};
    setup.struct_size = sizeof setup;
    setup.mesh = &view;
    setup.material = &material;
    setup.masses = mesh.masses.data();
    setup.fixed = mesh.fixed.data();
    setup.dt = dt;
    model = std::make_unique<MassSpringModel>(setup, options);
  }
};

inline MassSpringOptions with_integrator(MassSpringOptions::Integrator integrator) {
  MassSpringOptions o;
  o.integrator = integrator;
  return o;
}

}  // namespace tacta::models::testing
