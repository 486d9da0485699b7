// The retracted immersed boundary's geometry (coupling/retracted_points.h): the points moved
// inward along their normals, and the velocity extrapolated from them to the membrane by the
// body's velocity gradient, exact for an affine velocity field.
#include "ehd_capsule/coupling/retracted_points.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {
namespace {

TEST(RetractedPoints, CircleMarkersMoveInwardByTheDistance) {
  BodyShape<2> circle;
  circle.SetPositions(CircleMarkers(64, 5.0, Eigen::Vector2d(1.0, -2.0)));
  PointsOf<2> retracted;
  RetractAlongNormals(circle, 0.5, retracted);
  for (int k = 0; k < circle.size(); ++k) {
    EXPECT_NEAR((retracted.col(k) - Eigen::Vector2d(1.0, -2.0)).norm(), 4.5, 1e-5) << k;
  }
}

TEST(RetractedPoints, SphereVerticesMoveInwardByTheDistance) {
  BodyShape<3> sphere;
  sphere.mesh = IcosphereMesh(3, 4.0);
  PointsOf<3> retracted;
  RetractAlongNormals(sphere, 0.7, retracted);
  for (int v = 0; v < sphere.size(); ++v) {
    // The area-weighted normal of an icosphere is radial to ~1e-3 (it is exact by symmetry at
    // the 12 valence-5 vertices).
    EXPECT_NEAR(retracted.col(v).norm(), 3.3, 1e-3) << v;
  }
}

// U(x) = c + A x sampled at the retracted points extrapolates to the exact U at the points, for
// any distance: the least-squares gradient of an affine field is its gradient.
template <int D>
void ExpectAffineFieldExtrapolated(const BodyShape<D>& shape) {
  Eigen::Matrix<double, D, D> gradient = Eigen::Matrix<double, D, D>::Random();
  const Eigen::Matrix<double, D, 1> offset = Eigen::Matrix<double, D, 1>::Random();
  PointsOf<D> retracted;
  RetractAlongNormals(shape, 0.9, retracted);
  PointsOf<D> u = (gradient * retracted).colwise() + offset;
  ExtrapolateToPoints(retracted, shape.positions(), u);
  const PointsOf<D> exact = (gradient * shape.positions()).colwise() + offset;
  EXPECT_LT((u - exact).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(RetractedPoints, AffineVelocityIsExtrapolatedExactly) {
  BodyShape<2> ellipse;
  ellipse.SetPositions(EllipseMarkers(48, 6.0, 3.0));
  ExpectAffineFieldExtrapolated(ellipse);
  BodyShape<3> sphere;
  sphere.mesh = IcosphereMesh(2, 5.0);
  ExpectAffineFieldExtrapolated(sphere);
}

TEST(RetractedPoints, TankTreadingSpeedIsRestored) {
  // A rigid rotation about the centre sampled inside moves slower by (a - delta) / a; the
  // extrapolated velocity is the rotation's at the membrane.
  BodyShape<2> circle;
  circle.SetPositions(CircleMarkers(64, 8.0));
  PointsOf<2> retracted;
  RetractAlongNormals(circle, 0.5, retracted);
  PointsOf<2> u(2, circle.size());
  for (int k = 0; k < circle.size(); ++k) {
    u.col(k) = 0.5 * Eigen::Vector2d(-retracted(1, k), retracted(0, k));
  }
  EXPECT_NEAR(u.col(0).norm(), 0.5 * 7.5, 1e-5);
  ExtrapolateToPoints(retracted, circle.positions(), u);
  for (int k = 0; k < circle.size(); ++k) EXPECT_NEAR(u.col(k).norm(), 0.5 * 8.0, 1e-6) << k;
}

TEST(RetractedPoints, CollinearPointsAreRefused) {
  PointsOf<2> line(2, 4);
  line << 0, 1, 2, 3, 0, 1, 2, 3;
  PointsOf<2> u = PointsOf<2>::Zero(2, 4);
  EXPECT_THROW(ExtrapolateToPoints(line, line, u), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
