// The vbd model's pieces and its stepping: the colouring, the corner forces and Hessian blocks
// against differences, forces against the energy, free fall, fixed nodes, recovery from an
// inverted start, the parallel path against the serial one (bit for bit), and a step that
// allocates nothing (malloc is interposed in this test binary to count).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

#include "allocation_counter.hpp"  // the shared malloc interposer; off under the sanitizers
#include "element_energy.hpp"
#include "tacta/models/model_checks.hpp"
#include "vbd_test_support.hpp"

namespace tacta::models::vbd {
namespace {

using testing::BodyState;
using testing::make_vbd;
using testing::PoolHost;

constexpr Energy kEnergies[] = {Energy::kCorotational, Energy::kNeoHookean};

Options with_energy(Energy energy) {
  Options o;
  o.energy = energy;
  return o;
}

// A 2x2x2-cell 0.1 m cube moved by a random field of up to `size` m per coordinate.
std::vector<double> jiggled(const TestMesh& mesh, double size, uint64_t seed) {
  checks::TestRandom random(seed);
  std::vector<double> x = mesh.positions;
  for (double& c : x) c += size * random.next();
  return x;
}

TEST(VbdColouring, NoTetHoldsTwoFreeVerticesOfOneColour) {
  TestMesh mesh = box_tet_mesh({4, 3, 5}, {0.4, 0.3, 0.5}, 1000.0);
  mesh.fix_plane(2, 0.0);
  auto model = make_vbd(mesh, make_material(1e5, 0.3, 1000.0));
  std::vector<int> colour_of(mesh.node_count(), -1);
  for (uint32_t c = 0; c < model->colour_count(); ++c)
    for (uint32_t i : model->colour(c)) {
      EXPECT_EQ(colour_of[i], -1) << "vertex " << i << " in two colours";
      colour_of[i] = static_cast<int>(c);
    }
  for (uint32_t i = 0; i < mesh.node_count(); ++i)
    EXPECT_EQ(colour_of[i] == -1, mesh.fixed[i] != 0) << "vertex " << i;
  for (size_t t = 0; t < mesh.tets.size(); t += 4)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const int ca = colour_of[mesh.tets[t + a]], cb = colour_of[mesh.tets[t + b]];
        if (ca >= 0) {
          EXPECT_NE(ca, cb) << "tet " << t / 4;
        }
      }
  std::printf("colours: %u\n", model->colour_count());
}

// A 1 m reference tet deformed by a random F near identity (positions of its 4 nodes).
struct OneTet {
  TetRest rest{};
  std::vector<double> x;
  explicit OneTet(double strain, uint64_t seed) {
    const double p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t tet[4] = {0, 1, 2, 3};
    rest = checked_tet_rest("test", p, 4, tet, 0);
    checks::TestRandom random(seed);
    x.assign(p, p + 12);
    for (double& c : x) c += strain * random.next();
  }
};

TEST(VbdElementEnergy, CornerForcesAndHessiansMatchDifferences) {
  const Lame lame = lame_from_young(1e5, 0.45);
  for (double strain : {0.05, 0.3}) {
    OneTet t(strain, 7);
    // A rotation that is not F's polar one: the corotational corner terms hold R fixed.
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    for (int corner = 0; corner < 4; ++corner) {
      const auto energy = [&](const std::vector<double>& x, Energy which) {
        const Eigen::Matrix3d f = tet_deformation(t.rest, x.data());
        return t.rest.volume * (which == Energy::kCorotational
                                    ? corotational_energy_density(f, r, lame)
                                    : neo_hookean_energy_density(f, lame, 0.1));
      };
      const auto corner_terms = [&](const std::vector<double>& x, Energy which,
                                    Eigen::Matrix3d* hessian) {
        const Eigen::Matrix3d f = tet_deformation(t.rest, x.data());
        const Eigen::Vector3d g = corner_gradient(t.rest, corner);
        const double volume = t.rest.volume;
        Eigen::Vector3d force;
        if (which == Energy::kCorotational) {
          force = corotational_corner_force(g, volume, r.transpose() * f, r, lame);
          if (hessian) *hessian = corotational_corner_hessian(g, volume, r, lame);
        } else {
          neo_hookean_corner(g, volume, f, lame, 0.1, force, hessian);
        }
        return force;
      };
      for (Energy which : kEnergies) {
        Eigen::Matrix3d hessian;
        const Eigen::Vector3d force = corner_terms(t.x, which, &hessian);
        const double step = 1e-6;
        for (int k = 0; k < 3; ++k) {
          std::vector<double> plus = t.x, minus = t.x;
          plus[3 * corner + k] += step;
          minus[3 * corner + k] -= step;
          const double grad = (energy(plus, which) - energy(minus, which)) / (2 * step);
          EXPECT_NEAR(force[k], -grad, 1e-5 * lame.mu) << "corner " << corner << " k " << k;
          const Eigen::Vector3d column =
              -(corner_terms(plus, which, nullptr) - corner_terms(minus, which, nullptr)) /
              (2 * step);
          for (int r2 = 0; r2 < 3; ++r2)
            EXPECT_NEAR(hessian(r2, k), column[r2], 1e-5 * (lame.lambda + lame.mu))
                << "energy " << static_cast<int>(which) << " strain " << strain;
        }
      }
    }
  }
}

TEST(VbdElementEnergy, VolumeTermContinuesSmoothlyBelowTheFloor) {
  const Lame lame = lame_from_young(1e5, 0.45);
  const double floor = 0.1, d = 1e-7;
  const VolumeTerm below = neo_hookean_volume_term(floor - d, lame, floor);
  const VolumeTerm above = neo_hookean_volume_term(floor + d, lame, floor);
  // Value and slope continue across the floor (first-order steps over 2d agree).
  EXPECT_NEAR(below.energy, above.energy - 2 * d * above.slope, 1e-9 * std::abs(above.energy));
  EXPECT_NEAR(below.slope, above.slope - 2 * d * above.curvature, 1e-9 * std::abs(above.slope));
  // Inverted (J < 0): finite, and the slope pushes J back up.
  const VolumeTerm inverted = neo_hookean_volume_term(-0.5, lame, floor);
  EXPECT_TRUE(std::isfinite(inverted.energy));
  EXPECT_LT(inverted.slope, 0.0);
}

TEST(VbdForces, InternalForcesAreMinusTheEnergyGradient) {
  TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  for (Energy energy : kEnergies) {
    auto model = make_vbd(mesh, make_material(1e5, 0.4, 1000.0), with_energy(energy));
    std::vector<double> x = jiggled(mesh, 0.005, 3), f(x.size());
    model->internal_forces(x.data(), f.data());
    double largest = 0.0;
    for (double v : f) largest = std::max(largest, std::abs(v));
    const double step = 1e-7;
    for (size_t k = 0; k < x.size(); ++k) {
      const double keep = x[k];
      x[k] = keep + step;
      const double plus = model->elastic_energy(x.data());
      x[k] = keep - step;
      const double minus = model->elastic_energy(x.data());
      x[k] = keep;
      EXPECT_NEAR(f[k], -(plus - minus) / (2 * step), 1e-5 * largest) << "dof " << k;
    }
  }
}

TEST(VbdDynamics, FreeBodyFallsAsImplicitEuler) {
  // No elastic force under a translation: implicit Euler gives v_n = n g h and
  // x_n = x_0 + g h^2 n (n + 1) / 2 exactly, whatever the iteration count.
  TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  for (Energy energy : kEnergies) {
    auto model = make_vbd(mesh, make_material(1e5, 0.3, 1000.0), with_energy(energy));
    BodyState body(mesh);
    body.add_gravity(mesh, {0.0, 0.0, -9.81});
    model->begin(body.state, 1e-3);
    const int steps = 100;
    for (int n = 0; n < steps; ++n) ASSERT_EQ(model->step(body.state, 1e-3), TACTA_STEP_OK);
    const double h = 1e-3, expected = -9.81 * h * h * steps * (steps + 1) / 2.0;
    for (uint32_t i = 0; i < mesh.node_count(); ++i) {
      EXPECT_NEAR(body.positions[3 * i + 2] - mesh.positions[3 * i + 2], expected, 1e-12);
      EXPECT_NEAR(body.velocities[3 * i + 2], -9.81 * h * steps, 1e-10);
      EXPECT_NEAR(body.positions[3 * i], mesh.positions[3 * i], 1e-12);
    }
  }
}

TEST(VbdDynamics, FixedNodesStayBitwiseWhereTheyAre) {
  TestMesh mesh = box_tet_mesh({2, 2, 6}, {0.1, 0.1, 0.3}, 1000.0);
  mesh.fix_plane(2, 0.0);
  for (Energy energy : kEnergies) {
    auto model = make_vbd(mesh, make_material(1e5, 0.3, 1000.0), with_energy(energy));
    BodyState body(mesh);
    body.add_gravity(mesh, {0.0, -9.81, 0.0});
    model->begin(body.state, 1e-3);
    for (int n = 0; n < 100; ++n) model->step(body.state, 1e-3);
    double sag = 0.0;
    for (uint32_t i = 0; i < mesh.node_count(); ++i) {
      sag = std::min(sag, body.positions[3 * i + 1] - mesh.positions[3 * i + 1]);
      if (!mesh.fixed[i]) continue;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(body.positions[3 * i + c], mesh.positions[3 * i + c]);
        EXPECT_EQ(body.velocities[3 * i + c], 0.0);
      }
    }
    EXPECT_LT(sag, -1e-4);  // the free end moved
  }
}

double min_volume(const TestMesh& mesh, const std::vector<double>& x) {
  double smallest = 1e300;
  for (size_t t = 0; t < mesh.tets.size(); t += 4)
    smallest = std::min(smallest, tet_signed_volume(node_position(x.data(), mesh.tets[t]),
                                                    node_position(x.data(), mesh.tets[t + 1]),
                                                    node_position(x.data(), mesh.tets[t + 2]),
                                                    node_position(x.data(), mesh.tets[t + 3])));
  return smallest;
}

TEST(VbdDynamics, InvertedStartRecovers) {
  // The centre node of a one-diagonal 2x2x2 cube pushed 1.5 cells out through the +x faces.
  TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.2, 0.2, 0.2}, 1000.0, GridSplit::kOneDiagonal);
  for (Energy energy : kEnergies) {
    tacta_material material = make_material(1e5, 0.3, 1000.0);
    material.rayleigh_mass = 5.0;  // 1/s: settle within the simulated second
    auto model = make_vbd(mesh, material, with_energy(energy));
    BodyState body(mesh);
    body.positions[3 * (1 + 3 * (1 + 3 * 1))] += 0.15;
    ASSERT_LT(min_volume(mesh, body.positions), 0.0);
    const double start = model->elastic_energy(body.positions.data());
    model->begin(body.state, 1e-3);
    uint32_t flags = 0;
    for (int n = 0; n < 1000; ++n) flags |= model->step(body.state, 1e-3);
    EXPECT_EQ(flags & TACTA_STEP_FAULT_MASK, 0u);
    const double rest_volume = 0.1 * 0.1 * 0.1 / 6.0;
    EXPECT_GT(min_volume(mesh, body.positions), 0.9 * rest_volume)
        << "energy " << static_cast<int>(energy);
    // alpha = 5/s alone leaves e^-10 = 4.5e-5 of the energy after 1 s; implicit Euler damps
    // the fast modes further.
    EXPECT_LT(model->elastic_energy(body.positions.data()), 4.5e-5 * start);
  }
}

TEST(VbdDynamics, DampedMotionDiesOut) {
  // A twisted bar, Rayleigh alpha 5/s and beta 0.01 s: the energy falls below 5 % in 0.5 s.
  TestMesh mesh = box_tet_mesh({2, 2, 6}, {0.1, 0.1, 0.3}, 1000.0);
  mesh.fix_plane(2, 0.0);
  for (Energy energy : kEnergies) {
    tacta_material material = make_material(1e5, 0.3, 1000.0);
    material.rayleigh_mass = 5.0;
    material.rayleigh_stiffness = 0.01;
    auto model = make_vbd(mesh, material, with_energy(energy));
    BodyState body(mesh);
    for (uint32_t i = 0; i < mesh.node_count(); ++i) {
      const double z = mesh.positions[3 * i + 2], angle = 0.5 * z / 0.3;  // up to 0.5 rad
      const double x = mesh.positions[3 * i] - 0.05, y = mesh.positions[3 * i + 1] - 0.05;
      body.positions[3 * i] = 0.05 + std::cos(angle) * x - std::sin(angle) * y;
      body.positions[3 * i + 1] = 0.05 + std::sin(angle) * x + std::cos(angle) * y;
    }
    const double start = model->elastic_energy(body.positions.data());
    model->begin(body.state, 1e-3);
    for (int n = 0; n < 500; ++n)
      ASSERT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
    const double end = model->elastic_energy(body.positions.data()) + body.kinetic_energy(mesh);
    EXPECT_LT(end, 0.05 * start) << "energy " << static_cast<int>(energy);
  }
}

// 40 steps of a bar kicked sideways and falling, with every parameter that touches step().
std::vector<double> run_kicked_bar(Energy energy, const tacta_host_services* host) {
  TestMesh mesh = box_tet_mesh({6, 6, 16}, {0.06, 0.06, 0.16}, 1000.0);
  mesh.fix_plane(2, 0.0);
  tacta_material material = make_material(1e5, 0.4, 1000.0);
  material.rayleigh_mass = 1.0;
  material.rayleigh_stiffness = 0.005;
  Options options = with_energy(energy);
  options.host = host;
  auto model = make_vbd(mesh, material, options);
  BodyState body(mesh);
  body.add_gravity(mesh, {0.0, -9.81, 0.0});
  for (uint32_t i = 0; i < mesh.node_count(); ++i)
    body.velocities[3 * i] = 2.0 * mesh.positions[3 * i + 2];  // m/s, growing along the bar
  model->begin(body.state, 1e-3);
  for (int n = 0; n < 40; ++n) model->step(body.state, 1e-3);
  std::vector<double> out = body.positions;
  out.insert(out.end(), body.velocities.begin(), body.velocities.end());
  return out;
}

TEST(VbdParallel, EqualsSerialAndRepeatsBitForBit) {
  // Vertices of one colour share no tet, so each update reads only other colours' positions:
  // the order the workers take them in cannot change a bit.
  for (Energy energy : kEnergies) {
    const std::vector<double> serial = run_kicked_bar(energy, nullptr);
    PoolHost two(2);
    const std::vector<double> first = run_kicked_bar(energy, &two.services);
    EXPECT_GT(two.split_calls.load(), 0) << "no parallel_for was split: the test proves nothing";
    PoolHost again(2);
    const std::vector<double> second = run_kicked_bar(energy, &again.services);
    ASSERT_EQ(serial.size(), first.size());
    EXPECT_EQ(std::memcmp(serial.data(), first.data(), serial.size() * sizeof(double)), 0)
        << "energy " << static_cast<int>(energy);
    EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
  }
}

TEST(VbdAllocation, StepAllocatesNothing) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "the sanitizer owns malloc";
  TestMesh mesh = box_tet_mesh({6, 6, 12}, {0.06, 0.06, 0.12}, 1000.0);
  mesh.fix_plane(2, 0.0);
  tacta_material material = make_material(1e5, 0.3, 1000.0);
  material.rayleigh_mass = 1.0;
  material.rayleigh_stiffness = 0.01;
  PoolHost pool(2);
  for (const tacta_host_services* host : {static_cast<const tacta_host_services*>(nullptr),
                                          static_cast<const tacta_host_services*>(&pool.services)})
    for (Energy energy : kEnergies)
      for (InitialGuess guess : {InitialGuess::kAdaptive, InitialGuess::kInertia}) {
        Options options = with_energy(energy);
        options.host = host;
        options.initial_guess = guess;
        auto model = make_vbd(mesh, material, options);
        BodyState body(mesh);
        body.add_gravity(mesh, {0.0, -9.81, 0.0});
        model->begin(body.state, 1e-3);
        model->step(body.state, 1e-3);
        g_allocations = 0;
        g_counting = true;
        for (int n = 0; n < 20; ++n) model->step(body.state, 1e-3);
        g_counting = false;
        EXPECT_EQ(g_allocations, 0)
            << "energy " << static_cast<int>(energy) << " host " << (host != nullptr);
      }
}

}  // namespace
}  // namespace tacta::models::vbd
