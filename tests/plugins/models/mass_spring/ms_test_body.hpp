// A test mesh with its material and a mass-spring model built on it.
#pragma once

#include "mass_spring_model.hpp"
#include "tacta/models/test_meshes.hpp"

namespace tacta::models::testing {

using MsBody = ModelOnMesh<MassSpringModel, MassSpringOptions>;

inline MassSpringOptions with_integrator(MassSpringOptions::Integrator integrator) {
  MassSpringOptions o;
  o.integrator = integrator;
  return o;
}

}  // namespace tacta::models::testing
