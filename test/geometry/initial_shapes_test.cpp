// Initial shapes: counter-clockwise markers, equal spacing, and the enclosed area and perimeter
// against closed forms (circle, ellipse, song2019 eq. (152) biconcave profile).
#include "ehd_capsule/geometry/initial_shapes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ehd_capsule/geometry/closed_curve.h"

namespace ehd {
namespace {

TEST(InitialShapes, CircleIsCounterClockwiseWithExactRadius) {
  const Eigen::Vector2d centre(1.5, -2.0);
  const Eigen::Matrix2Xd x = CircleMarkers(40, 2.5, centre);
  const ClosedCurve c(x);
  EXPECT_EQ(c.orientation(), 1);
  for (int k = 0; k < 40; ++k) EXPECT_NEAR((x.col(k) - centre).norm(), 2.5, 1e-14);
  EXPECT_NEAR(c.Area(), M_PI * 2.5 * 2.5, 1e-4 * M_PI * 6.25);  // spline of 40 markers
  EXPECT_THROW(CircleMarkers(2, 1.0), std::invalid_argument);
  EXPECT_THROW(CircleMarkers(10, -1.0), std::invalid_argument);
}

TEST(InitialShapes, EllipseEqualArcLengthAndClosedForms) {
  // Area pi a b exactly; perimeter from Ramanujan's second approximation, relative error
  // ~3 h^5 / 2^17 with h = ((a-b)/(a+b))^2, far below the tolerance.
  const double a = 3.0, b = 1.5, angle = 0.4;
  const Eigen::Matrix2Xd x = EllipseMarkers(128, a, b, Eigen::Vector2d(0.5, 0.25), angle);
  const ClosedCurve c(x);
  EXPECT_EQ(c.orientation(), 1);
  EXPECT_NEAR(c.Area(), M_PI * a * b, 1e-6 * M_PI * a * b);
  const double h = std::pow((a - b) / (a + b), 2);
  const double perimeter = M_PI * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
  EXPECT_NEAR(c.ArcLength(), perimeter, 1e-6 * perimeter);
  // Equal arc-length spacing: every spline segment is perimeter / M.
  for (int k = 0; k < 128; ++k) EXPECT_NEAR(c.SegmentArcLength(k), perimeter / 128, 1e-6);
  // Marker 0 is the end of the rotated a axis.
  EXPECT_NEAR(x(0, 0), 0.5 + a * std::cos(angle), 1e-12);
  EXPECT_NEAR(x(1, 0), 0.25 + a * std::sin(angle), 1e-12);
}

TEST(InitialShapes, BiconcaveAreaAndPerimeterMatchTheParametricForm) {
  // eq. (152): the area has the closed form (pi a^2 alpha^2/2)(c0 + c1/4 + c2/8) = 0.5448 pi a^2
  // (equivalent diameter 1.48 a as quoted in sec. 5.3). The perimeter has no closed form; it is
  // computed here independently by the trapezoid rule (spectrally accurate for a smooth periodic
  // integrand) on the analytic derivative of eq. (152).
  const BiconcaveParameters p;
  const double area = BiconcaveArea(p);
  EXPECT_NEAR(area, 0.5 * M_PI * 1.3858 * 1.3858 * (0.207 + 2.003 / 4 - 1.123 / 8), 1e-14);
  EXPECT_NEAR(2.0 * std::sqrt(area / M_PI), 1.48, 0.01);
  const int n = 20000;
  double perimeter = 0.0;
  for (int i = 0; i < n; ++i) {
    const double chi = 2.0 * M_PI * i / n;
    const double s = std::sin(chi), co = std::cos(chi);
    const double g = p.c0 + p.c1 * s * s + p.c2 * s * s * s * s;
    const double dg = (2.0 * p.c1 * s + 4.0 * p.c2 * s * s * s) * co;
    const double dx = p.alpha * co, dy = 0.5 * p.alpha * (dg * co - g * s);
    perimeter += std::hypot(dx, dy) * 2.0 * M_PI / n;
  }
  const ClosedCurve c(BiconcaveMarkers(256, p));
  EXPECT_EQ(c.orientation(), 1);
  EXPECT_NEAR(c.Area(), area, 1e-6 * area);
  EXPECT_NEAR(c.ArcLength(), perimeter, 1e-6 * perimeter);
  // Dimples: the profile is thinner on the axis than at its thickest (biconcave).
  const Eigen::Matrix2Xd x = BiconcaveMarkers(256, p);
  EXPECT_NEAR(x(0, 0), p.alpha, 1e-12);               // marker 0 at the right-most point
  EXPECT_NEAR(x(1, 64), 0.5 * p.alpha * p.c0, 2e-3);  // top of the dimple at x ~ 0
  double top = 0.0;
  for (int k = 0; k < 256; ++k) top = std::max(top, x(1, k));
  EXPECT_GT(top, 2.0 * x(1, 64));
  // Uniform-parameter spacing gives the same curve.
  const ClosedCurve cu(
      BiconcaveMarkers(256, p, Eigen::Vector2d::Zero(), 0.0, MarkerSpacing::kUniformParameter));
  EXPECT_NEAR(cu.Area(), area, 1e-5 * area);
}

}  // namespace
}  // namespace ehd
