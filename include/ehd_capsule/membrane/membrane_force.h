// Force density that a 2D membrane with tension T = tau t + q n exerts on the fluid.
//
// song2019 eq. (110) (Pozrikidis): with arc length l, counter-clockwise unit tangent t, outward
// normal n and curvature kappa (> 0 on a circle) the Frenet-Serret formulas are
//   dt/dl = -kappa n,   dn/dl = kappa t,
// and the load on the membrane balanced by the hydrodynamic traction jump is
//   f_(110) = -d(tau t + q n)/dl = (kappa tau - dq/dl) n - (dtau/dl + kappa q) t.
// The force the membrane exerts on the fluid (the one spread by eq. (106)) is its negative:
//   f = d(tau t + q n)/dl = (dq/dl - kappa tau) n + (dtau/dl + kappa q) t.
// Check: a uniformly stretched circle (tau > 0, q = 0) pulls the fluid inward, f = -(tau/r) n;
// a drop (tau = gamma) gives the Laplace load -gamma kappa n. (The text's eq. (110) is the
// traction-jump convention; using it as the spread force would push the fluid outward.)
// Derivatives: dtau/dl and tau at markers from segment tensions by the staggered 4-point stencil,
// q and dq/dl from BendingTension; see arc_length_stencil.h.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/curve_segments.h"
#include "ehd_capsule/membrane/arc_length_stencil.h"

namespace ehd {

// Marker geometry of a curve (spline tangent, normal, curvature at the knots). orientation is +1
// if the markers run counter-clockwise, -1 otherwise: stencil derivatives follow the marker
// order, so d/dl along the counter-clockwise tangent is orientation * (stencil first derivative).
struct MarkerFrames {
  Eigen::Matrix2Xd tangent, normal;
  std::vector<double> curvature;
  int orientation = 1;
  void Update(const ClosedCurve& c);
  void Update(const CurveSegments& c);  // same values, no knot search
};

// f (2 x M, resized if needed) from segment tensions tau (size M) and, if q != nullptr, the
// transverse shear tension q and dq/dl at markers, both along the counter-clockwise tangent.
// tau_at_marker (size M) receives tau at markers.
void MembraneForceDensity(const MarkerFrames& frames, const ArcLengthStencil& stencil,
                          const std::vector<double>& segment_tension, const std::vector<double>* q,
                          const std::vector<double>* dq_dl, std::vector<double>& tau_at_marker,
                          Eigen::Matrix2Xd& force_density);

}  // namespace ehd
