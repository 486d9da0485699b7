// First-order (small-deformation) response of the 2D Hookean membrane, tau = E_s (lambda - 1)
// (song2019 eq. (113)), f = d(tau t)/dl (eq. (110), sign of membrane_force.h).
//
// These tests pin down why a 2D Hookean capsule without prestress deforms as D ~ Ca^(1/3) in
// shear (docs/validation_fsi.md):
//  1. an imposed non-uniform tangential stretch lambda = 1 + 2 delta cos 2 phi on a circle gives
//     the first-order force  f_t = dtau/dl = -(4 E_s delta / r) sin 2 phi,
//     f_n = -kappa tau = -(2 E_s delta / r) cos 2 phi  (the force terms are right);
//  2. but the shape mode of shear, circle -> ellipse with D = eps, needs no first-order stretch
//     when the membrane material slides along the curve: an ellipse of the same area with its
//     markers at equal arc length has uniform lambda = P_ellipse / P_circle = 1 + (3/4) eps^2 +
//     O(eps^4) (P = 2 pi r (1 + D^2/4) / sqrt(1 - D^2) at fixed area), so its force is
//     (3/4) E_s eps^2 kappa, second order, whereas the affine (material) ellipse has
//     lambda - 1 = -eps cos 2 phi and a first-order force 2 E_s eps / r. A tank-treading capsule
//     reaches the equal-arc state, so the restoring tension is tau_0 = (3/4) E_s D^2 and the
//     Taylor balance D ~ mu k a / tau_0 gives D^3 ~ Ca.
#include <gtest/gtest.h>

#include <cmath>

#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/membrane/membrane_model.h"

namespace ehd {
namespace {

double MaxForce(const Eigen::Matrix2Xd& f) {
  double m = 0.0;
  for (Eigen::Index k = 0; k < f.cols(); ++k) m = std::max(m, std::hypot(f(0, k), f(1, k)));
  return m;
}

TEST(MembraneFirstOrder, TangentialStretchWaveGivesFirstOrderForce) {
  const int markers = 128;
  const double r = 10.0, es = 0.7;
  MembraneModel model({0.0, es, 0.0, 0.0}, ClosedCurve(CircleMarkers(markers, r)));
  for (double delta : {1e-3, 2e-3}) {
    // Markers slid along the same circle: theta_k = phi_k + delta sin 2 phi_k, so the stretch is
    // dtheta/dphi = 1 + 2 delta cos 2 phi and the shape is unchanged.
    Eigen::Matrix2Xd x(2, markers);
    for (int k = 0; k < markers; ++k) {
      const double phi = 2.0 * M_PI * k / markers;
      const double theta = phi + delta * std::sin(2.0 * phi);
      x.col(k) << r * std::cos(theta), r * std::sin(theta);
    }
    const ClosedCurve curve(x);
    Eigen::Matrix2Xd f;
    model.ComputeForce(curve, 1.0, f);
    const double scale = 4.0 * es * delta / r;  // amplitude of f_t
    double max_error = 0.0;
    for (int k = 0; k < markers; ++k) {
      const double phi = 2.0 * M_PI * k / markers;
      const CurvePoint p = curve.AtMarker(k);
      const double ft = f.col(k).dot(p.tangent), fn = f.col(k).dot(p.normal);
      max_error = std::max(max_error, std::abs(ft + scale * std::sin(2.0 * phi)));
      max_error = std::max(max_error, std::abs(fn + 0.5 * scale * std::cos(2.0 * phi)));
    }
    // Neglected: O(delta^2) terms (relative 2 delta) and the discrete derivative of the segment
    // stretch (relative O(dphi^2) = 2.4e-3); 2% of the amplitude bounds both.
    EXPECT_LT(max_error, 0.02 * scale) << "delta " << delta;
  }
}

TEST(MembraneFirstOrder, SlidingEllipseModeCostsOnlySecondOrderForce) {
  const int markers = 128;
  const double r = 10.0, es = 0.7;
  MembraneModel sliding({0.0, es, 0.0, 0.0}, ClosedCurve(CircleMarkers(markers, r)));
  MembraneModel affine({0.0, es, 0.0, 0.0}, ClosedCurve(CircleMarkers(markers, r)));
  double previous_sliding = 0.0, previous_affine = 0.0;
  for (double eps : {0.04, 0.02}) {
    // Same area as the circle: A B = r^2; D = (A - B) / (A + B) = eps + O(eps^2).
    const double a = r * (1.0 + eps), b = r / (1.0 + eps);
    Eigen::Matrix2Xd f;
    // Equal arc length markers (the sliding state) and markers at t_k = 2 pi k / M (the affine
    // image of the reference circle's material points).
    sliding.ComputeForce(ClosedCurve(EllipseMarkers(markers, a, b)), 1.0, f);
    const double f_sliding = MaxForce(f) * r / es;
    affine.ComputeForce(ClosedCurve(EllipseMarkers(markers, a, b, Eigen::Vector2d::Zero(), 0.0,
                                                   MarkerSpacing::kUniformParameter)),
                        1.0, f);
    const double f_affine = MaxForce(f) * r / es;
    // Sliding: (3/4) eps^2 kappa_max r with kappa_max r = (A/B^2) r ~ 1 + 3 eps: below 1.2 eps^2.
    // Affine: |lambda - 1| up to eps gives f r / E_s ~ 2 eps: above eps.
    EXPECT_LT(f_sliding, 1.2 * eps * eps) << eps;
    EXPECT_GT(f_sliding, 0.5 * eps * eps) << eps;  // the second-order tension is there
    EXPECT_GT(f_affine, eps) << eps;
    if (previous_sliding > 0.0) {
      // Halving eps divides the sliding force by ~4 (second order), the affine one by ~2.
      EXPECT_NEAR(previous_sliding / f_sliding, 4.0, 0.6);
      EXPECT_NEAR(previous_affine / f_affine, 2.0, 0.3);
    }
    previous_sliding = f_sliding;
    previous_affine = f_affine;
  }
}

}  // namespace
}  // namespace ehd
