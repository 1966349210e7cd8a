// Materials: E, nu or Lamé lambda, mu (the other pair derived), density and Rayleigh damping.
#include <string>

#include "scene/readers.hpp"
#include "tacta/scene_loader.hpp"

namespace tacta {

LameParameters lame_from_engineering(double youngs_modulus, double poisson_ratio) {
  const double e = youngs_modulus, nu = poisson_ratio;
  return {e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))};
}

EngineeringConstants engineering_from_lame(double lambda, double mu) {
  return {mu * (3 * lambda + 2 * mu) / (lambda + mu), lambda / (2 * (lambda + mu))};
}

}  // namespace tacta

namespace tacta::scene_detail {

MaterialDesc read_material(const Field& field) {
  field.expect_map("a map {youngs_modulus, poisson_ratio, density, ...}");
  field.check_keys({"youngs_modulus", "poisson_ratio", "lame_lambda", "lame_mu", "density",
                    "rayleigh_mass", "rayleigh_stiffness"});
  const bool engineering = field.has("youngs_modulus") || field.has("poisson_ratio");
  const bool lame = field.has("lame_lambda") || field.has("lame_mu");
  if (engineering && lame)
    field.fail("expected exactly one of the pairs {youngs_modulus, poisson_ratio} or "
               "{lame_lambda, lame_mu}, found keys of both");
  if (!engineering && !lame)
    field.fail("expected exactly one of the pairs {youngs_modulus, poisson_ratio} or "
               "{lame_lambda, lame_mu}, found neither");

  MaterialDesc material;
  if (engineering) {
    material.youngs_modulus = field.require("youngs_modulus").real(Range::positive());
    // nu = 0.5 is incompressible (lambda infinite); below -1 the material is unstable.
    material.poisson_ratio = field.require("poisson_ratio").real(Range::open(-1.0, 0.5));
    const LameParameters l = lame_from_engineering(material.youngs_modulus, material.poisson_ratio);
    material.lame_lambda = l.lambda;
    material.lame_mu = l.mu;
  } else {
    material.lame_mu = field.require("lame_mu").real(Range::positive());
    // A positive bulk modulus K = lambda + 2 mu / 3 keeps E > 0 and nu in (-1, 0.5).
    material.lame_lambda = field.require("lame_lambda")
                               .real(Range{-2.0 * material.lame_mu / 3.0,
                                           std::numeric_limits<double>::infinity(), true, false});
    const EngineeringConstants c = engineering_from_lame(material.lame_lambda, material.lame_mu);
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
