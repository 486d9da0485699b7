// Checks of the periodic spline and the closed-curve geometry against exact curves.
#include "ehd_capsule/geometry/closed_curve.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ehd {
namespace {

Eigen::Matrix2Xd Ellipse(int m, double a, double b, double phase = 0.0, bool clockwise = false,
                         double jitter = 0.0) {
  Eigen::Matrix2Xd x(2, m);
  for (int k = 0; k < m; ++k) {
    double t = 2.0 * M_PI * k / m + phase + jitter * std::sin(3.0 * 2.0 * M_PI * k / m) / m;
    if (clockwise) t = -t;
    x(0, k) = a * std::cos(t);
    x(1, k) = b * std::sin(t);
  }
  return x;
}

// A periodic spline through samples of sin reproduces sin and its derivatives to O(h^4), O(h^3),
// O(h^2): halving h must cut the value error by about 16.
TEST(PeriodicCubicSpline, ConvergesFourthOrderOnSine) {
  double err[2];
  for (int r = 0; r < 2; ++r) {
    const int n = 16 << r;
    std::vector<double> s(n), v(n);
    for (int k = 0; k < n; ++k) {
      s[k] = 2.0 * M_PI * k / n;
      v[k] = std::sin(s[k]);
    }
    PeriodicCubicSpline sp;
    sp.Fit(s, 2.0 * M_PI, v);
    err[r] = 0.0;
    for (int q = 0; q < 1000; ++q) {
      const double x = 2.0 * M_PI * q / 1000.0;
      err[r] = std::max(err[r], std::abs(sp.Value(x) - std::sin(x)));
    }
  }
  EXPECT_GT(std::log2(err[0] / err[1]), 3.7);
}

TEST(PeriodicCubicSpline, RejectsBadKnots) {
  PeriodicCubicSpline sp;
  EXPECT_THROW(sp.Fit({0.0, 1.0}, 2.0, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(sp.Fit({0.0, 1.0, 1.0}, 3.0, {1.0, 2.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(sp.Fit({0.0, 1.0, 2.0}, 2.0, {1.0, 2.0, 3.0}), std::invalid_argument);
}

// Circle of radius r: curvature 1/r, outward normal = radial direction, length 2 pi r,
// area pi r^2, whichever way the markers run.
TEST(ClosedCurve, CircleGeometryBothOrientations) {
  for (bool cw : {false, true}) {
    const double r = 0.7;
    ClosedCurve c(Ellipse(64, r, r, 0.1, cw));
    EXPECT_EQ(c.orientation(), cw ? -1 : 1);
    for (int k = 0; k < c.size(); ++k) {
      const CurvePoint p = c.AtMarker(k);
      // Chord-length parametrisation makes the spline curvature second-order accurate only:
      // (h/r)^2 ~ 5e-3 relative at 64 markers, bounded here by 2e-3 / r.
      EXPECT_NEAR(p.curvature, 1.0 / r, 2e-3 / r);
      EXPECT_NEAR(p.normal.dot(p.position.normalized()), 1.0, 1e-8);
      // Counter-clockwise tangent: t = (-y, x)/r.
      EXPECT_NEAR(p.tangent.dot(Eigen::Vector2d(-p.position.y(), p.position.x()) / r), 1.0, 1e-8);
    }
    EXPECT_NEAR(c.ArcLength(), 2.0 * M_PI * r, 1e-6);
    EXPECT_NEAR(c.Area(), M_PI * r * r, 1e-6);
    EXPECT_NEAR(c.Centroid().norm(), 0.0, 1e-10);
  }
}

// Ellipse with unevenly spaced markers: curvature a b / (a^2 sin^2 t + b^2 cos^2 t)^{3/2} at
// the point (a cos t, b sin t); the error falls at least like h^2.
TEST(ClosedCurve, EllipseCurvatureConvergesWithUnevenMarkers) {
  const double a = 1.0, b = 0.5;
  double err[2];
  for (int r = 0; r < 2; ++r) {
    ClosedCurve c(Ellipse(64 << r, a, b, 0.0, false, 2.0));
    err[r] = 0.0;
    for (int k = 0; k < c.size(); ++k) {
      const CurvePoint p = c.AtMarker(k);
      const double t = std::atan2(p.position.y() / b, p.position.x() / a);
      const double st = std::sin(t), ct = std::cos(t);
      const double exact = a * b / std::pow(a * a * st * st + b * b * ct * ct, 1.5);
      err[r] = std::max(err[r], std::abs(p.curvature - exact));
    }
  }
  EXPECT_LT(err[1], 2e-2);  // max curvature a/b^2 = 4: 0.5% of it
  EXPECT_GT(std::log2(err[0] / err[1]), 1.8);
}

TEST(ClosedCurve, SignedDistanceAndContains) {
  const double r = 0.5;
  ClosedCurve c(Ellipse(48, r, r));
  for (double rho : {0.0, 0.2, 0.49, 0.501, 0.8, 2.0}) {
    for (int q = 0; q < 7; ++q) {
      const double th = 0.3 + q;
      const Eigen::Vector2d p(rho * std::cos(th), rho * std::sin(th));
      if (rho > 0.0) {
        EXPECT_NEAR(c.SignedDistance(p), rho - r, 1e-6);
      }
      EXPECT_EQ(c.Contains(p), rho < r);
    }
  }
}

// d/dl and d^2/dl^2 of w = cos(theta) on a circle of radius r: -sin(theta)/r, -cos(theta)/r^2.
TEST(ClosedCurve, ArcLengthDerivativesOfMarkerScalar) {
  const double r = 0.5;
  for (bool cw : {false, true}) {
    ClosedCurve c(Ellipse(128, r, r, 0.0, cw));
    std::vector<double> w(c.size());
    for (int k = 0; k < c.size(); ++k) w[k] = c.markers()(0, k) / r;
    const PeriodicCubicSpline f = c.FitScalar(w);
    for (int k = 0; k < c.size(); k += 7) {
      const CurvePoint p = c.AtMarker(k);
      const double th = std::atan2(p.position.y(), p.position.x());
      double d1, d2;
      c.ArcLengthDerivatives(f, p.s, &d1, &d2);
      EXPECT_NEAR(d1, -std::sin(th) / r, 1e-4);
      EXPECT_NEAR(d2, -std::cos(th) / (r * r), 1e-2);
    }
  }
}

}  // namespace
}  // namespace ehd
