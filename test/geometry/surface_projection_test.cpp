// Closest points on triangulated surfaces (geometry/surface_projection.h): the triangle routine
// in each of its Voronoi regions, and the bucketed search against brute force over all triangles
// and against the analytic sphere.
#include "ehd_capsule/geometry/surface_projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ehd {
namespace {

TEST(SurfaceProjection, TriangleRegions) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // Face interior: straight down.
  SurfacePoint s = ClosestPointOnTriangle(Eigen::Vector3d(0.2, 0.3, 0.7), a, b, c);
  EXPECT_NEAR(s.distance, 0.7, 1e-15);
  EXPECT_NEAR(s.barycentric.sum(), 1.0, 1e-15);
  EXPECT_NEAR(s.barycentric(1), 0.2, 1e-15);
  // Vertex region.
  s = ClosestPointOnTriangle(Eigen::Vector3d(-1, -1, 0.5), a, b, c);
  EXPECT_NEAR((s.point - a).norm(), 0.0, 1e-15);
  // Edge bc region.
  s = ClosestPointOnTriangle(Eigen::Vector3d(1, 1, 0), a, b, c);
  EXPECT_NEAR(s.point.x(), 0.5, 1e-15);
  EXPECT_NEAR(s.point.y(), 0.5, 1e-15);
}

TEST(SurfaceProjection, BucketedSearchEqualsBruteForce) {
  BiconcaveParameters p;
  const TriangleMesh cell = BiconcaveMesh(3, p);
  const SurfaceProjector projector(cell, 0.1);
  std::mt19937 gen(4);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  for (int q = 0; q < 300; ++q) {
    const Eigen::Vector3d x(u(gen), 0.5 * u(gen), u(gen));
    const SurfacePoint found = projector.Closest(x);
    double brute = 1e300;
    for (const auto& t : cell.triangles()) {
      brute = std::min(
          brute, ClosestPointOnTriangle(x, cell.vertices().col(t[0]), cell.vertices().col(t[1]),
                                        cell.vertices().col(t[2]))
                     .distance);
    }
    EXPECT_NEAR(found.distance, brute, 1e-14) << q;
    EXPECT_GE(found.triangle, 0);
  }
}

TEST(SurfaceProjection, SphereDistanceWithinTheSagitta) {
  const double r = 0.8;
  const TriangleMesh sphere = IcosphereMesh(4, r);
  const SurfaceProjector projector(sphere, 0.05);
  const double edge = MeasureQuality(sphere).max_edge, sagitta = edge * edge / (4 * r);
  std::mt19937 gen(5);
  std::normal_distribution<double> n(0, 1);
  for (int q = 0; q < 200; ++q) {
    Eigen::Vector3d d(n(gen), n(gen), n(gen));
    d.normalize();
    const double rad = r + 0.1 * (q % 7 - 3) / 3.0;
    const SurfacePoint s = projector.Closest(rad * d);
    EXPECT_NEAR(s.distance, std::abs(rad - r), sagitta + 1e-12);
    EXPECT_NEAR(s.point.norm(), r, sagitta + 1e-12);
  }
}

}  // namespace
}  // namespace ehd
