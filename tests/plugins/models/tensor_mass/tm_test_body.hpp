// A test mesh with its material and a tensor-mass model built on it.
#pragma once

#include "tacta/models/test_meshes.hpp"
#include "tensor_mass_model.hpp"

namespace tacta::models::testing {

using TmBody = ModelOnMesh<TensorMassModel, TensorMassOptions>;

}  // namespace tacta::models::testing
