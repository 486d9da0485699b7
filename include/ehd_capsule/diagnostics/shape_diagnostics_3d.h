// Shape measures of a 3D capsule (triangulated surface): volume, surface area, centroid, and the
// equivalent ellipsoid of the enclosed volume's second-moment tensor.
//
// S = int_V (x - x_c)(x - x_c)^T dV, by the divergence theorem over the tetrahedra (p, a, b, c)
// of each triangle with a reference point p: a tetrahedron with vertices v_0..v_3 has
//   int x x^T dV = (V_t / 20) (sum v_i v_i^T + (sum v_i)(sum v_i)^T).
// An ellipsoid with semi-axes a_i has S = (V/5) diag(a_i^2), so a_i = sqrt(5 lambda_i / V). In
// the shear flow u = (k y, 0, 0) the vorticity axis is z: of the three principal axes, the one
// closest to z is left out, and the Taylor deformation and the inclination are those of the
// other two, in the shear plane (Ramanujan & Pozrikidis 1998; Lac et al. 2004):
//   D_xy = (L - B)/(L + B) (L, B the larger and smaller of the two semi-axes), theta = the angle
//   of the L axis's projection on x-y from +x, in (-pi/2, pi/2].
// The deformation along z (the axis of song2019 ch. 6's field): D_z = (a_z - a_perp)/(a_z +
// a_perp), a_z the semi-axis of the principal axis closest to z, a_perp the mean of the other two
// (> 0: prolate along z, < 0 oblate; Taylor's D for a drop in a field along z).
#pragma once

#include <Eigen/Core>

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

struct ShapeDiagnostics3D {
  double volume = 0, area = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d semi_axes = Eigen::Vector3d::Zero();  // of the equivalent ellipsoid, descending
  double dxy = 0, inclination = 0;                      // in the shear plane x-y
  double dz = 0;                                        // along z
};

ShapeDiagnostics3D MeasureShape3D(const TriangleMesh& mesh);

// Amplitude U of the meridional surface flow u_theta = U sin(theta) cos(theta) about the z axis
// through the centroid (theta the polar angle from +z): the P2 circulation of a drop in a field
// along z (Taylor 1966). Least squares over the vertices, weighted by their areas, of the
// velocities relative to the area-weighted mean (the drift of the drop):
//   U = sum A_i cos(theta_i) (u_i - u_mean).(r_i cos(theta_i) - z) / sum A_i sin^2 cos^2,
// with sin(theta) e_theta = r cos(theta) - z (r the unit radial vector), so no division by
// sin(theta) at the poles. U > 0: the surface flows from the poles to the equator. Units of
// the velocities given. velocity: 3 x V.
double MeasureMeridionalFlow(const TriangleMesh& mesh, const Eigen::Matrix3Xd& velocity,
                             const Eigen::Vector3d& centroid);

}  // namespace ehd
