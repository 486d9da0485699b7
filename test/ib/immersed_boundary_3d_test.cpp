// The immersed-boundary transfer in 3D: the tensor product of the 1D cosine delta (song2019
// eqs. (102)-(106) with delta_h = prod phi(x_a/h) / h^3). Checked against the kernel's exact
// discrete identities (partition of unity, sum of squares 3/8 per axis), the product structure,
// adjointness, force conservation, periodic images, wall truncation, and the 2D transfer.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ehd_capsule/ib/cosine_delta.h"
#include "ehd_capsule/ib/immersed_boundary.h"

namespace ehd {
namespace {

Grid3D Box(int nx, int ny, int nz, double h = 1.0) {
  return Grid3D{nx, ny, nz, h, -0.5 * nx * h, -0.5 * ny * h, -0.5 * nz * h};
}

Eigen::Matrix3Xd RandomPoints(int m, const Grid3D& g, double margin, unsigned seed) {
  std::mt19937 rng(seed);
  Eigen::Matrix3Xd x(3, m);
  for (int c = 0; c < m; ++c) {
    for (int a = 0; a < 3; ++a) {
      std::uniform_real_distribution<double> u(g.origin(a) + margin,
                                               g.origin(a) + g.extent(a) * g.h - margin);
      x(a, c) = u(rng);
    }
  }
  return x;
}

std::vector<double> FieldOf(const Grid3D& g, double (*f)(double, double, double)) {
  std::vector<double> v(g.size());
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) v[g.index(i, j, k)] = f(g.x(i), g.y(j), g.z(k));
  return v;
}

TEST(ImmersedBoundary3D, ConstantFieldIsInterpolatedExactly) {
  // sum_j phi(r - j) = 1 on every axis, so the product kernel sums to 1 anywhere.
  const Grid3D g = Box(12, 10, 9, 0.5);
  const ImmersedBoundary3D ib(g, {true, false, true});
  const std::vector<double> one(g.size(), 1.0), two(g.size(), 2.0), three(g.size(), -3.0);
  const Eigen::Matrix3Xd x = RandomPoints(50, g, 2.0 * g.h, 1);
  Eigen::Matrix3Xd u;
  ib.Interpolate({&one, &two, &three}, x, u);
  for (int c = 0; c < x.cols(); ++c) {
    EXPECT_NEAR(u(0, c), 1.0, 1e-14);
    EXPECT_NEAR(u(1, c), 2.0, 1e-14);
    EXPECT_NEAR(u(2, c), -3.0, 1e-14);
  }
}

TEST(ImmersedBoundary3D, KernelIsTheProductOfOneDimensionalKernels) {
  // Spreading a unit force from one point gives prod_a phi((x_a - X_a)/h) / h^3 at each node.
  const Grid3D g = Box(10, 10, 10, 0.25);
  const ImmersedBoundary3D ib(g, {true, true, true});
  Eigen::Matrix3Xd x(3, 1), f(3, 1);
  x << 0.113, -0.271, 0.0457;
  f << 1.0, 0.0, 0.0;
  std::vector<double> fx(g.size(), 0.0), fy(g.size(), 0.0), fz(g.size(), 0.0);
  ib.Spread(x, f, {&fx, &fy, &fz});
  double sum_squares = 0.0;
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const double expected = CosineDelta((g.x(i) - x(0, 0)) / g.h) *
                                CosineDelta((g.y(j) - x(1, 0)) / g.h) *
                                CosineDelta((g.z(k) - x(2, 0)) / g.h) / std::pow(g.h, 3);
        EXPECT_NEAR(fx[g.index(i, j, k)], expected, 1e-12);
        EXPECT_EQ(fy[g.index(i, j, k)], 0.0);
        sum_squares += std::pow(fx[g.index(i, j, k)] * std::pow(g.h, 3), 2);
      }
    }
  }
  // sum_j phi^2 = 3/8 on each axis (cosine_delta.h), for any offset.
  EXPECT_NEAR(sum_squares, std::pow(3.0 / 8.0, 3), 1e-14);
}

TEST(ImmersedBoundary3D, SpreadAndInterpolateAreAdjoint) {
  const Grid3D g = Box(14, 12, 16, 0.7);
  const ImmersedBoundary3D ib(g, {true, false, true});
  const Eigen::Matrix3Xd x = RandomPoints(40, g, 2.5 * g.h, 2);
  const Eigen::Matrix3Xd F = Eigen::Matrix3Xd::Random(3, 40);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-1, 1);
  std::vector<double> u[3];
  for (auto& c : u) {
    c.resize(g.size());
    for (double& v : c) v = uni(rng);
  }
  std::vector<double> f[3];
  for (auto& c : f) c.assign(g.size(), 0.0);
  ib.Spread(x, F, {&f[0], &f[1], &f[2]});
  Eigen::Matrix3Xd U;
  ib.Interpolate({&u[0], &u[1], &u[2]}, x, U);
  double grid_side = 0.0;
  for (int d = 0; d < 3; ++d)
    for (std::size_t n = 0; n < g.size(); ++n) grid_side += f[d][n] * u[d][n];
  grid_side *= std::pow(g.h, 3);
  const double point_side = (F.array() * U.array()).sum();
  EXPECT_NEAR(grid_side, point_side, 1e-12 * std::abs(point_side) + 1e-13);

  // Total force is conserved: sum_j p_j h^3 = sum_c F_c.
  for (int d = 0; d < 3; ++d) {
    double total = 0.0;
    for (double v : f[d]) total += v;
    EXPECT_NEAR(total * std::pow(g.h, 3), F.row(d).sum(), 1e-12);
  }
}

TEST(ImmersedBoundary3D, PeriodicImageGivesSameVelocity) {
  const Grid3D g = Box(8, 8, 8);
  const ImmersedBoundary3D ib(g, {true, true, true});
  const std::vector<double> u = FieldOf(
      g, [](double x, double y, double z) { return std::sin(0.7 * x) + std::cos(0.4 * y) * z; });
  Eigen::Matrix3Xd x(3, 2);
  x.col(0) << 0.3, -1.2, 2.9;
  x.col(1) = x.col(0) + Eigen::Vector3d(8.0, -16.0, 8.0);  // whole periods
  Eigen::Matrix3Xd U;
  ib.Interpolate({&u, &u, &u}, x, U);
  EXPECT_NEAR(U(0, 0), U(0, 1), 1e-13);
}

TEST(ImmersedBoundary3D, WallTruncationDropsForceOutsideTheGrid) {
  // Bounded in y: a point 1h from the wall loses the part of its support beyond the wall, the
  // same fraction as in 1D: the weights of the nodes beyond.
  const Grid3D g = Box(8, 8, 8);
  const ImmersedBoundary3D ib(g, {true, false, true});
  Eigen::Matrix3Xd x(3, 1), F(3, 1);
  x << 0.2, g.y0 + 1.0, -0.4;
  F << 0.0, 1.0, 0.0;
  std::vector<double> fx(g.size(), 0.0), fy(g.size(), 0.0), fz(g.size(), 0.0);
  ib.Spread(x, F, {&fx, &fy, &fz});
  double total = 0.0;
  for (double v : fy) total += v;
  // 1D: nodes at y0 + 0.5 + j; the point sits 0.5 above node 0: weights of nodes -1 and -2
  // (beyond the wall) are phi(1.5) and phi(2.5) = 0.
  EXPECT_NEAR(total, 1.0 - CosineDelta(1.5), 1e-14);
}

TEST(ImmersedBoundary3D, AgreesWithTheTwoDimensionalTransferOnZIndependentFields) {
  const Grid2D g2{12, 12, 1.0, -6.0, -6.0};
  const Grid3D g3{12, 12, 6, 1.0, -6.0, -6.0, -3.0};
  const ImmersedBoundary ib2(g2, true, false);
  const ImmersedBoundary3D ib3(g3, {true, false, true});
  std::vector<double> u2(g2.size()), v2(g2.size()), u3(g3.size()), v3(g3.size()), w3(g3.size());
  for (int j = 0; j < 12; ++j) {
    for (int i = 0; i < 12; ++i) {
      u2[g2.index(i, j)] = std::sin(0.5 * i) * j;
      v2[g2.index(i, j)] = std::cos(0.3 * j) + i;
      for (int k = 0; k < 6; ++k) {
        u3[g3.index(i, j, k)] = u2[g2.index(i, j)];
        v3[g3.index(i, j, k)] = v2[g2.index(i, j)];
        w3[g3.index(i, j, k)] = 0.0;
      }
    }
  }
  Eigen::Matrix2Xd x2(2, 3);
  x2 << -2.3, 0.7, 3.1, -1.1, 2.6, 0.0;
  Eigen::Matrix3Xd x3(3, 3);
  x3.topRows<2>() = x2;
  x3.row(2) << 0.37, -1.9, 2.2;
  Eigen::Matrix2Xd U2;
  Eigen::Matrix3Xd U3;
  ib2.Interpolate(u2, v2, x2, U2);
  ib3.Interpolate({&u3, &v3, &w3}, x3, U3);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(U3(0, c), U2(0, c), 1e-13);
    EXPECT_NEAR(U3(1, c), U2(1, c), 1e-13);
    EXPECT_EQ(U3(2, c), 0.0);
  }
}

TEST(ImmersedBoundary3D, RejectsSmallGridsAndWrongFieldSizes) {
  EXPECT_THROW(ImmersedBoundary3D(Box(8, 8, 3), {true, true, true}), std::invalid_argument);
  const Grid3D g = Box(8, 8, 8);
  const ImmersedBoundary3D ib(g, {true, true, true});
  const std::vector<double> good(g.size(), 0.0), bad(g.size() - 1, 0.0);
  Eigen::Matrix3Xd x = Eigen::Matrix3Xd::Zero(3, 1), U;
  EXPECT_THROW(ib.Interpolate({&good, &bad, &good}, x, U), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
