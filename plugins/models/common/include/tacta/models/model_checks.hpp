// Checks shared by the model tests, written against any model class with
//   void internal_forces(const double* x, double* f);   uint32_t step(tacta_body_state&, double)
// Header-only and test-side: these allocate freely.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models::checks {

// Dense stiffness K = -dF/dx by central differences of internal_forces around x (N/m).
template <class Model>
Eigen::MatrixXd stiffness_by_differences(Model& model, const std::vector<double>& x,
                                         double step = 1e-6) {
  const Eigen::Index n = static_cast<Eigen::Index>(x.size());
  Eigen::MatrixXd k(n, n);
  std::vector<double> probe = x, plus(x.size()), minus(x.size());
  for (Eigen::Index j = 0; j < n; ++j) {
    const size_t jj = static_cast<size_t>(j);
    probe[jj] = x[jj] + step;
    model.internal_forces(probe.data(), plus.data());
    probe[jj] = x[jj] - step;
    model.internal_forces(probe.data(), minus.data());
    probe[jj] = x[jj];
    for (Eigen::Index i = 0; i < n; ++i)
      k(i, j) = -(plus[static_cast<size_t>(i)] - minus[static_cast<size_t>(i)]) / (2 * step);
  }
  return k;
}

// Smallest eigenvalue of the symmetric part and the relative asymmetry |K - K^T| / |K|.
struct StiffnessReport {
  double asymmetry = 0;
  double min_eigenvalue = 0;  // N/m
  double max_eigenvalue = 0;  // N/m
};
inline StiffnessReport inspect_stiffness(const Eigen::MatrixXd& k) {
  StiffnessReport r;
  r.asymmetry = (k - k.transpose()).norm() / k.norm();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (k + k.transpose()));
  r.min_eigenvalue = eig.eigenvalues().minCoeff();
  r.max_eigenvalue = eig.eigenvalues().maxCoeff();
  return r;
}

// Rotates rest positions about the centroid by angle (rad) around the z axis.
inline std::vector<double> rotated_about_z(const std::vector<double>& rest, double angle) {
  const size_t n = rest.size() / 3;
  double cx = 0, cy = 0;
  for (size_t i = 0; i < n; ++i) cx += rest[3 * i] / n, cy += rest[3 * i + 1] / n;
  std::vector<double> x = rest;
  const double c = std::cos(angle), s = std::sin(angle);
  for (size_t i = 0; i < n; ++i) {
    const double dx = rest[3 * i] - cx, dy = rest[3 * i + 1] - cy;
    x[3 * i] = cx + c * dx - s * dy;
    x[3 * i + 1] = cy + s * dx + c * dy;
  }
  return x;
}

// A body state over caller-owned arrays.
struct StateBuffers {
  std::vector<double> x, v, f_ext;
  explicit StateBuffers(const std::vector<double>& positions)
      : x(positions), v(positions.size(), 0.0), f_ext(positions.size(), 0.0) {}
  tacta_body_state state(double time = 0) {
    return {static_cast<uint32_t>(x.size() / 3), x.data(), v.data(), f_ext.data(), time};
  }
};

// Period (s) of a signal sampled every dt, from the mean spacing of its upward zero crossings
// (linear interpolation between samples); 0 when fewer than two crossings.
inline double period_from_crossings(const std::vector<double>& signal, double dt) {
  std::vector<double> crossings;
  for (size_t k = 1; k < signal.size(); ++k)
    if (signal[k - 1] < 0 && signal[k] >= 0)
      crossings.push_back(
          dt * (static_cast<double>(k) - 1 + signal[k - 1] / (signal[k - 1] - signal[k])));
  if (crossings.size() < 2) return 0;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

}  // namespace tacta::models::checks

namespace tacta::models::checks {

// Largest stable step by bisection: stable(dt) runs the model and says whether it stayed
// bounded. Returns the midpoint of the final bracket [lo, hi] (s); relative width ~ 2^-iterations.
template <class StableFn>
double critical_dt(StableFn&& stable, double lo, double hi, int iterations = 12) {
  for (int it = 0; it < iterations; ++it) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

// Deterministic pseudo-random numbers in [-1, 1) (a 64-bit LCG), for perturbations in tests.
class TestRandom {
 public:
  explicit TestRandom(uint64_t seed) : state_(seed) {}
  double next() {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state_ >> 11) / static_cast<double>(1ull << 52) - 1.0;
  }

 private:
  uint64_t state_;
};

}  // namespace tacta::models::checks

namespace tacta::models::checks {

// Steps the model and reports whether every velocity stayed finite and below limit (m/s).
template <class Model>
bool stays_bounded(Model& model, StateBuffers& s, double dt, int steps, double limit) {
  for (int k = 0; k < steps; ++k) {
    tacta_body_state st = s.state(k * dt);
    model.step(st, dt);
    for (double v : s.v)
      if (!(std::abs(v) < limit)) return false;  // also catches NaN
  }
  return true;
}

}  // namespace tacta::models::checks
