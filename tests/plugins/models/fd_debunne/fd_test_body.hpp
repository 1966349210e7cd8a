// A test mesh with its material and a model built on it (fd_debunne tests).
#pragma once

#include "fd_debunne_model.hpp"
#include "tacta/models/test_meshes.hpp"

namespace tacta::models::testing {

using FdBody = ModelOnMesh<FdDebunneModel, FdDebunneOptions>;

}  // namespace tacta::models::testing
