// The hyperelastic plugin's stress against closed-form uniaxial stress, through the C ABI with
// the plugin's default material constants (so a wrong C10, C01 or bulk default fails here, which
// the energy-gradient checks of test_hyperelastic_tangent cannot see).
//
// A cube of linear tets deformed homogeneously, x = F X with F = diag(t, t, s): each tet's
// nodal force is -V P grad N, so the internal forces on the face z = L sum to -P_zz A exactly,
// and on the face x = L to -P_xx A. s is the prescribed axial stretch; t is the lateral stretch
// of uniaxial stress (P_xx = 0), found from the closed forms below by bisection.
//
// Derivations (principal stretches l = (t, t, s), J = s t^2, P_i = d psi / d l_i):
// - St Venant-Kirchhoff, psi = mu E:E + lambda/2 tr(E)^2, E_i = (l_i^2 - 1)/2, S_i = lambda tr E
//   + 2 mu E_i, P_i = l_i S_i. S_xx = 0 gives E_t = -nu E_s (nu = lambda / (2 (lambda + mu))), so
//   t = sqrt(1 - nu (s^2 - 1)) and S_zz = Young E_s: P_zz = Young s (s^2 - 1) / 2.
// - Compressible Mooney-Rivlin, psi = C10 (J^-2/3 I1 - 3) + C01 (J^-4/3 I2 - 3) + K/2 (J - 1)^2,
//   dI1/dl_i = 2 l_i, dI2/dl_i = 2 l_i (I1 - l_i^2), dJ/dl_i = J / l_i:
//   P_i = C10 J^-2/3 (2 l_i - 2/3 I1 / l_i) + C01 J^-4/3 (2 l_i (I1 - l_i^2) - 4/3 I2 / l_i)
//         + K (J - 1) J / l_i.
//   Incompressible limit (J = 1, t = s^-1/2; Rivlin): P_zz = 2 (s - s^-2) (C10 + C01 / s).
// - Compressible Neo-Hookean, psi = mu/2 (I1 - 3) - mu ln J + lambda/2 ln^2 J:
//   P_i = mu l_i + (lambda ln J - mu) / l_i; incompressible limit P_zz = mu (s - s^-2).
// The plugin's defaults (plugin.cpp): mooney_rivlin C10 = mu/2, C01 = 0, K = lambda + 2 mu / 3,
// so that its small-strain limit is the body's E and nu (checked below at s = 1.001).
#include <cmath>
#include <cstdio>
#include <functional>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "plugin_fixture.hpp"
#include "tacta/model_api.h"
#include "tacta/models/test_meshes.hpp"
#include "validation_row.hpp"

namespace {

using tacta::testing::LoadedPlugin;

constexpr double kYoung = 1e4, kSide = 0.1;  // Pa, m

struct Lame {
  double lambda, mu;
};
Lame lame(double nu) { return {kYoung * nu / ((1 + nu) * (1 - 2 * nu)), kYoung / (2 * (1 + nu))}; }

// Principal first Piola-Kirchhoff stress P_i of each law at stretches l (the closed forms above).
using Principal = std::function<double(const double* l, int i)>;

Principal stvk(double nu) {
  const Lame m = lame(nu);
  return [m](const double* l, int i) {
    double tr = 0;
    for (int k = 0; k < 3; ++k) tr += 0.5 * (l[k] * l[k] - 1);
    return l[i] * (m.lambda * tr + m.mu * (l[i] * l[i] - 1));
  };
}

Principal mooney_rivlin(double c10, double c01, double bulk) {
  return [=](const double* l, int i) {
    const double i1 = l[0] * l[0] + l[1] * l[1] + l[2] * l[2];
    const double i2 =
        l[0] * l[0] * l[1] * l[1] + l[1] * l[1] * l[2] * l[2] + l[2] * l[2] * l[0] * l[0];
    const double j = l[0] * l[1] * l[2];
    return c10 * std::pow(j, -2.0 / 3) * (2 * l[i] - 2.0 / 3 * i1 / l[i]) +
           c01 * std::pow(j, -4.0 / 3) * (2 * l[i] * (i1 - l[i] * l[i]) - 4.0 / 3 * i2 / l[i]) +
           bulk * (j - 1) * j / l[i];
  };
}

Principal neo_hookean(double nu) {
  const Lame m = lame(nu);
  return [m](const double* l, int i) {
    const double j = l[0] * l[1] * l[2];
    return m.mu * l[i] + (m.lambda * std::log(j) - m.mu) / l[i];
  };
}

// Lateral stretch t of uniaxial stress at axial stretch s: P_xx(t, t, s) = 0 by bisection (P_xx
// rises with t for each law on this range).
double lateral_stretch(const Principal& p, double s) {
  double lo = 0.3, hi = 2.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi), l[3] = {mid, mid, s};
    (p(l, 0) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

struct FaceStress {
  double axial = 0, lateral = 0;  // Pa: -(sum of internal forces on the face) / face area
};

// The plugin (material, extra parameters) on a 2x2x2-cell cube at x = diag(t, t, s) X.
FaceStress plugin_stress(const std::string& material,
                         const std::vector<std::pair<std::string, double>>& extra, double nu,
                         double t, double s) {
  LoadedPlugin plugin("tacta_hyperelastic.so");
  const tacta_descriptor& d = plugin.descriptor("hyperelastic");
  const auto& api = plugin.api<tacta_model_api>("hyperelastic");
  auto params = tacta::testing::default_params(d);
  for (uint32_t i = 0; i < d.param_count; ++i) {
    const std::string name = d.params[i].name;
    if (name == "material") {
      params[i].text = material == "neo_hookean" ? "neo_hookean"
                       : material == "stvk"      ? "stvk"
                                                 : "mooney_rivlin";
      params[i].number = material == "neo_hookean" ? 0 : material == "stvk" ? 1 : 2;
    }
    for (const auto& [key, value] : extra)
      if (name == key) params[i].number = value;
  }
  tacta::models::TestMesh mesh =
      tacta::models::box_tet_mesh({2, 2, 2}, {kSide, kSide, kSide}, 1000);
  const tacta_mesh_view view = mesh.view();
  const tacta_material elastic = tacta::models::make_material(kYoung, nu, 1000);
  const tacta_model_setup setup = mesh.setup(view, elastic, params.data(), d.param_count, 1e-3);
  void* instance = nullptr;
  char message[256] = {0};
  EXPECT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
  if (instance == nullptr) return {};
  std::vector<double> x = mesh.positions, f(x.size(), 0.0);
  for (size_t k = 0; k < x.size(); k += 3) x[k] *= t, x[k + 1] *= t, x[k + 2] *= s;
  api.internal_forces(instance, x.data(), f.data());
  api.destroy(instance);
  FaceStress out;
  for (uint32_t n = 0; n < mesh.node_count(); ++n) {
    if (mesh.positions[3 * n + 2] > kSide - 1e-12) out.axial -= f[3 * n + 2];
    if (mesh.positions[3 * n + 0] > kSide - 1e-12) out.lateral -= f[3 * n + 0];
  }
  out.axial /= kSide * kSide;
  out.lateral /= kSide * kSide;
  return out;
}

struct Case {
  const char* name;
  std::string material;
  std::vector<std::pair<std::string, double>> extra;
  double nu;
  Principal closed_form;
};

// Row printed for scripts/validate (docs/VALIDATION.md).
void check(const Case& c, double s, double reference, const char* reference_name, double tolerance,
           const char* why) {
  const double t = lateral_stretch(c.closed_form, s);
  const FaceStress p = plugin_stress(c.material, c.extra, c.nu, t, s);
  const double error = std::abs(p.axial - reference) / std::abs(reference);
  const bool pass = error <= tolerance && std::abs(p.lateral) <= tolerance * std::abs(reference);
  char name[96];
  std::snprintf(name, sizeof name, "hyperelastic.uniaxial.%s.s%.3f", c.name, s);
  tacta::test::validation_row(
      name,
      std::string(reference_name) + ", " + tacta::test::validation_number(reference, 7) + " Pa",
      tacta::test::validation_number(tolerance) + " relative (" + why + ")",
      tacta::test::validation_number(p.axial, 7) + " Pa (lateral " +
          tacta::test::validation_number(p.lateral, 2) + " Pa)",
      pass);
  EXPECT_NEAR(p.axial, reference, tolerance * std::abs(reference)) << c.name << " s " << s;
  EXPECT_NEAR(p.lateral, 0.0, tolerance * std::abs(reference)) << c.name << " s " << s;
}

// Homogeneous F on linear tets: the face sums are exact, so only rounding separates the plugin
// from the closed form (1e-9: the bisection and the sums are at 1e-13).
TEST(HyperelasticUniaxialStress, EveryLawMatchesItsClosedFormAtLargeStretch) {
  const Lame m3 = lame(0.3);
  const std::vector<Case> cases = {
      {"stvk", "stvk", {}, 0.3, stvk(0.3)},
      {"mooney_rivlin_default",
       "mooney_rivlin",
       {},
       0.3,
       mooney_rivlin(0.5 * m3.mu, 0.0, m3.lambda + 2 * m3.mu / 3)},
      {"mooney_rivlin_c10_c01",
       "mooney_rivlin",
       {{"c10", 400.0}, {"c01", 300.0}, {"bulk_modulus", 2e4}},
       0.3,
       mooney_rivlin(400.0, 300.0, 2e4)},
      {"neo_hookean", "neo_hookean", {}, 0.3, neo_hookean(0.3)},
  };
  for (const Case& c : cases)
    for (const double s : {0.7, 1.5}) {
      const double t = lateral_stretch(c.closed_form, s), l[3] = {t, t, s};
      check(c, s, c.closed_form(l, 2), "closed-form uniaxial P_zz (derivation in the test)", 1e-9,
            "homogeneous F is exact on linear tets: rounding only");
    }
  // StVK's own closed form, without the bisection: P_zz = E s (s^2 - 1) / 2.
  const Case stvk_direct{"stvk_direct", "stvk", {}, 0.3, stvk(0.3)};
  for (const double s : {0.7, 1.5})
    check(stvk_direct, s, kYoung * s * (s * s - 1) / 2, "StVK P_zz = E s (s^2 - 1)/2", 1e-9,
          "exact on linear tets");
}

// Small-strain limit: every law's default constants must give the body's Young's modulus.
// Reference: linear elasticity, P_zz = E (s - 1). Tolerance 0.3 %: the laws differ from linear
// at second order, 1.5 (s - 1) = 0.15 % at s = 1.001 (StVK: 3/2 (s - 1) exactly).
TEST(HyperelasticUniaxialStress, DefaultConstantsGiveTheBodysYoungsModulus) {
  for (const char* material : {"stvk", "mooney_rivlin", "neo_hookean"}) {
    const Case c{
        material,
        material,
        {},
        0.3,
        std::string(material) == "stvk" ? stvk(0.3)
        : std::string(material) == "neo_hookean"
            ? neo_hookean(0.3)
            : mooney_rivlin(0.5 * lame(0.3).mu, 0.0, lame(0.3).lambda + 2 * lame(0.3).mu / 3)};
    check(c, 1.001, kYoung * 0.001, "linear elasticity E (s - 1), E = 1e4 Pa", 3e-3,
          "second-order terms 1.5 (s - 1)");
  }
}

// Nearly incompressible (nu 0.499, K = 500 mu): the compressible laws approach the textbook
// incompressible closed forms, an independent reference. Tolerance 1 %: J - 1 is of order
// P / K, 0.2-0.5 % here.
TEST(HyperelasticUniaxialStress, NearlyIncompressibleLawsMeetRivlinsClosedForm) {
  const Lame m = lame(0.499);
  for (const double s : {0.8, 1.5}) {
    const Case mr{"mooney_rivlin_nu0.499",
                  "mooney_rivlin",
                  {},
                  0.499,
                  mooney_rivlin(0.5 * m.mu, 0.0, m.lambda + 2 * m.mu / 3)};
    check(mr, s, 2 * (s - 1 / (s * s)) * (0.5 * m.mu),
          "incompressible Mooney-Rivlin 2 (s - s^-2)(C10 + C01/s), C10 = mu/2", 1e-2,
          "J - 1 ~ P/K");
    const Case nh{"neo_hookean_nu0.499", "neo_hookean", {}, 0.499, neo_hookean(0.499)};
    check(nh, s, m.mu * (s - 1 / (s * s)), "incompressible Neo-Hookean mu (s - s^-2)", 1e-2,
          "J - 1 ~ P/K");
  }
}

}  // namespace
