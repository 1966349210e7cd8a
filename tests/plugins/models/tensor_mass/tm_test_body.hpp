// A test mesh with its material and a tensor-mass model built on it.
#pragma once

#include <memory>

#include "tacta/models/test_meshes.hpp"
#include "tensor_mass_model.hpp"

namespace tacta::models::testing {

struct TmBody {
  TestMesh mesh;
  tacta_mesh_view view;
  tacta_material material;
  std::unique_ptr<TensorMassModel> model;

  TmBody(TestMesh m, const tacta_material& mat, const TensorMassOptions& options = {}, double dt = 1e-3)
      : mesh(std::move(m)), view(mesh.view()), material(mat) {
    tacta_model_setup setup{};
    setup.struct_size = sizeof setup;
    setup.mesh = &view;
    setup.material = &material;
    setup.masses = mesh.masses.data();
    setup.fixed = mesh.fixed.data();
    setup.dt = dt;
    model = std::make_unique<TensorMassModel>(setup, options);
  }
};

}  // namespace tacta::models::testing
