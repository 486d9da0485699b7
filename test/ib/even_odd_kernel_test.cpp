// The kernels that do not couple to the lattice's undamped momentum mode at the grid's Nyquist
// (ib/delta_kernel.h; docs/validation_3d.md, "Damping the grid-Nyquist mode"): trapezoid3 against
// its defining identities (sum 1, first moment 0, Peskin's even-odd condition) and its Fourier
// transform, and the roma3_even_odd transfer (trapezoid3 along each component's own axis, roma3
// along the others) in 2D and 3D: adjoint, force-conserving, exact on linear fields, blind to a
// field alternating node by node along its own component's axis, and roma3 across it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ehd_capsule/ib/delta_kernel.h"
#include "ehd_capsule/ib/immersed_boundary.h"
#include "ehd_capsule/membrane/membrane_stability.h"
#include "support/ib_contract.h"

namespace ehd {
namespace {

constexpr DeltaKernel kTrap = DeltaKernel::kTrapezoid3;
constexpr DeltaKernel kEvenOdd = DeltaKernel::kRoma3EvenOdd;

TEST(Trapezoid3Delta, MomentsAndTheEvenOddConditionForAnyOffset) {
  EXPECT_EQ(ParseDeltaKernel("trapezoid3"), kTrap);
  EXPECT_EQ(ParseDeltaKernel("roma3_even_odd"), kEvenOdd);
  for (double r = -3.0; r <= 3.0; r += 0.0173) {
    double m0 = 0.0, m1 = 0.0, even = 0.0;
    for (int j = -8; j <= 8; ++j) {
      const double p = DeltaKernelValue(kTrap, r - j);
      m0 += p;
      m1 += (r - j) * p;
      if (j % 2 == 0) even += p;
    }
    EXPECT_NEAR(m0, 1.0, 1e-14) << r;
    EXPECT_NEAR(m1, 0.0, 1e-14) << r;
    EXPECT_NEAR(even, 0.5, 1e-14) << r;  // and so the odd nodes 1/2 too
    const DeltaStencil st = Trapezoid3DeltaStencil(r);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(st.weight[a], DeltaKernelValue(kTrap, r - (st.first + a)), 1e-15) << r;
    }
    // The same three nodes as roma3's stencil (roma3_even_odd mixes the two per axis).
    EXPECT_EQ(st.first, Roma3DeltaStencil(r).first) << r;
  }
}

TEST(Trapezoid3Delta, FourierTransformAndNoGridNyquistTransmission) {
  for (double xi : {0.0, 0.4, 1.0, 2.0, 3.14159, 5.0}) {
    const int n = 300000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double r = 1.5 * (i + 0.5) / n;
      sum += DeltaKernelValue(kTrap, r) * std::cos(xi * r);
    }
    EXPECT_NEAR(Trapezoid3DeltaTransform(xi), 2.0 * 1.5 * sum / n, 1e-9) << xi;
  }
  EXPECT_NEAR(GridNyquistTransmission(Trapezoid3DeltaTransform), 0.0, 1e-12);
  EXPECT_NEAR(GridNyquistTransmission(Roma3DeltaTransform), 1.0 / 3.0, 1e-4);
}

TEST(Roma3EvenOddTransfer, TwoDimensionalAdjointConservingExactAndNyquistBlind) {
  const Grid2D grid = test::ContractGrid();
  const ImmersedBoundaryTransfer<2> ib(grid, {true, false}, kEvenOdd);
  const ImmersedBoundaryTransfer<2> roma(grid, {true, false}, DeltaKernel::kRoma3);
  const Eigen::Matrix2Xd X = test::ExpectAdjointConservingAndExactOnLinearFields(ib, 5);
  const std::size_t n = grid.size();
  std::vector<double> ux(n), uy(n);
  Eigen::Matrix2Xd U, V;
  // u_x alternating along x and u_y along y (the lattice's undamped mode, longitudinal): not
  // seen. Across its own axis each component is interpolated with roma3: u_x = g(y), u_y = g(x)
  // give roma3's values.
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      ux[grid.index(i, j)] = (i % 2 ? -1.0 : 1.0) * (1.0 + 0.1 * j);
      uy[grid.index(i, j)] = (j % 2 ? -1.0 : 1.0) * (1.0 + 0.1 * i);
    }
  }
  ib.Interpolate({&ux, &uy}, X, U);
  for (int c = 0; c < 30; ++c) {
    EXPECT_NEAR(U(0, c), 0.0, 1e-14) << c;
    EXPECT_NEAR(U(1, c), 0.0, 1e-14) << c;
  }
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      ux[grid.index(i, j)] = std::sin(1.3 * grid.y(j)) + (j % 2 ? 0.5 : 0.0);
      uy[grid.index(i, j)] = std::cos(0.9 * grid.x(i)) + (i % 2 ? 0.5 : 0.0);
    }
  }
  ib.Interpolate({&ux, &uy}, X, U);
  roma.Interpolate({&ux, &uy}, X, V);
  EXPECT_LT((U - V).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Roma3EvenOddTransfer, ThreeDimensionalAdjointExactAndNyquistBlind) {
  const Grid3D g{10, 10, 10, 0.25, -1.25, -1.25, -1.25};
  const ImmersedBoundaryTransfer<3> ib(g, {true, true, true}, kEvenOdd);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3Xd X(3, 12), F(3, 12), U;
  for (int c = 0; c < 12; ++c) {
    X.col(c) << 0.6 * u(gen), 0.6 * u(gen), 0.6 * u(gen);  // away from the periodic seam
    F.col(c) << u(gen), u(gen), u(gen);
  }
  const std::size_t n = g.size();
  std::vector<double> v[3] = {std::vector<double>(n), std::vector<double>(n),
                              std::vector<double>(n)};
  std::vector<double> f[3] = {std::vector<double>(n, 0.0), std::vector<double>(n, 0.0),
                              std::vector<double>(n, 0.0)};
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        v[0][g.index(i, j, k)] = 1.0 + g.x(i) + 2.0 * g.y(j) - g.z(k);
        v[1][g.index(i, j, k)] = g.y(j) - 0.5 * g.x(i);
        v[2][g.index(i, j, k)] = g.z(k) + 0.3 * g.y(j);
      }
    }
  }
  ib.Interpolate({&v[0], &v[1], &v[2]}, X, U);
  for (int c = 0; c < 12; ++c) {
    EXPECT_NEAR(U(0, c), 1.0 + X(0, c) + 2.0 * X(1, c) - X(2, c), 1e-13);
    EXPECT_NEAR(U(1, c), X(1, c) - 0.5 * X(0, c), 1e-13);
    EXPECT_NEAR(U(2, c), X(2, c) + 0.3 * X(1, c), 1e-13);
  }
  ib.Spread(X, F, {&f[0], &f[1], &f[2]});
  double lhs = 0.0, rhs = 0.0, total[3] = {};
  for (std::size_t m = 0; m < n; ++m) {
    for (int d = 0; d < 3; ++d) {
      lhs += f[d][m] * v[d][m] * g.h * g.h * g.h;
      total[d] += f[d][m] * g.h * g.h * g.h;
    }
  }
  for (int c = 0; c < 12; ++c) rhs += F.col(c).dot(U.col(c));
  EXPECT_NEAR(lhs, rhs, 1e-12 * (1.0 + std::abs(rhs)));
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(total[d], F.row(d).sum(), 1e-12);
  // u_d alternating along axis d: not seen.
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        v[0][g.index(i, j, k)] = i % 2 ? -1.0 : 1.0;
        v[1][g.index(i, j, k)] = j % 2 ? -1.0 : 1.0;
        v[2][g.index(i, j, k)] = k % 2 ? -1.0 : 1.0;
      }
    }
  }
  ib.Interpolate({&v[0], &v[1], &v[2]}, X, U);
  EXPECT_LT(U.cwiseAbs().maxCoeff(), 1e-14);
}

}  // namespace
}  // namespace ehd
