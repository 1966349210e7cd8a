// Shared helpers for the hyperelastic tests: models built straight from the core library on a
// test mesh, the material of each law from (E, nu), and a dense copy of the block matrix.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "hyperelastic_model.hpp"
#include "tacta/models/test_meshes.hpp"

namespace tacta::models::hyperelastic::testing {

inline std::vector<MaterialLaw> all_laws() {
  return {MaterialLaw::kNeoHookean, MaterialLaw::kStVenantKirchhoff, MaterialLaw::kMooneyRivlin};
}
inline std::string law_name(MaterialLaw law) {
  return law == MaterialLaw::kNeoHookean ? "NeoHookean"
         : law == MaterialLaw::kStVenantKirchhoff ? "StVenantKirchhoff"
                                                  : "MooneyRivlin";
}

// Mooney-Rivlin gets C10 = 0.3 mu, C01 = 0.2 mu (small-strain shear modulus mu) and K from nu.
inline MaterialConstants material_for(MaterialLaw law, double youngs_modulus, double poisson) {
  MaterialConstants m;
  m.law = law;
  m.mu = youngs_modulus / (2.0 * (1.0 + poisson));
  m.lambda = youngs_modulus * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  m.c10 = 0.3 * m.mu;
  m.c01 = 0.2 * m.mu;
  m.bulk = m.lambda + 2.0 * m.mu / 3.0;
  return m;
}

inline std::unique_ptr<HyperelasticModel> make_model(const TestMesh& mesh, MaterialLaw law,
                                                     double youngs_modulus, double poisson,
                                                     bool project, Options options = {}) {
  options.material = material_for(law, youngs_modulus, poisson);
  options.project_tangent = project;
  const tacta_material material = make_material(youngs_modulus, poisson, 1000.0);
  return std::make_unique<HyperelasticModel>(mesh.view(), material, mesh.masses, mesh.fixed,
                                             options);
}

inline Eigen::MatrixXd dense(const sparse::BlockSparseMatrix& a) {
  const size_t n = 3 * static_cast<size_t>(a.node_count());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  const auto starts = a.row_starts();
  const auto columns = a.columns();
  for (uint32_t i = 0; i < a.node_count(); ++i)
    for (uint32_t k = starts[i]; k < starts[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          m(3 * i + r, 3 * columns[k] + c) = a.block(k)[3 * r + c];
          m(3 * columns[k] + c, 3 * i + r) = a.block(k)[3 * r + c];
        }
  return m;
}

}  // namespace tacta::models::hyperelastic::testing
