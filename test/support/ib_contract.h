// The 2D immersed-boundary contract every kernel keeps (test/ib/delta_kernel_test.cpp,
// even_odd_kernel_test.cpp): on the 24^2 grid of h = 0.5 on [-6, 6]^2, periodic in x and walled
// in y, 30 random points (beyond the periodic x ends, >= 1.5 h from the walls) with random forces:
// a linear field a + b y is interpolated exactly (sum phi = 1, first moment 0), spreading is the
// adjoint of interpolating (sum_grid f.u h^2 = sum_points F.U), and the force is conserved.
// Returns the points, for further checks on the same grid (ContractGrid()).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "ehd_capsule/ib/immersed_boundary.h"

namespace ehd::test {

inline Grid2D ContractGrid() { return Grid2D{24, 24, 0.5, -6.0, -6.0}; }

inline Eigen::Matrix2Xd ExpectAdjointConservingAndExactOnLinearFields(
    const ImmersedBoundaryTransfer<2>& ib, unsigned seed) {
  const Grid2D grid = ContractGrid();
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix2Xd X(2, 30), F(2, 30), U;
  for (int c = 0; c < 30; ++c) {
    X(0, c) = 9.0 * u(gen);
    X(1, c) = 4.5 * u(gen);
    F.col(c) << u(gen), u(gen);
  }
  const std::size_t n = grid.size();
  std::vector<double> ux(n), uy(n), fx(n, 0.0), fy(n, 0.0);
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      ux[grid.index(i, j)] = 2.0 + 0.3 * grid.y(j);
      uy[grid.index(i, j)] = -1.0 - 0.7 * grid.y(j);
    }
  }
  ib.Interpolate({&ux, &uy}, X, U);
  for (int c = 0; c < 30; ++c) {
    EXPECT_NEAR(U(0, c), 2.0 + 0.3 * X(1, c), 1e-13) << c;
    EXPECT_NEAR(U(1, c), -1.0 - 0.7 * X(1, c), 1e-13) << c;
  }
  ib.Spread(X, F, {&fx, &fy});
  double lhs = 0.0, sx = 0.0, sy = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    lhs += (fx[j] * ux[j] + fy[j] * uy[j]) * grid.h * grid.h;
    sx += fx[j] * grid.h * grid.h;
    sy += fy[j] * grid.h * grid.h;
  }
  double rhs = 0.0;
  for (int c = 0; c < 30; ++c) rhs += F(0, c) * U(0, c) + F(1, c) * U(1, c);
  EXPECT_NEAR(lhs, rhs, 1e-12 * (1.0 + std::abs(rhs)));
  EXPECT_NEAR(sx, F.row(0).sum(), 1e-12);
  EXPECT_NEAR(sy, F.row(1).sum(), 1e-12);
  return X;
}

}  // namespace ehd::test
