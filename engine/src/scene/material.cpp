// Materials: E, nu or Lamé lambda, mu (the other pair derived), density and Rayleigh damping.
#include <fmt/format.h>
#include <string>

#include "scene/section_readers.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sdk/elastic_constants.hpp"

namespace tacta {

LameParameters lame_from_engineering(double youngs_modulus, double poisson_ratio) {
  const sdk::Lame l = sdk::lame_from_young(youngs_modulus, poisson_ratio);
  return {l.lambda, l.mu};
}

EngineeringConstants engineering_from_lame(double lambda, double mu) {
  return {sdk::young_from_lame(lambda, mu), sdk::poisson_from_lame(lambda, mu)};
}

}  // namespace tacta

namespace tacta::scene_detail {

namespace {

// Past nu = 0.499 (lambda = 499 mu) linear tetrahedra lock and the stiffness grows as
// 1 / (1 - 2 nu): the corotational liver demo diverges within 0.1 s at nu = 0.4999.
constexpr double kMaxPoissonRatio = 0.499;

std::string too_incompressible(double nu) {
  return fmt::format(
      "a Poisson ratio of {:.9g} is closer to 0.5 than the models handle: at most {} (lambda = 499 "
      "mu); nearer "
      "to 0.5 linear tetrahedra lock and the step diverges. For nearly incompressible tissue use "
      "0.45 to 0.49",
      nu, kMaxPoissonRatio);
}

}  // namespace

MaterialDesc read_material(const Field& field) {
  field.expect_map("a map {youngs_modulus, poisson_ratio, density, ...}");
  field.check_keys({"youngs_modulus", "poisson_ratio", "lame_lambda", "lame_mu", "density",
                    "rayleigh_mass", "rayleigh_stiffness"});
  const bool engineering = field.has("youngs_modulus") || field.has("poisson_ratio");
  const bool lame = field.has("lame_lambda") || field.has("lame_mu");
  if (engineering && lame)
    field.fail(
        "expected exactly one of the pairs {youngs_modulus, poisson_ratio} or "
        "{lame_lambda, lame_mu}, found keys of both");
  if (!engineering && !lame)
    field.fail(
        "expected exactly one of the pairs {youngs_modulus, poisson_ratio} or "
        "{lame_lambda, lame_mu}, found neither");

  MaterialDesc material;
  if (engineering) {
    material.youngs_modulus = field.require("youngs_modulus").real(Range::positive());
    // nu = 0.5 is incompressible (lambda infinite); below -1 the material is unstable.
    const Field nu = field.require("poisson_ratio");
    material.poisson_ratio = nu.real(Range::open(-1.0, 0.5));
    if (material.poisson_ratio > kMaxPoissonRatio)
      nu.fail(too_incompressible(material.poisson_ratio));
    const LameParameters l = lame_from_engineering(material.youngs_modulus, material.poisson_ratio);
    material.lame_lambda = l.lambda;
    material.lame_mu = l.mu;
  } else {
    material.lame_mu = field.require("lame_mu").real(Range::positive());
    // A positive bulk modulus K = lambda + 2 mu / 3 keeps E > 0 and nu in (-1, 0.5).
    const Field lambda = field.require("lame_lambda");
    material.lame_lambda = lambda.real(
        Range{-2.0 * material.lame_mu / 3.0, std::numeric_limits<double>::infinity(), true, false});
    const EngineeringConstants c = engineering_from_lame(material.lame_lambda, material.lame_mu);
    if (c.poisson_ratio > kMaxPoissonRatio) lambda.fail(too_incompressible(c.poisson_ratio));
    material.youngs_modulus = c.youngs_modulus;
    material.poisson_ratio = c.poisson_ratio;
  }
  if (auto f = field.get("density")) material.density = f->real(Range::positive());
  if (auto f = field.get("rayleigh_mass")) material.rayleigh_mass = f->real(Range::non_negative());
  if (auto f = field.get("rayleigh_stiffness"))
    material.rayleigh_stiffness = f->real(Range::non_negative());
  return material;
}

}  // namespace tacta::scene_detail
