// Checks of the periodic spline and the closed-curve geometry against exact curves.
#include "ehd_capsule/geometry/closed_curve.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ehd_capsule/geometry/gauss_legendre.h"

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

// IntegralWeights: the weights must be the integrals of the cardinal splines (checked against
// fitting each cardinal spline and integrating it with the same Gauss rule), and on uneven knots
// sum_k w_k f(s_k) must converge to the exact integral at fourth order (the trapezoid rule with
// the same knots is second order).
TEST(PeriodicCubicSpline, IntegralWeightsAreTheCardinalIntegralsAndFourthOrder) {
  const double period = 2.0 * M_PI;
  auto knots_for = [&](int n) {
    std::vector<double> s(n);
    for (int k = 0; k < n; ++k) {
      const double u = period * k / n;
      s[k] = u + 0.3 * std::sin(u);  // uneven, increasing (derivative 1 + 0.3 cos u > 0)
    }
    return s;
  };
  auto rho = [](double s) { return 1.0 + 0.5 * std::cos(s); };
  auto f = [](double s) { return std::exp(std::sin(s)) + std::cos(3.0 * s); };
  // exact: integral of (1 + cos(s)/2)(exp(sin s) + cos 3s) = 2 pi I0(1) (the cos terms vanish:
  // cos s exp(sin s) integrates to 0, cos s cos 3s and cos 3s too).
  const double exact = period * std::cyl_bessel_i(0.0, 1.0);
  double err[2], trapezoid_err[2];
  for (int r = 0; r < 2; ++r) {
    const int n = 48 << r;
    const std::vector<double> s = knots_for(n);
    std::vector<double> nodes(n * kGaussPoints);
    for (int k = 0; k < n; ++k) {
      const double h = (k + 1 < n ? s[k + 1] : period) - s[k];
      for (int q = 0; q < kGaussPoints; ++q)
        nodes[k * kGaussPoints + q] = rho(s[k] + kGaussNode[q] * h);
    }
    const std::vector<double> w = PeriodicCubicSpline::IntegralWeights(s, period, nodes);
    if (r == 0) {
      for (int j : {0, 5, n - 1}) {
        std::vector<double> unit(n, 0.0);
        unit[j] = 1.0;
        PeriodicCubicSpline cardinal;
        cardinal.Fit(s, period, unit);
        double integral = 0.0;
        for (int k = 0; k < n; ++k) {
          const double h = (k + 1 < n ? s[k + 1] : period) - s[k];
          for (int q = 0; q < kGaussPoints; ++q) {
            const double x = s[k] + kGaussNode[q] * h;
            integral += kGaussWeight[q] * h * rho(x) * cardinal.Value(x);
          }
        }
        EXPECT_NEAR(w[j], integral, 1e-13) << j;
      }
    }
    double sum = 0.0, trapezoid = 0.0;
    for (int k = 0; k < n; ++k) {
      sum += w[k] * f(s[k]);
      const double left = s[k] - (k > 0 ? s[k - 1] : s[n - 1] - period);
      const double right = (k + 1 < n ? s[k + 1] : period) - s[k];
      trapezoid += 0.5 * (left + right) * rho(s[k]) * f(s[k]);
    }
    err[r] = std::abs(sum - exact);
    trapezoid_err[r] = std::abs(trapezoid - exact);
  }
  EXPECT_GT(std::log2(err[0] / err[1]), 3.5);
  EXPECT_LT(err[1], 0.1 * trapezoid_err[1]);
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
