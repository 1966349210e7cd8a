// The 1 kHz path allocates nothing: malloc and friends are interposed in this executable and
// counted while the models step. (glibc only; skipped under AddressSanitizer, which owns malloc.)
#include <cstddef>
#include <gtest/gtest.h>
#include <memory>

#include "allocation_counter.hpp"
#include "fd_debunne_model.hpp"
#include "hyperelastic_model.hpp"
#include "mass_spring_model.hpp"
#include "tacta/models/model_checks.hpp"
#include "tacta/models/test_meshes.hpp"
#include "tensor_mass_model.hpp"
#include "vbd_model.hpp"

using namespace tacta::models;

namespace {

// Builds the model, steps once outside the count (first-touch paths), then counts 20 steps.
template <class Model, class Options>
long allocations_in_steps(const Options& options, bool with_begin) {
  TestMesh mesh = box_tet_mesh({3, 2, 2}, {0.3, 0.2, 0.2}, 1000.0);
  mesh.fix_plane(0, 0.0);
  const tacta_mesh_view view = mesh.view();
  const tacta_material material = make_material(1e5, 0.3, 1000.0);
  tacta_model_setup setup = mesh.setup(view, material, nullptr, 0, 1e-4);
  Model model(setup, options);
  checks::StateBuffers s(mesh.positions);
  for (size_t i = 2; i < s.f_ext.size(); i += 3) s.f_ext[i] = -9.81 * mesh.masses[i / 3];
  tacta_body_state st = s.state();
  if constexpr (requires { model.begin(st, 1e-4); }) {
    if (with_begin) model.begin(st, 1e-4);
  }
  model.step(st, 1e-4);
  std::vector<double> forces(s.x.size());
  g_allocations = 0;
  g_counting = true;
  for (int k = 0; k < 20; ++k) {
    st = s.state();
    model.step(st, 1e-4);
  }
  model.internal_forces(s.x.data(), forces.data());
  g_counting = false;
  return g_allocations;
}

// The hyperelastic core built the way allocations_in_steps builds the others, its moduli from
// the setup's material.
struct Hyperelastic {
  Hyperelastic(const tacta_model_setup& setup, tacta::models::hyperelastic::Options options)
      : model(*setup.mesh, *setup.material,
              std::span<const double>(setup.masses, setup.mesh->node_count),
              std::span<const uint8_t>(setup.fixed, setup.mesh->node_count),
              with_moduli(options, *setup.material)) {}
  static tacta::models::hyperelastic::Options with_moduli(tacta::models::hyperelastic::Options o,
                                                          const tacta_material& m) {
    o.material.mu = m.lame_mu;
    o.material.lambda = m.lame_lambda;
    o.material.c10 = 0.5 * m.lame_mu;
    o.material.bulk = m.lame_lambda + 2.0 * m.lame_mu / 3.0;
    return o;
  }
  uint32_t step(tacta_body_state& state, double dt) noexcept { return model.step(state, dt); }
  void begin(const tacta_body_state& state, double dt) noexcept { model.begin(state, dt); }
  void internal_forces(const double* x, double* f) noexcept { model.internal_forces(x, f); }
  tacta::models::hyperelastic::HyperelasticModel model;
};

// The vbd core built the way allocations_in_steps builds the others (serial: no host).
struct Vbd {
  Vbd(const tacta_model_setup& setup, const tacta::models::vbd::Options& options)
      : model(*setup.mesh, *setup.material,
              std::span<const double>(setup.masses, setup.mesh->node_count),
              std::span<const uint8_t>(setup.fixed, setup.mesh->node_count), options) {}
  uint32_t step(tacta_body_state& state, double dt) noexcept { return model.step(state, dt); }
  void begin(const tacta_body_state& state, double dt) noexcept { model.begin(state, dt); }
  void internal_forces(const double* x, double* f) noexcept { model.internal_forces(x, f); }
  tacta::models::vbd::VbdModel model;
};

}  // namespace

TEST(ModelsNoAllocation, VbdStepsWithoutAllocating) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "malloc belongs to the sanitizer here";
  using tacta::models::vbd::Energy;
  for (const Energy energy : {Energy::kCorotational, Energy::kNeoHookean}) {
    tacta::models::vbd::Options o;
    o.energy = energy;
    EXPECT_EQ((allocations_in_steps<Vbd>(o, true)), 0) << "vbd " << static_cast<int>(energy);
  }
}

TEST(ModelsNoAllocation, HyperelasticStepsWithoutAllocating) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "malloc belongs to the sanitizer here";
  using tacta::models::hyperelastic::MaterialLaw;
  using tacta::models::hyperelastic::SolveMode;
  using tacta::models::hyperelastic::Volumetric;
  for (const MaterialLaw law :
       {MaterialLaw::kNeoHookean, MaterialLaw::kStVenantKirchhoff, MaterialLaw::kMooneyRivlin})
    for (const Volumetric volumetric : {Volumetric::kElement, Volumetric::kNodalAverage})
      for (const SolveMode mode : {SolveMode::kDynamic, SolveMode::kStatic})
        for (const auto solver : {tacta::models::sparse::LinearSolver::kConjugateGradient,
                                  tacta::models::sparse::LinearSolver::kCholesky}) {
          tacta::models::hyperelastic::Options o;
          if (volumetric == Volumetric::kNodalAverage && law == MaterialLaw::kStVenantKirchhoff)
            continue;  // not offered (nodal_volume.hpp)
          o.material.law = law;
          o.volumetric = volumetric;
          o.mode = mode;
          o.solver.solver = solver;
          EXPECT_EQ((allocations_in_steps<Hyperelastic>(o, true)), 0)
              << "hyperelastic " << static_cast<int>(law) << " " << static_cast<int>(volumetric)
              << " " << static_cast<int>(mode) << " " << static_cast<int>(solver);
        }
}

TEST(ModelsNoAllocation, EveryIntegratorStepsWithoutAllocating) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "malloc belongs to the sanitizer here";
  // The counter itself works: a vector allocates.
  g_counting = true;
  auto probe = std::make_unique<std::vector<double>>(100);
  g_counting = false;
  ASSERT_GT(g_allocations, 0);

  for (auto integrator : {FdDebunneOptions::Integrator::kSymplecticEuler,
                          FdDebunneOptions::Integrator::kExplicitEuler}) {
    FdDebunneOptions o;
    o.integrator = integrator;
    EXPECT_EQ((allocations_in_steps<FdDebunneModel>(o, false)), 0)
        << "fd_debunne " << static_cast<int>(integrator);
  }
  for (auto integrator : {TensorMassOptions::Integrator::kCentralDifference,
                          TensorMassOptions::Integrator::kImplicitEuler}) {
    TensorMassOptions o;
    o.integrator = integrator;
    EXPECT_EQ((allocations_in_steps<TensorMassModel>(o, true)), 0)
        << "tensor_mass " << static_cast<int>(integrator);
  }
  for (auto integrator :
       {MassSpringOptions::Integrator::kSymplecticEuler,
        MassSpringOptions::Integrator::kImplicitEuler, MassSpringOptions::Integrator::kDesbrun}) {
    MassSpringOptions o;
    o.integrator = integrator;
    EXPECT_EQ((allocations_in_steps<MassSpringModel>(o, false)), 0)
        << "mass_spring " << static_cast<int>(integrator);
  }
}
