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

}  // namespace
}  // namespace ehd
