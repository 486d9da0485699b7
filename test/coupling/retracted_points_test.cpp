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

// U(x) = c + A x with a traceless A (a divergence-free flow) sampled at the retracted points
// extrapolates to the exact U at the points, for any distance: the least-squares gradient of an
// affine field is its gradient.
template <int D>
void ExpectAffineFieldExtrapolated(const BodyShape<D>& shape) {
  Eigen::Matrix<double, D, D> gradient = Eigen::Matrix<double, D, D>::Random();
  gradient.diagonal().array() -= gradient.trace() / D;
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

TEST(RetractedPoints, TheGradientsTraceIsRemoved) {
  // A uniform expansion U = x inside is not an incompressible flow: nothing is extrapolated.
  BodyShape<2> circle;
  circle.SetPositions(CircleMarkers(32, 4.0));
  PointsOf<2> retracted;
  RetractAlongNormals(circle, 0.5, retracted);
  PointsOf<2> u = retracted;
  ExtrapolateToPoints(retracted, circle.positions(), u);
  EXPECT_LT((u - retracted).cwiseAbs().maxCoeff(), 1e-12);
}

// The enclosed measure's rate sum_k grad(V)_k . U_k vanishes after the projection, and a
// velocity that keeps it (a rotation) is left as it is.
// (the polygon's area through the markers in 2D, the mesh's volume in 3D).
double PolygonArea(const PointsOf<2>& x) {
  double twice = 0.0;
  for (int k = 0; k < x.cols(); ++k) {
    const int next = (k + 1) % static_cast<int>(x.cols());
    twice += x(0, k) * x(1, next) - x(0, next) * x(1, k);
  }
  return 0.5 * twice;
}

template <int D>
double MeasureRate(const BodyShape<D>& shape, const PointsOf<D>& u) {
  const double eps = 1e-6;
  const PointsOf<D> moved = shape.positions() + eps * u;
  if constexpr (D == 2) {
    return (PolygonArea(moved) - PolygonArea(shape.positions())) / eps;
  } else {
    return (EnclosedVolume(moved, shape.mesh.triangles()) - EnclosedVolume(shape.mesh)) / eps;
  }
}

TEST(RetractedPoints, EnclosedMeasureRateIsRemoved) {
  BodyShape<2> ellipse;
  ellipse.SetPositions(EllipseMarkers(64, 6.0, 3.0));
  PointsOf<2> u = ellipse.positions();  // an expansion
  const double area = ellipse.curve.Area();
  EXPECT_NEAR(MeasureRate(ellipse, u), 2.0 * area, 0.01 * area);
  RemoveEnclosedMeasureRate(ellipse, u);
  EXPECT_LT(std::abs(MeasureRate(ellipse, u)), 1e-6 * area);
  PointsOf<2> rotation(2, ellipse.size());
  for (int k = 0; k < ellipse.size(); ++k) {
    rotation.col(k) = Eigen::Vector2d(-ellipse.positions()(1, k), ellipse.positions()(0, k));
  }
  PointsOf<2> kept = rotation;
  RemoveEnclosedMeasureRate(ellipse, kept);
  EXPECT_LT((kept - rotation).cwiseAbs().maxCoeff(), 1e-3);
  BodyShape<3> sphere;
  sphere.mesh = IcosphereMesh(2, 5.0);
  PointsOf<3> v = sphere.positions();
  RemoveEnclosedMeasureRate(sphere, v);
  EXPECT_LT(std::abs(MeasureRate(sphere, v)), 1e-6 * EnclosedVolume(sphere.mesh));
}

TEST(RetractedPoints, CollinearPointsAreRefused) {
  PointsOf<2> line(2, 4);
  line << 0, 1, 2, 3, 0, 1, 2, 3;
  PointsOf<2> u = PointsOf<2>::Zero(2, 4);
  EXPECT_THROW(ExtrapolateToPoints(line, line, u), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
