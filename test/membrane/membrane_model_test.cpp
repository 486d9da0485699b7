// 2D membrane forces, song2019 sec. 3.3 eqs. (110)-(116): exact cases (stretched circle, drop,
// Kelvin-Voigt with a known stretch rate), force-free reference shapes, global balance (zero net
// force and torque), bending against the analytic curvature derivatives of an ellipse.
#include "ehd_capsule/membrane/membrane_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {
namespace {

// sqrt(sum f^2) by a plain loop (Eigen's vectorised reduction trips a GCC 12
// -Wmaybe-uninitialized false positive under -march=native).
double FrobeniusNorm(const Eigen::Matrix2Xd& f) {
  double s = 0.0;
  for (Eigen::Index k = 0; k < f.cols(); ++k) s += f(0, k) * f(0, k) + f(1, k) * f(1, k);
  return std::sqrt(s);
}

// Net force and torque (about the origin) of a force density integrated with the arc elements.
struct Balance {
  double force = 0.0, torque = 0.0, magnitude = 0.0, arm = 0.0;
};
Balance Integrate(const ClosedCurve& c, const Eigen::Matrix2Xd& f) {
  Balance b;
  Eigen::Vector2d net = Eigen::Vector2d::Zero();
  for (int k = 0; k < c.size(); ++k) {
    const double dl =
        0.5 * (c.SegmentArcLength((k + c.size() - 1) % c.size()) + c.SegmentArcLength(k));
    const Eigen::Vector2d x = c.markers().col(k);
    net += f.col(k) * dl;
    b.torque += (x.x() * f(1, k) - x.y() * f(0, k)) * dl;
    b.magnitude += f.col(k).norm() * dl;
    b.arm = std::max(b.arm, x.norm());
  }
  b.force = net.norm();
  return b;
}

TEST(MembraneModel, UniformlyStretchedCirclePullsInward) {
  // Hookean tau = E_s (lambda - 1) uniform on a circle: dtau/dl = 0 and f = -kappa tau n,
  // |f| = E_s (lambda - 1) / r pointing to the centre (membrane_force.h sign check).
  const double r0 = 5.0, lambda = 1.2, es = 0.3;
  const Eigen::Vector2d centre(1.0, -2.0);
  MembraneModel model({0.0, es, 0.0, 0.0}, ClosedCurve(CircleMarkers(64, r0, centre)));
  const ClosedCurve stretched(CircleMarkers(64, lambda * r0, centre));
  Eigen::Matrix2Xd f;
  model.ComputeForce(stretched, 1.0, f);
  // The chord-length periodic cubic spline through M equally spaced circle markers has knot
  // curvature (1/r)(1 + dtheta^2/12 + O(dtheta^4)), dtheta = 2 pi / M (observed, ~8e-4 at M = 64):
  // that is the only error, the force uses it exactly.
  const double expected = es * (lambda - 1.0) / (lambda * r0);
  const double dtheta = 2.0 * M_PI / 64;
  for (int k = 0; k < 64; ++k) {
    const Eigen::Vector2d inward = -(stretched.markers().col(k) - centre).normalized();
    const double kappa = stretched.AtMarker(k).curvature;
    EXPECT_NEAR(f.col(k).dot(inward), es * (lambda - 1.0) * kappa, 1e-12) << k;
    EXPECT_NEAR(f.col(k).norm(), expected, dtheta * dtheta / 10.0 * expected) << k;
    EXPECT_NEAR(model.tension()[k], es * (lambda - 1.0), 1e-12);
    EXPECT_NEAR(model.stretch()[k], lambda, 1e-12);
  }
}

TEST(MembraneModel, InterfacialTensionOfACircleIsLaplace) {
  // Drop: tau = gamma, f = -gamma kappa n = -(gamma / r) n.
  const double r = 7.0, gamma = 0.05;
  MembraneModel model({gamma, 0.0, 0.0, 0.0}, ClosedCurve(CircleMarkers(80, r)));
  const ClosedCurve c(CircleMarkers(80, r));
  Eigen::Matrix2Xd f;
  model.ComputeForce(c, 1.0, f);
  const double dtheta = 2.0 * M_PI / 80;  // spline curvature error, see the stretched circle
  for (int k = 0; k < 80; ++k) {
    const Eigen::Vector2d n = c.markers().col(k).normalized();
    EXPECT_NEAR((f.col(k) + gamma / r * n).norm(), 0.0, dtheta * dtheta / 10.0 * gamma / r);
  }
  EXPECT_EQ(model.Describe(), "interfacial tension(gamma=0.05)");
}

TEST(MembraneModel, ReferenceShapeIsForceFree) {
  // lambda = 1, kappa = kappa_0, lambda_dot = 0 on the reference shape: every term vanishes
  // identically (eqs. (113)-(115)), for any reference shape, whatever the marker spacing.
  for (const Eigen::Matrix2Xd& x :
       {BiconcaveMarkers(96), EllipseMarkers(64, 3.0, 1.0, Eigen::Vector2d(2, 1), 0.4),
        BiconcaveMarkers(70, {}, Eigen::Vector2d::Zero(), 0.0, MarkerSpacing::kUniformParameter)}) {
    const ClosedCurve c(x);
    MembraneModel model({0.0, 1.0, 2.0, 0.5}, c);
    EXPECT_EQ(model.Describe(), "Hookean(E_s=1) + Kelvin-Voigt(mu_s=2) + bending(E_B=0.5)");
    Eigen::Matrix2Xd f;
    for (int step = 0; step < 3; ++step) {
      model.ComputeForce(c, 0.5, f);
      EXPECT_LT(FrobeniusNorm(f), 1e-12);
    }
  }
}

TEST(MembraneModel, NetForceAndTorqueVanishOnAClosedMembrane) {
  // f = d(tau t + q n)/dl is a total derivative, so oint f dl = 0, and
  // oint x cross f dl = [x cross T] - oint t cross (tau t + q n) dl = -oint q dl = 0 (q is itself a
  // derivative). Discretely both hold to truncation error, which must shrink with M. The
  // deformed shape and the reference spacing have no symmetry (which would cancel them exactly).
  double previous_ratio = 1.0;
  for (int m : {64, 128, 256}) {
    const ClosedCurve reference(
        BiconcaveMarkers(m, {}, Eigen::Vector2d::Zero(), 0.0, MarkerSpacing::kUniformParameter));
    MembraneModel model({0.01, 1.0, 0.0, 0.2}, reference);
    Eigen::Matrix2Xd x = EllipseMarkers(m, 1.6, 0.7, Eigen::Vector2d(0.3, -0.2), 0.5);
    for (int k = 0; k < m; ++k) {
      const double th = 2.0 * M_PI * k / m;
      x.col(k) += 0.08 * Eigen::Vector2d(std::cos(3 * th + 0.3), std::sin(2 * th + 1.0));
    }
    const ClosedCurve deformed(x);
    Eigen::Matrix2Xd f;
    model.ComputeForce(deformed, 1.0, f);
    const Balance b = Integrate(deformed, f);
    const double ratio = std::max(b.force, std::abs(b.torque) / b.arm) / b.magnitude;
    std::printf("balance M=%d force %.3e torque %.3e ratio %.3e\n", m, b.force, b.torque, ratio);
    EXPECT_LT(ratio, 2e-3) << m;
    EXPECT_LT(ratio, 0.5 * previous_ratio) << m;  // converges with the marker spacing
    previous_ratio = ratio;
  }
}

TEST(MembraneModel, MarkerOrderDoesNotChangeTheForce) {
  // The physics does not depend on the direction in which the markers are numbered: reversing
  // the order of both reference and deformed markers gives the same force at each point.
  const int m = 96;
  const Eigen::Matrix2Xd ref =
      BiconcaveMarkers(m, {}, Eigen::Vector2d::Zero(), 0.0, MarkerSpacing::kUniformParameter);
  Eigen::Matrix2Xd def = EllipseMarkers(m, 1.5, 0.8, Eigen::Vector2d(0.1, 0.2), 0.3);
  for (int k = 0; k < m; ++k) def(0, k) += 0.05 * std::sin(3.0 * 2.0 * M_PI * k / m);
  const Eigen::Matrix2Xd ref_rev = ref.rowwise().reverse(), def_rev = def.rowwise().reverse();
  MembraneModel ccw({0.01, 1.0, 0.0, 0.1}, ClosedCurve(ref));
  MembraneModel cw({0.01, 1.0, 0.0, 0.1}, ClosedCurve(ref_rev));
  Eigen::Matrix2Xd f, f_rev;
  ccw.ComputeForce(ClosedCurve(def), 1.0, f);
  cw.ComputeForce(ClosedCurve(def_rev), 1.0, f_rev);
  double scale = 0.0, diff = 0.0;
  for (int k = 0; k < m; ++k) {
    scale = std::max(scale, f.col(k).norm());
    diff = std::max(diff, (f.col(k) - f_rev.col(m - 1 - k)).norm());
  }
  EXPECT_LT(diff, 1e-10 * scale);
}

TEST(MembraneModel, CircleWithReferenceCurvatureHasNoBendingForce) {
  // kappa - kappa_0 is constant on any circle (1/r - 1/r_0), so q = E_B d(kappa - kappa_0)/dl = 0.
  const ClosedCurve reference(CircleMarkers(64, 4.0));
  MembraneModel model({0.0, 0.0, 0.0, 1.0}, reference);
  EXPECT_EQ(model.Describe(), "bending(E_B=1)");
  Eigen::Matrix2Xd f;
  model.ComputeForce(ClosedCurve(CircleMarkers(64, 4.0, Eigen::Vector2d(1, 1))), 1.0, f);
  EXPECT_LT(FrobeniusNorm(f), 1e-10);
  model.ComputeForce(ClosedCurve(CircleMarkers(64, 5.0)), 1.0, f);
  EXPECT_LT(FrobeniusNorm(f), 1e-8);
}

// Analytic curvature of (a cos t, b sin t) and its arc-length derivatives: with
// W = a^2 sin^2 t + b^2 cos^2 t, dl/dt = sqrt(W), kappa = a b W^(-3/2),
// dkappa/dl = -(3/2) a b W^(-3) W',  d2kappa/dl2 = -(3/2) a b (W'' W^(-3) - 3 W'^2 W^(-4))
// W^(-1/2), W' = (a^2 - b^2) sin 2t, W'' = 2 (a^2 - b^2) cos 2t.
struct EllipseCurvature {
  double kappa, d1, d2;
};
EllipseCurvature AnalyticEllipse(double a, double b, double t) {
  const double s = std::sin(t), c = std::cos(t);
  const double w = a * a * s * s + b * b * c * c;
  const double w1 = (a * a - b * b) * std::sin(2 * t), w2 = 2 * (a * a - b * b) * std::cos(2 * t);
  return {a * b * std::pow(w, -1.5), -1.5 * a * b * w1 / (w * w * w),
          -1.5 * a * b * (w2 / (w * w * w) - 3.0 * w1 * w1 / (w * w * w * w)) / std::sqrt(w)};
}

TEST(MembraneModel, BendingOfAnEllipseTowardsItsReferenceCircle) {
  // Reference circle (kappa_0 = 1/r constant) deformed to an ellipse a > b: the bending force
  // f = (dq/dl) n + kappa q t with q = E_B dkappa/dl. At the tips (kappa maximal, kappa'' < 0) it
  // pushes inward, at the flat sides outward: it rounds the shape. Against the analytic ellipse
  // the error decreases at (at least) second order in the marker spacing: the spline curvature
  // at the knots is O(dl^2) accurate and the 5-point derivatives are O(dl^3) or better.
  const double a = 2.0, b = 1.0, eb = 0.1;
  double previous = 0.0;
  for (int m : {64, 128, 256}) {
    const ClosedCurve reference(CircleMarkers(m, std::sqrt(a * b)));
    MembraneModel model({0.0, 0.0, 0.0, eb}, reference);
    const ClosedCurve ellipse(EllipseMarkers(m, a, b));
    Eigen::Matrix2Xd f;
    model.ComputeForce(ellipse, 1.0, f);
    double error = 0.0, scale = 0.0;
    for (int k = 0; k < m; ++k) {
      const Eigen::Vector2d x = ellipse.markers().col(k);
      const double t = std::atan2(x.y() / b, x.x() / a);
      const EllipseCurvature e = AnalyticEllipse(a, b, t);
      const CurvePoint p = ellipse.AtMarker(k);
      const Eigen::Vector2d exact = eb * e.d2 * p.normal + e.kappa * eb * e.d1 * p.tangent;
      error = std::max(error, (f.col(k) - exact).norm());
      scale = std::max(scale, exact.norm());
    }
    // Direction at the tip (marker 0, (a, 0)) and at the top flat side (marker m/4, (0, b)).
    EXPECT_LT(f.col(0).dot(ellipse.AtMarker(0).normal), 0.0);
    EXPECT_GT(f.col(m / 4).dot(ellipse.AtMarker(m / 4).normal), 0.0);
    // Observed orders 1.57 (64 -> 128) and 1.95 (128 -> 256): second order once resolved.
    if (previous > 0.0) {
      EXPECT_GT(std::log2(previous / error), m == 128 ? 1.4 : 1.8) << m;
    }
    if (m == 256) {
      EXPECT_LT(error, 0.01 * scale);
    }
    std::printf("bending M=%d max error %.3e (scale %.3e)\n", m, error, scale);
    previous = error;
  }
}

TEST(MembraneModel, KelvinVoigtTensionFromAKnownStretchRate) {
  // A circle inflating linearly, r(t) = r0 (1 + alpha t): lambda = 1 + alpha t on every segment,
  // so the one-sided second-order difference is exact, lambda_dot = alpha, and eq. (114) gives
  // tau_v = mu_s alpha / lambda; the force is -tau_v / r n. The first step (first-order
  // difference from the reference lambda = 1) is exact for linear lambda too.
  const double r0 = 3.0, alpha = 0.02, dt = 0.5, mu_s = 4.0;
  MembraneModel model({0.0, 0.0, mu_s, 0.0}, ClosedCurve(CircleMarkers(48, r0)));
  Eigen::Matrix2Xd f;
  for (int n = 1; n <= 4; ++n) {
    const double lambda = 1.0 + alpha * n * dt;
    const ClosedCurve c(CircleMarkers(48, r0 * lambda));
    model.ComputeForce(c, dt, f);
    for (int k = 0; k < 48; ++k) {
      EXPECT_NEAR(model.segment_tension()[k], mu_s * alpha / lambda, 1e-10) << n;
      const Eigen::Vector2d n_out = c.markers().col(k).normalized();
      // Spline curvature error (1 + dtheta^2/12), as for the stretched circle.
      const double fn = -mu_s * alpha / lambda / (r0 * lambda), dtheta = 2.0 * M_PI / 48;
      EXPECT_NEAR(f.col(k).dot(n_out), fn, dtheta * dtheta / 10.0 * std::abs(fn)) << n;
    }
  }
  EXPECT_THROW(model.ComputeForce(ClosedCurve(CircleMarkers(48, r0)), 0.0, f),
               std::invalid_argument);
}

TEST(MembraneModel, StabilityLimitsScaleLikeStokesRelaxation) {
  // sigma = S k^(p-1) phi_hat(k h)^2 / (4 mu): dt_max scales as mu h / gamma for tension and
  // elasticity and mu h^3 / E_B for bending (scale the grid and the markers together), and
  // inversely with each coefficient. A term that is off gives no limit.
  const ClosedCurve c(CircleMarkers(64, 10.0));
  const ClosedCurve c2(CircleMarkers(64, 20.0));
  MembraneModel model({0.0, 0.01, 0.5, 0.002}, c);
  const MembraneStabilityLimits l1 = model.Stability(c, 0.1, 1.0);
  const MembraneStabilityLimits l2 =
      MembraneModel({0.0, 0.01, 0.5, 0.002}, c2).Stability(c2, 0.1, 2.0);
  EXPECT_TRUE(std::isinf(l1.tension_dt));
  EXPECT_NEAR(l2.elastic_dt / l1.elastic_dt, 2.0, 1e-9);
  EXPECT_NEAR(l2.bending_dt / l1.bending_dt, 8.0, 1e-9);
  EXPECT_NEAR(model.Stability(c, 0.2, 1.0).elastic_dt / l1.elastic_dt, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(model.StableTimeStep(c, 0.1), std::min(l1.elastic_dt, l1.bending_dt));
  // The cosine kernel filters the grid scale: max_k k phi_hat(k)^2 = 0.586 / h when markers are
  // finer than the grid, so the elastic limit is ~ 4 mu h / (0.586 E_s).
  EXPECT_NEAR(l1.elastic_dt * 0.01 / (4 * 0.1), 1.0 / 0.586, 0.01);
  EXPECT_NEAR(CosineDeltaTransform(0.0), 1.0, 1e-15);
  EXPECT_NEAR(CosineDeltaTransform(M_PI_2), 0.5, 1e-7);
  EXPECT_NEAR(CosineDeltaTransform(M_PI), 0.0, 1e-15);
}

TEST(MembraneModel, RejectsBadInput) {
  const ClosedCurve c(CircleMarkers(16, 2.0));
  EXPECT_THROW(MembraneModel({0.0, -1.0, 0.0, 0.0}, c), std::invalid_argument);
  MembraneModel model({0.0, 1.0, 0.0, 0.0}, c);
  Eigen::Matrix2Xd f;
  EXPECT_THROW(model.ComputeForce(ClosedCurve(CircleMarkers(17, 2.0)), 1.0, f),
               std::invalid_argument);
  EXPECT_EQ(MembraneModel({}, c).Describe(), "none");
}

}  // namespace
}  // namespace ehd
