// A test mesh with its material and a model built on it (fd_debunne tests).
#pragma once

#include <memory>

#include "fd_debunne_model.hpp"
#include "tacta/models/test_meshes.hpp"

namespace tacta::models::testing {

struct FdBody {
  TestMesh mesh;
  tacta_mesh_view view;
  tacta_material material;
  std::unique_ptr<FdDebunneModel> model;

  FdBody(TestMesh m, const tacta_material& mat, const FdDebunneOptions& options)
      : mesh(std::move(m)), view(mesh.view()), material(mat) {
    tacta_model_setup setup{};
    setup.struct_size = sizeof setup;
    setup.mesh = &view;
    setup.material = &material;
    setup.masses = mesh.masses.data();
    setup.fixed = mesh.fixed.data();
    setup.dt = 1e-3;
    model = std::make_unique<FdDebunneModel>(setup, options);
  }
};

}  // namespace tacta::models::testing
