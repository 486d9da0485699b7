// Real spherical harmonics and the icosphere parametrisation (geometry/spherical_harmonics.h):
// the addition theorem sum_m Y_lm(x)^2 = (2l + 1) / (4 pi) at every direction (exact; it checks
// the normalisation of every order m), known low-degree functions, orthonormality by quadrature
// on a fine icosphere, and the recognition of icosphere connectivity and its submeshes.
#include "ehd_capsule/geometry/spherical_harmonics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace ehd {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(SphericalHarmonics, AdditionTheoremAndLowDegrees) {
  const int lmax = 30;
  Eigen::Matrix3Xd d(3, 5);
  d << 0.3, -0.7, 0.0, 1.0, 0.2, 0.4, 0.1, 0.0, 0.0, -0.9, 0.866, 0.2, 1.0, 0.0, -0.1;
  const Eigen::MatrixXd y = RealSphericalHarmonics(d, lmax);
  ASSERT_EQ(y.cols(), SphericalHarmonicCount(lmax));
  for (int i = 0; i < d.cols(); ++i) {
    std::vector<double> sum(lmax + 1, 0.0);
    int col = 0;
    for (int m = 0; m <= lmax; ++m) {
      for (int l = m; l <= lmax; ++l) {
        for (int part = 0; part < (m == 0 ? 1 : 2); ++part) sum[l] += y(i, col) * y(i, col), ++col;
      }
    }
    for (int l = 0; l <= lmax; ++l) EXPECT_NEAR(sum[l], (2 * l + 1) / (4 * kPi), 1e-12) << l;
    const Eigen::Vector3d u = d.col(i).normalized();
    EXPECT_NEAR(y(i, 0), std::sqrt(1 / (4 * kPi)), 1e-14);                             // Y_00
    EXPECT_NEAR(y(i, 1), std::sqrt(3 / (4 * kPi)) * u.z(), 1e-14);                     // Y_10
    EXPECT_NEAR(y(i, 2), std::sqrt(5 / (16 * kPi)) * (3 * u.z() * u.z() - 1), 1e-14);  // Y_20
    // m = 1, l = 1 (cos, sin): -sqrt(3/4pi) x, -sqrt(3/4pi) y (Condon-Shortley phase).
    const int m1 = lmax + 1;
    EXPECT_NEAR(y(i, m1), -std::sqrt(3 / (4 * kPi)) * u.x(), 1e-14);
    EXPECT_NEAR(y(i, m1 + 1), -std::sqrt(3 / (4 * kPi)) * u.y(), 1e-14);
  }
  EXPECT_THROW(RealSphericalHarmonics(d, -1), std::invalid_argument);
  EXPECT_THROW(RealSphericalHarmonics(Eigen::Matrix3Xd::Zero(3, 1), 2), std::invalid_argument);
}

TEST(SphericalHarmonics, OrthonormalOnTheIcosphere) {
  const TriangleMesh sphere = IcosphereMesh(5);
  const std::vector<double> area = VertexThirdAreas(sphere);
  const Eigen::MatrixXd y = RealSphericalHarmonics(sphere.vertices(), 8);
  const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(area.data(), area.size());
  const Eigen::MatrixXd gram = y.transpose() * w.asDiagonal() * y;
  const double error =
      (gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff();
  // The third-area rule is second order: 10242 vertices, edge 0.019, degree 8.
  EXPECT_LT(error, 5e-3);
}

TEST(SphericalHarmonics, RecognisesIcosphereConnectivity) {
  for (int k = 0; k <= 5; ++k) EXPECT_EQ(IcosphereLevel(IcosphereMesh(k, 0.3)), k);
  EXPECT_EQ(IcosphereLevel(EllipsoidMesh(4, 1, 0.8, 0.6)), 4);
  EXPECT_EQ(IcosphereLevel(BiconcaveMesh(3)), 3);
  // The same surface with its triangles in another order is not recognised.
  const TriangleMesh sphere = IcosphereMesh(3);
  std::vector<TriangleMesh::Triangle> reordered = sphere.triangles();
  std::swap(reordered[0], reordered[1]);
  EXPECT_EQ(IcosphereLevel(TriangleMesh(sphere.vertices(), reordered)), -1);
  // A submesh is the coarser icosphere at the same vertices.
  const TriangleMesh ellipsoid = EllipsoidMesh(4, 1, 0.8, 0.6);
  const TriangleMesh coarse = IcosphereSubmesh(ellipsoid, 2);
  const TriangleMesh expected = EllipsoidMesh(2, 1, 0.8, 0.6);
  EXPECT_EQ(coarse.triangles(), expected.triangles());
  EXPECT_LT((coarse.vertices() - expected.vertices()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_THROW(IcosphereSubmesh(ellipsoid, 5), std::invalid_argument);
  EXPECT_THROW(IcosphereSubmesh(TriangleMesh(sphere.vertices(), reordered), 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace ehd
