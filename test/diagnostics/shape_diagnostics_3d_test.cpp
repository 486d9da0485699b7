// Equivalent-ellipsoid diagnostics (diagnostics/shape_diagnostics_3d.h) on rotated and shifted
// ellipsoid meshes with known semi-axes, inclination and volume, converging with the mesh.
#include "ehd_capsule/diagnostics/shape_diagnostics_3d.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace ehd {
namespace {

TEST(ShapeDiagnostics3D, RotatedEllipsoidGivesItsAxesDeformationAndInclination) {
  const double a = 1.2, b = 0.8, c = 0.95, angle = 0.35;  // c along z (vorticity axis)
  const Eigen::Vector3d shift(2.0, -1.0, 0.5);
  double previous_error = 1e300;
  for (int k = 3; k <= 5; ++k) {
    TriangleMesh m = EllipsoidMesh(k, a, b, c);
    const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    m.SetVertices((r * m.vertices()).colwise() + shift);
    const ShapeDiagnostics3D d = MeasureShape3D(m);
    const double error = std::abs(d.dxy - (a - b) / (a + b));
    EXPECT_LT(error, 5e-3) << "k " << k;
    EXPECT_LT(error, previous_error);
    previous_error = error;
    EXPECT_NEAR(d.inclination, angle, 2e-3);
    EXPECT_NEAR(d.volume, 4.0 * M_PI * a * b * c / 3.0, 1e-2 * 4.0 * M_PI * a * b * c / 3.0);
    EXPECT_NEAR((d.centroid - shift).norm(), 0.0, 1e-12);
    EXPECT_NEAR(d.semi_axes(0), a, 1e-2);
    EXPECT_NEAR(d.semi_axes(2), b, 1e-2);
  }
}

TEST(ShapeDiagnostics3D, SphereHasNoDeformation) {
  const ShapeDiagnostics3D d = MeasureShape3D(IcosphereMesh(4, 3.0));
  EXPECT_LT(d.dxy, 1e-6);
  EXPECT_NEAR(d.semi_axes(0), 3.0, 1e-2);
}

TEST(ShapeDiagnostics3D, ProlateAlongZIsNotAShearPlaneDeformation) {
  // Long along the vorticity axis: the shear-plane section is a circle.
  const ShapeDiagnostics3D d = MeasureShape3D(EllipsoidMesh(4, 1.0, 1.0, 1.5));
  EXPECT_LT(d.dxy, 1e-6);
  EXPECT_NEAR(d.semi_axes(0), 1.5, 1e-2);
}

// u = U sin(theta) cos(theta) e_theta about an off-origin centroid, plus a drift and a rigid
// rotation about z (neither has a meridional component): U is recovered to the quadrature error
// of the mesh, and reversing the flow reverses the sign.
TEST(ShapeDiagnostics3D, MeridionalFlowAmplitudeAndSign) {
  const Eigen::Vector3d c(1.0, -2.0, 0.5);
  TriangleMesh mesh = IcosphereMesh(4, 2.0);
  Eigen::Matrix3Xd x = mesh.vertices();
  x.colwise() += c;
  mesh.SetVertices(x);
  const double amplitude = 0.37;
  Eigen::Matrix3Xd u(3, mesh.vertex_count());
  for (int i = 0; i < mesh.vertex_count(); ++i) {
    const Eigen::Vector3d r = (x.col(i) - c).normalized();
    const double cos_t = r.z();
    const Eigen::Vector3d sin_e_theta = r * cos_t - Eigen::Vector3d::UnitZ();
    u.col(i) = amplitude * cos_t * sin_e_theta + Eigen::Vector3d(0.2, -0.1, 0.05) +
               0.8 * Eigen::Vector3d::UnitZ().cross(x.col(i) - c);
  }
  EXPECT_NEAR(MeasureMeridionalFlow(mesh, u, c), amplitude, 1e-3 * amplitude);
  Eigen::Matrix3Xd reversed = -u;
  EXPECT_NEAR(MeasureMeridionalFlow(mesh, reversed, c), -amplitude, 1e-3 * amplitude);
  EXPECT_THROW(MeasureMeridionalFlow(mesh, Eigen::Matrix3Xd::Zero(3, 3), c), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
