// Viscosity contrast field, song2019 eqs. (117)-(118), (153)-(154): the smoothed Heaviside, the
// field around a circle against the exact signed distance, and the band update against a full
// recomputation.
#include "ehd_capsule/ib/viscosity_indicator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {
namespace {

double SmoothedHeaviside(double d, double h) { return ViscosityIndicator::SmoothedHeaviside(d, h); }

Grid2D LatticeGrid(int n) { return Grid2D{n, n, 1.0, -0.5 * n, -0.5 * n}; }

TEST(SmoothedHeaviside, ShapeOfEq117) {
  // H(0) = 1/2, H(-d) = 1 - H(d) (sin is odd), continuous with zero slope at |d| = 2h
  // (H' = (1 + cos(pi d / 2h)) / 4h), monotone in between.
  const double h = 0.7;
  EXPECT_DOUBLE_EQ(SmoothedHeaviside(0.0, h), 0.5);
  EXPECT_NEAR(SmoothedHeaviside(2.0 * h - 1e-9, h), 1.0, 1e-12);
  EXPECT_NEAR(SmoothedHeaviside(-2.0 * h + 1e-9, h), 0.0, 1e-12);
  EXPECT_EQ(SmoothedHeaviside(5.0, h), 1.0);
  EXPECT_EQ(SmoothedHeaviside(-5.0, h), 0.0);
  double prev = -1.0;
  for (double d = -3.0 * h; d <= 3.0 * h; d += 0.01 * h) {
    const double v = SmoothedHeaviside(d, h);
    EXPECT_NEAR(v + SmoothedHeaviside(-d, h), 1.0, 1e-14);
    EXPECT_GE(v, prev);
    prev = v;
  }
}

// Expected field of a circle of radius r about c from the exact signed distance |x - c| - r.
void ExpectCircleField(const ViscosityIndicator& ind, const Grid2D& g, const Eigen::Vector2d& c,
                       double r, bool periodic_x) {
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      Eigen::Vector2d p(g.x(i), g.y(j));
      if (periodic_x) p.x() += g.width() * std::round((c.x() - p.x()) / g.width());
      const double d = (p - c).norm() - r;
      const double nu = ind.viscosity()[g.index(i, j)];
      if (d < -2.0 * g.h) {
        EXPECT_EQ(nu, ind.viscosity_inside()) << i << " " << j;
      } else if (d > 2.0 * g.h) {
        EXPECT_EQ(nu, ind.viscosity_outside()) << i << " " << j;
      } else {
        // The spline of 96 markers matches the circle to ~1e-5 r; H' <= 1/(2h).
        const double expected =
            ind.viscosity_inside() +
            (ind.viscosity_outside() - ind.viscosity_inside()) * SmoothedHeaviside(d, g.h);
        EXPECT_NEAR(nu, expected, 1e-4) << i << " " << j << " d=" << d;
      }
    }
  }
}

TEST(ViscosityIndicator, CircleFieldMatchesExactDistanceAndIsMonotone) {
  const Grid2D g = LatticeGrid(48);
  const Eigen::Vector2d c(0.3, -0.6);
  const double r = 10.0, nu_in = 0.5, nu_out = 0.1;
  ViscosityIndicator ind(g, true, false, nu_in, nu_out);
  ind.Update(ClosedCurve(CircleMarkers(96, r, c)));
  EXPECT_TRUE(ind.last_update_was_full());
  ExpectCircleField(ind, g, c, r, true);
  // Along a ray from the centre the viscosity goes monotonically from nu_in to nu_out.
  const int j = static_cast<int>(std::floor((c.y() - g.y0) / g.h));
  double prev = nu_in;
  for (int i = g.nx / 2; i < g.nx; ++i) {
    const double nu = ind.viscosity()[g.index(i, j)];
    EXPECT_LE(nu, prev + 1e-15);
    prev = nu;
  }
  EXPECT_EQ(prev, nu_out);
}

TEST(ViscosityIndicator, BandUpdateEqualsFullRecomputation) {
  // A biconcave cell translating and rotating by small steps (markers move < margin = 1h per
  // update, so no full refill is triggered): the band-only update must give
  // exactly the field of a fresh full computation, while touching O(perimeter) nodes.
  const Grid2D g = LatticeGrid(64);
  ViscosityIndicator moving(g, true, false, 2.0, 1.0);
  for (int step = 0; step < 12; ++step) {
    const Eigen::Matrix2Xd x = BiconcaveMarkers(
        128, {12.0}, Eigen::Vector2d(-3.0 + 0.25 * step, 1.0 - 0.15 * step), 0.02 * step);
    const ClosedCurve c(x);
    moving.Update(c);
    ViscosityIndicator fresh(g, true, false, 2.0, 1.0);
    fresh.Update(c);
    EXPECT_EQ(moving.last_update_was_full(), step == 0);
    for (std::size_t n = 0; n < g.size(); ++n) {
      ASSERT_NEAR(moving.viscosity()[n], fresh.viscosity()[n], 1e-12) << step << " node " << n;
    }
    if (step == 0) {
      // Sides of the nodes outside the smooth band agree with ClosedCurve::Contains (an
      // independent winding-number / closest-point test), dimples included.
      for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
          const double hv = fresh.heaviside()[g.index(i, j)];
          if (hv == 0.0 || hv == 1.0) {
            EXPECT_EQ(hv == 0.0, c.Contains(Eigen::Vector2d(g.x(i), g.y(j)))) << i << " " << j;
          }
        }
      }
    }
    if (step > 0) {
      // Band ~ perimeter (~85 h) x 2R (6 h) ~ 500 nodes, far below N^2 = 4096.
      EXPECT_LT(moving.updated_nodes().size(), g.size() / 3);
    }
  }
}

TEST(ViscosityIndicator, CurveAcrossThePeriodicEdge) {
  // Unwrapped markers beyond x_max: the nodes near x0 see the part of the circle that wrapped.
  const Grid2D g = LatticeGrid(40);
  const Eigen::Vector2d c(g.x_max() - 2.0, 0.0);
  ViscosityIndicator ind(g, true, false, 3.0, 1.0);
  ind.Update(ClosedCurve(CircleMarkers(96, 8.0, c)));
  ExpectCircleField(ind, g, c, 8.0, true);
  ind.Update(ClosedCurve(CircleMarkers(96, 8.0, c + Eigen::Vector2d(0.3, 0.0))));
  EXPECT_FALSE(ind.last_update_was_full());
  ExpectCircleField(ind, g, c + Eigen::Vector2d(0.3, 0.0), 8.0, true);
}

TEST(ViscosityIndicator, RejectsBadParameters) {
  EXPECT_THROW(ViscosityIndicator(LatticeGrid(8), true, false, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(ViscosityIndicator(LatticeGrid(8), true, false, 1.0, 1.0, 0.1),
               std::invalid_argument);
}

}  // namespace
}  // namespace ehd
