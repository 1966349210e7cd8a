// SOFA's cantilever (0.02 x 0.02 x 0.2 m, E 2e6 Pa, nu 0.45, rho 1100, g 9.81) over three
// refinements, as validation rows: each level against its value measured when this was written
// +-5 % (a regression guard: a band around the code's own output), and the convergence against
// the analytic tip deflection (the reference): the deflection grows with every refinement, by
// less each time, and stays below the analytic one (a conforming displacement FEM is stiffer
// than the exact solution; 2 % for beam theory's own approximations of the 3D beam).
#pragma once

#include <array>
#include <gtest/gtest.h>
#include <string>

#include "validation_row.hpp"

namespace tacta::test {

inline constexpr double kCantileverAnalytic = 0.03237 + 0.00038;  // m, Euler-Bernoulli + shear

inline void expect_cantilever_convergence(const std::string& model,
                                          const std::array<double, 3>& tips,
                                          const std::array<double, 3>& measured,
                                          const std::array<const char*, 3>& levels) {
  for (size_t i = 0; i < 3; ++i) {
    const bool pass = std::abs(tips[i] - measured[i]) <= 0.05 * measured[i];
    validation_row(model + ".cantilever." + levels[i],
                   "this code's own tip, measured " + validation_number(measured[i]) + " m",
                   "5 % (regression guard)", validation_number(tips[i]) + " m", pass,
                   RowKind::regression);
    EXPECT_NEAR(tips[i], measured[i], 0.05 * measured[i]) << levels[i];
  }
  const bool monotone = tips[0] < tips[1] && tips[1] < tips[2] &&
                        tips[2] - tips[1] < tips[1] - tips[0] &&
                        tips[2] < 1.02 * kCantileverAnalytic;
  validation_row(model + ".cantilever.convergence",
                 "analytic 0.03275 m, approached from below with shrinking steps",
                 "monotone; below 1.02 x analytic (conforming FEM is stiffer)",
                 validation_number(tips[0] / kCantileverAnalytic, 3) + " / " +
                     validation_number(tips[1] / kCantileverAnalytic, 3) + " / " +
                     validation_number(tips[2] / kCantileverAnalytic, 3) + " of analytic",
                 monotone);
  EXPECT_LT(tips[0], tips[1]);
  EXPECT_LT(tips[1], tips[2]);
  EXPECT_LT(tips[2] - tips[1], tips[1] - tips[0]) << "the steps must shrink";
  EXPECT_LT(tips[2], 1.02 * kCantileverAnalytic);
}

}  // namespace tacta::test
