// Self-checks of the boundary-integral reference solver reference/stokes_bie.h (equal viscosities,
// Re = 0), which drives the core MembraneModel force:
//   (1) a circle under uniform tension (drop gamma, or a uniformly stretched Hookean circle) is an
//       equilibrium: oint G . n dl = 0, so the velocity vanishes to quadrature accuracy;
//   (2) a slightly elliptic drop relaxes with the 2D mode-2 rate: for r = a (1 + delta cos 2 phi),
//       the Laplace load on the fluid is f_r = -(3 gamma delta / a) cos 2 phi and the equal-
//       viscosity Stokes solution of a circle with f_r = F cos 2 phi has u_r(a) = F a /(6 mu)
//       (stream functions A r^2 + B r^4 inside, C r^-2 + D outside, continuity of u and the
//       traction jump), so d delta / dt = -gamma delta / (2 mu a);
//   (3) the same balance with the shear's radial velocity (k a / 2) sin 2 phi gives the 2D
//       small-deformation Taylor result for viscosity ratio 1: D = delta = mu k a / gamma = Ca
//       (c = 1), theta = pi/4 - Ca (radians) to first order (test below).
#include "ehd_capsule/reference/stokes_bie.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {
namespace {

const double kPi = std::acos(-1.0);

void Shape(const bie::CapsuleBem& bem, double* dxy, double* theta) {
  const bie::SpectralShape s = bie::MeasureSpectralShape(bem.layer(), bem.markers());
  *dxy = s.dxy;
  *theta = s.inclination;
}

TEST(StokesBie, CircleUnderUniformTensionDoesNotMove) {
  // Drop: tau = gamma; Hookean: reference radius 1, current radius 1.2 (tau = 0.2 E_s).
  for (int case_id = 0; case_id < 2; ++case_id) {
    MembraneParameters p;
    Eigen::Matrix2Xd reference = CircleMarkers(64, 1.0);
    Eigen::Matrix2Xd current = reference;
    if (case_id == 0) {
      p.tension = 1.0;
    } else {
      p.shear_modulus = 5.0;
      current *= 1.2;
    }
    bie::CapsuleBem bem(p, reference, 1.0, 0.0);
    Eigen::Matrix2Xd u;
    bem.Evaluate(current, u);
    // The force is O(1) (|f| = gamma kappa = 1, resp. 0.2 * 5 / 1.2): velocities of O(1) would be
    // expected from a wrong kernel; the exact answer is 0.
    EXPECT_LT(u.cwiseAbs().maxCoeff(), 1e-11) << "case " << case_id;
  }
}

TEST(StokesBie, EllipticDropRelaxesAtTheMode2Rate) {
  // delta(t) = delta_0 exp(-gamma t / (2 mu a)) (header); gamma = mu = a = 1, t = 0.4.
  const double delta0 = 0.01, t_end = 0.4, dt = 2e-3;
  MembraneParameters p;
  p.tension = 1.0;
  bie::CapsuleBem bem(p, CircleMarkers(64, 1.0), 1.0, 0.0);
  bie::CapsuleBem relaxing(p, EllipseMarkers(64, 1.0 + delta0, 1.0 - delta0), 1.0, 0.0);
  double d0, theta;
  Shape(relaxing, &d0, &theta);
  while (relaxing.time() < t_end - 1e-12) relaxing.Step(dt);
  double d1;
  Shape(relaxing, &d1, &theta);
  const double expected = std::exp(-0.5 * t_end);
  // O(delta) nonlinear and O(dt^2) errors: 1% is well above them and far below a sign or factor
  // error (a wrong sign grows the ellipse; the 3D or straight-interface rates differ by > 20%).
  EXPECT_NEAR(d1 / d0, expected, 0.01 * expected);
}

TEST(StokesBie, DropInShearFollowsTwoDimensionalTaylor) {
  // Ca = mu k a / gamma with mu = k = a = 1. Mode-2 amplitude d = delta exp(-2 i phi_0) obeys
  // dd/dt = -i k a / 2 (strain) - d / (2 Ca) (relaxation, header (2)) - i k d (the vorticity
  // -k/2 turns the mode-2 pattern at 2 x k/2), so at steady state
  //   D = Ca / sqrt(1 + 4 Ca^2),   theta = pi/4 - atan(2 Ca) / 2 = pi/4 - Ca + O(Ca^3),
  // the 2D analogue of Taylor's O(Ca) inclination correction. Nonlinear corrections to D are
  // O(Ca^2). Lagrangian drop markers cluster as the interface tank-treads (spacing ratio 1.6 at
  // t = 0.5) and the spline curvature degrades, so the run stops at t = 0.5, 12 relaxation
  // times 2 Ca. Observed: D/Ca - 1 = -1e-4, +7e-3; theta/pi off by 2e-4, 5e-4 (M = 64).
  for (double ca : {0.02, 0.01}) {
    MembraneParameters p;
    p.tension = 1.0 / ca;
    bie::CapsuleBem bem(p, CircleMarkers(64, 1.0), 1.0, 1.0);
    const double dt = 0.4 * (2 * kPi / 64) * ca;
    while (bem.time() < 0.5 - 1e-12) bem.Step(dt);
    double d, theta;
    Shape(bem, &d, &theta);
    EXPECT_NEAR(d / ca, 1.0 / std::sqrt(1.0 + 4.0 * ca * ca), 0.015) << "Ca " << ca;
    // Tolerance 0.001 pi = 3e-3 rad, well below the O(Ca) correction (0.01-0.02 rad).
    EXPECT_NEAR(theta / kPi, 0.25 - 0.5 * std::atan(2.0 * ca) / kPi, 1e-3) << "Ca " << ca;
  }
}

}  // namespace
}  // namespace ehd
