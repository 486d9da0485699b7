// The retracted immersed boundary (issue #42, docs/validation_3d.md "The retracted immersed
// boundary"): the membrane's force is spread and the fluid velocity interpolated at the points
// moved inward along their normals by a distance delta,
//   X_r = X - delta n(X),
// one point set for both operators, so spreading and interpolation stay adjoint (song2019 eqs.
// (104), (106) at X_r). The cosine kernel's 4 h support makes the flow go round a body larger
// than the marker surface (a + 0.7-0.9 h by the stresslet of a nearly rigid sphere, and a
// small-Ca deformation 12-25 % above (25/12) Ca); retracting the points removes most of it
// (Breugem, J. Comput. Phys. 231 (2012) 4469, for direct forcing). delta is calibrated per
// kernel on the exact small-Ca deformation and rotation of a spherical capsule: 0.5 h for the
// cosine kernel (the default), 0.37 h for roma3 (docs/validation_3d.md "The kernel"); with cosine
// the stresslet would need 0.8-1.0 h, which no single adjoint delta reconciles
// (docs/validation_3d.md).
//
// Departure from Breugem (rigid particles, whose velocity is prescribed): a membrane moves with
// the fluid at its own position, not at X_r (the kinematic condition). The velocity at X_r is
// extrapolated to X with the body's best-fit velocity gradient A (least squares over the points
// of U(X_r) = c + A (X_r - mean X_r)):
//   U(X) = U(X_r) + A (X - X_r) = U(X_r) + delta A n,
// exact for the linear interior flow of a tank-treading sphere, cylinder or ellipsoid (A is made
// traceless: the inside is incompressible); without it the membrane tank-treads slower by
// (a - delta) / a. That velocity is not the value of one divergence-free field at the points, so
// its net flux through the membrane is removed (RemoveEnclosedMeasureRate).
#pragma once

#include "ehd_capsule/coupling/body.h"

namespace ehd {

// out = X - distance n at each point (2D: the curve's normal at the marker; 3D: the area-weighted
// vertex normal).
template <int D>
void RetractAlongNormals(const BodyShape<D>& shape, double distance, PointsOf<D>& out);

// U (the velocity at `retracted`) += A (points - retracted), A the least-squares gradient of U
// over the retracted points. Throws std::invalid_argument when the points do not span D
// dimensions.
template <int D>
void ExtrapolateToPoints(const PointsOf<D>& retracted, const PointsOf<D>& points, PointsOf<D>& U);

// U -= c g with g the gradient of the enclosed area (2D polygon) or volume (3D) with respect to
// the points and c such that sum_k g_k . U_k = 0: the smallest change (least squares) that makes
// the points' motion keep the enclosed measure to first order. The membrane is impermeable and
// the inside incompressible, but U(X_r) + delta A n is not the velocity of one divergence-free
// field at the points, and without this the enclosed area leaks (2D drop in shear: -0.25 % per
// unit of time at a = 16, delta = 0.5 h; docs/validation_3d.md).
template <int D>
void RemoveEnclosedMeasureRate(const BodyShape<D>& shape, PointsOf<D>& U);

}  // namespace ehd
