// Force checks: an elastic model pushes nothing at rest, nothing under a rigid motion it claims to
// be blind to, and (when it claims momentum) its forces cancel. Limits are fractions of E h^2,
// the force a unit strain puts on a node of the test cube (250 N here).
#include <algorithm>
#include <cmath>

#include "conformance/checks.hpp"
#include "conformance/test_body.hpp"

namespace tacta::conformance {

namespace {

// Of E h^2: the least a 1 % stretch must push (the in-tree models give about 1e-2).
constexpr double kResponse = 1e-4;

// Builds a fresh instance and measures the elastic forces at positions(rest).
template <class Shape>
std::vector<double> forces_at(const tacta_descriptor& model, Shape&& shape, std::string& how,
                              double& scale) {
  const auto body = make_test_body(model, false);
  const auto instance = create_model(model, *body);
  scale = body->force_scale();
  return elastic_forces(*instance, *body, shape(body->mesh.positions), how);
}

CheckResult largest_force(const char* name, const tacta_descriptor& model, double fraction,
                          auto&& shape) {
  std::string how;
  double scale = 0;
  const double worst = largest_node_force(forces_at(model, shape, how, scale));
  const double limit = fraction * scale;
  return {name, "max |f| " + figure(worst) + " N (" + how + "), limit " + figure(limit) + " N",
          worst <= limit ? Verdict::Pass : Verdict::Fail};
}

// The cube's centre (it spans [0, 0.1] m on each axis).
constexpr double kCentre = 0.05;

}  // namespace

uint32_t claims_of(const tacta_descriptor& model) {
  return tacta_model_claims(static_cast<const tacta_model_api*>(model.api), model.api_size);
}

CheckResult check_force_at_rest(const tacta_descriptor& model) {
  return largest_force("force at rest", model, kForceRoundOff,
                       [](std::vector<double> x) { return x; });
}

CheckResult check_stretch_response(const tacta_descriptor& model) {
  std::string how;
  double scale = 0;
  const auto stretched = [](std::vector<double> x) {
    for (double& c : x) c = kCentre + 1.01 * (c - kCentre);
    return x;
  };
  const double worst = largest_node_force(forces_at(model, stretched, how, scale));
  const double least = kResponse * scale;
  // Without it every other force check passes on a model that pushes nothing at all.
  return {"stretch response",
          "max |f| under 1 % stretch " + figure(worst) + " N (" + how + "), at least " +
              figure(least) + " N",
          worst >= least && std::isfinite(worst) ? Verdict::Pass : Verdict::Fail};
}

CheckResult check_rigid_translation(const tacta_descriptor& model) {
  return largest_force("rigid translation", model, kForceRoundOff, [](std::vector<double> x) {
    for (size_t i = 0; i < x.size(); i += 3) {
      x[i] += 0.3;
      x[i + 1] -= 0.2;
      x[i + 2] += 0.7;
    }
    return x;
  });
}

CheckResult check_rigid_rotation(const tacta_descriptor& model) {
  if (!(claims_of(model) & TACTA_MODEL_CLAIM_ROTATION_INVARIANT))
    return {"rigid rotation", "not claimed (TACTA_MODEL_CLAIM_ROTATION_INVARIANT unset)",
            Verdict::Skip};
  // 40 degrees about (1, 2, 3) / |(1, 2, 3)| through the centre (Rodrigues' formula).
  const double angle = 40.0 * M_PI / 180.0, c = std::cos(angle), s = std::sin(angle);
  const double n = std::sqrt(14.0), a[3] = {1 / n, 2 / n, 3 / n};
  return largest_force("rigid rotation", model, kForceRoundOff, [&](std::vector<double> x) {
    for (size_t i = 0; i < x.size(); i += 3) {
      const double p[3] = {x[i] - kCentre, x[i + 1] - kCentre, x[i + 2] - kCentre};
      const double dot = a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
      const double cross[3] = {a[1] * p[2] - a[2] * p[1], a[2] * p[0] - a[0] * p[2],
                               a[0] * p[1] - a[1] * p[0]};
      for (int k = 0; k < 3; ++k)
        x[i + k] = kCentre + p[k] * c + cross[k] * s + a[k] * dot * (1 - c);
    }
    return x;
  });
}

CheckResult check_net_force(const tacta_descriptor& model) {
  if (!(claims_of(model) & TACTA_MODEL_CLAIM_MOMENTUM))
    return {"net internal force", "not claimed (TACTA_MODEL_CLAIM_MOMENTUM unset)", Verdict::Skip};
  // Every coordinate moved by up to 2 % of a cell, from a fixed linear congruential sequence.
  uint64_t seed = 12345;
  const auto jiggled = [&](std::vector<double> x) {
    for (double& c : x) {
      seed = seed * 6364136223846793005ull + 1442695040888963407ull;
      c += 0.001 * (static_cast<double>(seed >> 11) / 9007199254740992.0 * 2.0 - 1.0);
    }
    return x;
  };
  std::string how;
  double scale = 0;
  const std::vector<double> f = forces_at(model, jiggled, how, scale);
  double net[3] = {0, 0, 0}, total = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    net[i % 3] += f[i];
    total += std::abs(f[i]);
  }
  const double size = std::hypot(net[0], net[1], net[2]),
               limit = kForceRoundOff * std::max(total, 1e-300);
  return {"net internal force",
          "|sum f| " + figure(size) + " N over sum |f| " + figure(total) + " N (" + how +
              "), limit " + figure(limit) + " N",
          size <= limit && total > 0 ? Verdict::Pass : Verdict::Fail};
}

}  // namespace tacta::conformance
