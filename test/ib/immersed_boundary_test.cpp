// Immersed boundary transfer (song2019 eqs. (102)-(106)): kernel moments, adjointness of
// spreading and interpolation, force conservation, periodic wrap, wall truncation, marker update.
#include "ehd_capsule/ib/immersed_boundary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/ib/cosine_delta.h"

namespace ehd {
namespace {

// Lattice-unit grid as used by the coupled solver: walls at y = +-N/2, periodic in x.
Grid2D LatticeGrid(int n) { return Grid2D{n, n, 1.0, -0.5 * n, -0.5 * n}; }

// Largest |entry| (a plain loop: Eigen's vectorised maxCoeff trips a GCC 12 -Wmaybe-uninitialized
// false positive under -march=native).
template <typename Derived>
double MaxAbs(const Eigen::DenseBase<Derived>& m) {
  double r = 0.0;
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) r = std::max(r, std::abs(double(m(i, j))));
  }
  return r;
}

TEST(CosineDelta, KernelValuesAndSupport) {
  // eq. (103): phi(0) = 1/2, phi(1) = 1/4, phi(2) = 0, even.
  EXPECT_DOUBLE_EQ(CosineDelta(0.0), 0.5);
  EXPECT_NEAR(CosineDelta(1.0), 0.25, 1e-15);
  EXPECT_NEAR(CosineDelta(-1.0), 0.25, 1e-15);
  EXPECT_EQ(CosineDelta(2.0), 0.0);
  EXPECT_EQ(CosineDelta(-2.5), 0.0);
}

TEST(CosineDelta, DiscreteMomentsForAnyOffset) {
  // Sums over the integer nodes, derived in cosine_delta.h from the identities
  // sum of the four quarter-turn-shifted cosines = 0 and cos^2 = (1 + cos 2x)/2:
  //   sum phi = 1, even/odd sums = 1/2, sum phi^2 = 3/8, first moment d - 1/2 + (cos - sin)/2.
  for (double r = -3.0; r <= 3.0; r += 0.0371) {
    double m0 = 0.0, m1 = 0.0, m2 = 0.0, even = 0.0;
    for (int j = -8; j <= 8; ++j) {
      const double p = CosineDelta(r - j);
      m0 += p;
      m1 += (r - j) * p;
      m2 += p * p;
      if (j % 2 == 0) even += p;
    }
    const double d = r - std::floor(r);
    const double expected_m1 = d - 0.5 + 0.5 * (std::cos(M_PI_2 * d) - std::sin(M_PI_2 * d));
    EXPECT_NEAR(m0, 1.0, 1e-14) << r;
    EXPECT_NEAR(even, 0.5, 1e-14) << r;
    EXPECT_NEAR(m2, 3.0 / 8.0, 1e-14) << r;
    EXPECT_NEAR(m1, expected_m1, 1e-14) << r;
    EXPECT_LE(std::abs(m1), 0.0212) << r;
    // The stencil helper reproduces the kernel at its four nodes.
    const DeltaStencil st = CosineDeltaStencil(r);
    for (int a = 0; a < 4; ++a) {
      EXPECT_NEAR(st.weight[a], CosineDelta(r - (st.first + a)), 1e-15) << r;
    }
  }
}

class ImmersedBoundaryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    ux.resize(grid.size());
    uy.resize(grid.size());
    for (auto& v : ux) v = u(gen);
    for (auto& v : uy) v = u(gen);
    // Markers everywhere, including across the periodic x edge and off-centre offsets.
    X.resize(2, 40);
    F.resize(2, 40);
    for (int c = 0; c < 40; ++c) {
      X(0, c) = 1.4 * grid.x0 + 1.3 * grid.width() * (c + 0.5) / 40.0;  // beyond both x ends
      X(1, c) = 0.6 * grid.y0 * u(gen);                                 // >= 2h from the walls
      F(0, c) = u(gen);
      F(1, c) = u(gen);
    }
  }
  Grid2D grid = LatticeGrid(24);
  std::vector<double> ux, uy;
  Eigen::Matrix2Xd X, F;
};

TEST_F(ImmersedBoundaryTest, SpreadAndInterpolateAreAdjoint) {
  // <Spread(F), u> h^2 = <F, Interpolate(u)>: both are sum_c sum_j phi phi F_c u_j, eq. (104)
  // and (106) use the same kernel. Holds with the periodic wrap in x (markers outside the box).
  for (double h : {1.0, 0.37}) {
    Grid2D g = grid;
    g.h = h;
    g.x0 *= h;
    g.y0 *= h;
    ImmersedBoundary ib(g, true, false);
    Eigen::Matrix2Xd Xs = X * h, U;
    std::vector<double> fx(g.size(), 0.0), fy(g.size(), 0.0);
    ib.Spread(Xs, F, fx, fy);
    ib.Interpolate(ux, uy, Xs, U);
    double lhs = 0.0;
    for (std::size_t j = 0; j < g.size(); ++j) lhs += (fx[j] * ux[j] + fy[j] * uy[j]) * h * h;
    double rhs = 0.0;  // plain loop, see MaxAbs
    for (Eigen::Index c = 0; c < F.cols(); ++c) rhs += F(0, c) * U(0, c) + F(1, c) * U(1, c);
    EXPECT_NEAR(lhs, rhs, 1e-12 * (1.0 + std::abs(rhs))) << h;
  }
}

TEST_F(ImmersedBoundaryTest, SpreadConservesTotalForceAndAdds) {
  // sum_j p_j h^2 = sum_c F_c because sum_j phi = 1 in each direction (support inside the walls).
  ImmersedBoundary ib(grid, true, false);
  std::vector<double> fx(grid.size(), 1.0), fy(grid.size(), -2.0);
  ib.Spread(X, F, fx, fy);
  double sx = 0.0, sy = 0.0;
  for (std::size_t j = 0; j < grid.size(); ++j) {
    sx += fx[j] - 1.0;  // Spread adds to what was there
    sy += fy[j] + 2.0;
  }
  EXPECT_NEAR(sx, F.row(0).sum(), 1e-12);
  EXPECT_NEAR(sy, F.row(1).sum(), 1e-12);
}

TEST_F(ImmersedBoundaryTest, PeriodicImageGivesSameVelocity) {
  // A marker shifted by the domain width sees the same nodes, so the same velocity.
  ImmersedBoundary ib(grid, true, false);
  Eigen::Matrix2Xd U, U2, X2 = X;
  X2.row(0).array() += grid.width();
  ib.Interpolate(ux, uy, X, U);
  ib.Interpolate(ux, uy, X2, U2);
  EXPECT_LT(MaxAbs(U - U2), 1e-13);
}

TEST(ImmersedBoundary, LinearFieldErrorIsTheKernelFirstMoment) {
  // The cosine kernel has sum phi = 1 but a nonzero first moment m1(d) (cosine_delta.h), so a
  // linear field u = a + b x is interpolated as a + b (x - m1(d_x) h): exact at node and
  // mid-cell offsets, off by at most 0.0211 b h elsewhere. This checks eq. (104) exactly.
  const Grid2D grid = LatticeGrid(32);
  ImmersedBoundary ib(grid, true, false);
  std::vector<double> ux(grid.size()), uy(grid.size());
  const double bx = 0.3, by = -0.7;
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      ux[grid.index(i, j)] = 2.0 + bx * grid.y(j);  // shear-like, varies along y only
      uy[grid.index(i, j)] = 1.0 + by * grid.y(j);
    }
  }
  Eigen::Matrix2Xd X(2, 50), U;
  for (int c = 0; c < 50; ++c) X.col(c) << 0.21 * c - 5.0, -6.0 + 0.2437 * c;
  ib.Interpolate(ux, uy, X, U);
  for (int c = 0; c < 50; ++c) {
    const double yi = (X(1, c) - grid.y0) / grid.h - 0.5;
    const double d = yi - std::floor(yi);
    const double m1 = d - 0.5 + 0.5 * (std::cos(M_PI_2 * d) - std::sin(M_PI_2 * d));
    EXPECT_NEAR(U(0, c), 2.0 + bx * (X(1, c) - m1 * grid.h), 1e-12);
    EXPECT_NEAR(U(1, c), 1.0 + by * (X(1, c) - m1 * grid.h), 1e-12);
    EXPECT_LE(std::abs(U(0, c) - (2.0 + bx * X(1, c))), 0.0212 * std::abs(bx) * grid.h);
  }
  // Mid-cell and node offsets are exact.
  Eigen::Matrix2Xd Xe(2, 2);
  Xe << 0.0, 0.0, 0.5, 1.0;  // y = 0.5 is a node (cell centre), y = 1.0 a cell face
  ib.Interpolate(ux, uy, Xe, U);
  EXPECT_NEAR(U(0, 0), 2.0 + bx * 0.5, 1e-13);
  EXPECT_NEAR(U(0, 1), 2.0 + bx * 1.0, 1e-13);
}

TEST(ImmersedBoundary, WallTruncationDropsForceOutsideTheGrid) {
  // Without periodic y the support rows beyond the wall are dropped (documented, not
  // renormalised): a marker on the first node row (0.5h from the wall at y = -N/2) has support
  // rows -1, 0, 1 with weights 1/4, 1/2, 1/4; row -1 lies beyond the wall, so 1/4 is lost.
  const Grid2D grid = LatticeGrid(16);
  ImmersedBoundary ib(grid, true, false);
  std::vector<double> fx(grid.size(), 0.0), fy(grid.size(), 0.0);
  Eigen::Matrix2Xd X(2, 1), F(2, 1);
  X << 0.3, grid.y0 + 0.5;
  F << 1.0, 0.0;
  ib.Spread(X, F, fx, fy);
  double total = 0.0;
  for (double v : fx) total += v;
  EXPECT_NEAR(total, 1.0 - CosineDelta(1.0), 1e-14);
  // With periodic y nothing is lost.
  ImmersedBoundary ib_periodic(grid, true, true);
  std::fill(fx.begin(), fx.end(), 0.0);
  ib_periodic.Spread(X, F, fx, fy);
  total = 0.0;
  for (double v : fx) total += v;
  EXPECT_NEAR(total, 1.0, 1e-14);
}

TEST(ImmersedBoundary, RejectsWrongFieldSize) {
  const Grid2D grid = LatticeGrid(8);
  ImmersedBoundary ib(grid, true, false);
  std::vector<double> small(10), ok(grid.size());
  Eigen::Matrix2Xd X = Eigen::Matrix2Xd::Zero(2, 3), U;
  EXPECT_THROW(ib.Interpolate(small, ok, X, U), std::invalid_argument);
  EXPECT_THROW(ImmersedBoundary(Grid2D{2, 8, 1.0, 0.0, 0.0}, true, false), std::invalid_argument);
}

TEST(MarkerAdvector, EulerAndAdamsBashforthOrders) {
  // dX/dt = A X (rigid rotation, angular speed w): exact X(t) = R(w t) X0. Forward Euler (eq.
  // (105)) has global error O(dt), AB2 O(dt^2): halving dt divides the error by ~2 and ~4.
  const double w = 1.0, t_end = 1.0;
  Eigen::Matrix2d A;
  A << 0.0, -w, w, 0.0;
  auto run = [&](MarkerIntegrator scheme, int steps) {
    Eigen::Matrix2Xd X(2, 1);
    X << 1.0, 0.0;
    MarkerAdvector adv(scheme);
    const double dt = t_end / steps;
    for (int n = 0; n < steps; ++n) {
      const Eigen::Matrix2Xd U = A * X;
      adv.Advance(U, dt, X);
    }
    return (X.col(0) - Eigen::Vector2d(std::cos(w * t_end), std::sin(w * t_end))).norm();
  };
  const double e1 = run(MarkerIntegrator::kForwardEuler, 200);
  const double e2 = run(MarkerIntegrator::kForwardEuler, 400);
  EXPECT_NEAR(std::log2(e1 / e2), 1.0, 0.1);
  const double a1 = run(MarkerIntegrator::kAdamsBashforth2, 200);
  const double a2 = run(MarkerIntegrator::kAdamsBashforth2, 400);
  EXPECT_NEAR(std::log2(a1 / a2), 2.0, 0.15);
  EXPECT_LT(a2, e2);
}

TEST(MarkerArcElements, CircleElementsSumToPerimeter) {
  // dl_k = (l_{k-1} + l_k)/2 telescopes: sum dl = curve length, and equal on a circle of equally
  // spaced markers (2 pi r / M up to spline accuracy).
  const ClosedCurve c(CircleMarkers(64, 3.0));
  const std::vector<double> dl = MarkerArcElements(c);
  double sum = 0.0;
  for (double v : dl) sum += v;
  EXPECT_NEAR(sum, c.ArcLength(), 1e-12);
  for (double v : dl) EXPECT_NEAR(v, 2.0 * M_PI * 3.0 / 64.0, 1e-6);
  std::vector<double> seg(64), dl2;
  for (int k = 0; k < 64; ++k) seg[k] = c.SegmentArcLength(k);
  MarkerArcElementsFromSegments(seg, dl2);
  for (int k = 0; k < 64; ++k) EXPECT_NEAR(dl2[k], dl[k], 1e-14);
}

TEST(WrapCurveIntoDomain, ShiftsWholeCurveByPeriods) {
  // The curve stays continuous (every marker shifted by the same multiple of the width) and its
  // mean ends in [x0, x0 + width).
  const Grid2D grid = LatticeGrid(20);
  Eigen::Matrix2Xd X = CircleMarkers(16, 3.0, Eigen::Vector2d(2.0 * grid.width() + 9.5, 0.0));
  const Eigen::Matrix2Xd before = X;
  const double shift = WrapCurveIntoDomain(grid, X);
  EXPECT_DOUBLE_EQ(shift, -2.0 * grid.width());
  EXPECT_LT(MaxAbs((X - before).row(0).array() - shift), 1e-12);
  EXPECT_LT(MaxAbs((X - before).row(1)), 1e-15);
  EXPECT_GE(X.row(0).mean(), grid.x0);
  EXPECT_LT(X.row(0).mean(), grid.x_max());
  EXPECT_EQ(WrapCurveIntoDomain(grid, X), 0.0);
}

}  // namespace
}  // namespace ehd
