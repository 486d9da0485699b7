// Shape diagnostics (song2019 sec. 4.1, eq. (151)) and the tank-treading / tumbling tracker.
#include "ehd_capsule/diagnostics/shape_diagnostics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ehd_capsule/diagnostics/tank_treading.h"
#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {
namespace {

TEST(MeasureShape, CircleHasZeroDeformationAndExactArea) {
  // A circle of radius r: D = 0, area pi r^2, length 2 pi r, centroid at its centre; the
  // equivalent ellipse is the circle itself (L = B = 2r).
  const Eigen::Vector2d centre(3.0, -1.0);
  const ShapeDiagnostics d = MeasureShape(ClosedCurve(CircleMarkers(96, 2.0, centre)));
  EXPECT_NEAR(d.dxy, 0.0, 1e-6);
  EXPECT_NEAR(d.area, 4.0 * M_PI, 1e-5);
  EXPECT_NEAR(d.length, 4.0 * M_PI, 1e-5);
  EXPECT_NEAR((d.centroid - centre).norm(), 0.0, 1e-10);
  EXPECT_NEAR(d.major_axis, 4.0, 1e-5);
  EXPECT_NEAR(d.minor_axis, 4.0, 1e-5);
}

TEST(MeasureShape, RotatedEllipseGivesTaylorDeformationAndInclination) {
  // An ellipse is its own equivalent ellipse: D = (a - b)/(a + b), theta = rotation angle
  // (mapped into (-pi/2, pi/2]), L = 2a, B = 2b, to spline accuracy.
  const double a = 2.0, b = 1.2;
  for (double angle : {0.0, 0.3, -0.7, 1.2, 2.0, M_PI_2}) {
    const ClosedCurve c(EllipseMarkers(128, a, b, Eigen::Vector2d(0.4, 0.1), angle));
    const ShapeDiagnostics d = MeasureShape(c);
    double expected = std::remainder(angle, M_PI);  // in [-pi/2, pi/2]
    if (expected <= -M_PI_2) expected += M_PI;
    EXPECT_NEAR(d.dxy, (a - b) / (a + b), 1e-6) << angle;
    EXPECT_NEAR(d.inclination, expected, 1e-6) << angle;
    EXPECT_NEAR(d.major_axis, 2.0 * a, 1e-5);
    EXPECT_NEAR(d.minor_axis, 2.0 * b, 1e-5);
    EXPECT_NEAR(d.area, M_PI * a * b, 1e-5);
    EXPECT_NEAR((d.centroid - Eigen::Vector2d(0.4, 0.1)).norm(), 0.0, 1e-9);
  }
  // Clockwise markers give the same measures.
  Eigen::Matrix2Xd x = EllipseMarkers(128, a, b, Eigen::Vector2d::Zero(), 0.3);
  const Eigen::Matrix2Xd reversed = x.rowwise().reverse();
  const ShapeDiagnostics d = MeasureShape(ClosedCurve(reversed));
  EXPECT_NEAR(d.dxy, (a - b) / (a + b), 1e-6);
  EXPECT_NEAR(d.inclination, 0.3, 1e-6);
  EXPECT_NEAR(RelativeAreaDrift(d.area * 1.01, d.area), 0.01, 1e-14);
  EXPECT_THROW(RelativeAreaDrift(1.0, 0.0), std::invalid_argument);
}

TEST(TankTreadingTracker, RigidRotationGivesPeriodAndFrequency) {
  // Markers rotating rigidly clockwise at the shear flow's vorticity rate k/2 (what a rigid
  // circle does in u = (k y, 0)): T = 4 pi / k, so the normalised frequency f = 4 pi/(k T) = 1.
  const double k = 0.05, omega = -0.5 * k, dt = 0.7;
  const Eigen::Vector2d centre(1.0, 2.0);
  const Eigen::Matrix2Xd x0 = CircleMarkers(32, 3.0, Eigen::Vector2d::Zero());
  TankTreadingTracker tracker(5);
  double t = 0.0;
  for (int n = 0; n < 2000; ++n, t += dt) {
    const double phi = omega * t;
    Eigen::Matrix2d rot;
    rot << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
    Eigen::Matrix2Xd x = rot * x0;
    x.colwise() += centre;
    tracker.Update(t, x, centre);
  }
  const double initial = 2.0 * M_PI * 5 / 32;
  EXPECT_NEAR(tracker.phase(), initial + omega * (t - dt), 1e-9);
  EXPECT_EQ(tracker.revolutions(), -static_cast<int>(std::abs(omega) * (t - dt) / (2 * M_PI)));
  EXPECT_NEAR(tracker.period(), 4.0 * M_PI / k, 1e-6);  // linear crossing interpolation of a
  EXPECT_NEAR(tracker.frequency(k), 1.0, 1e-6);         // linear phase is exact
  EXPECT_NEAR(tracker.mean_angular_speed(), omega, 1e-12);
  EXPECT_FALSE(tracker.tumbling());
}

TEST(TankTreadingTracker, TumblingWhenInclinationPassesMinusHalfPi) {
  // theta(t) = 0.3 - 0.1 t folded into (-pi/2, pi/2] as MeasureShape reports it: the unwrapped
  // angle decreases through -pi/2 at t = (0.3 + pi/2)/0.1 ~ 18.7 (tumbling, clockwise for k > 0);
  // an oscillating angle that stays inside (tank-treading with swinging) is not tumbling.
  TankTreadingTracker tumbling, swinging;
  const Eigen::Matrix2Xd x = CircleMarkers(8, 1.0);
  for (int n = 0; n <= 400; ++n) {
    const double t = 0.1 * n;
    double theta = std::remainder(0.3 - 0.1 * t, M_PI);
    if (theta <= -M_PI_2) theta += M_PI;
    tumbling.Update(t, x, Eigen::Vector2d::Zero(), theta);
    swinging.Update(t, x, Eigen::Vector2d::Zero(), 0.2 + 0.3 * std::sin(t));
    if (t < 18.6) {
      EXPECT_FALSE(tumbling.tumbling()) << t;
    }
    if (t > 18.8) {
      EXPECT_TRUE(tumbling.tumbling()) << t;
    }
  }
  EXPECT_NEAR(tumbling.unwrapped_inclination(), 0.3 - 4.0, 1e-12);
  EXPECT_EQ(tumbling.flips(), 1);  // |theta| = 3.7 < 3 pi / 2
  EXPECT_FALSE(swinging.tumbling());
  EXPECT_EQ(swinging.flips(), 0);
}

}  // namespace
}  // namespace ehd
