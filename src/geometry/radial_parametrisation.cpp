#include "ehd_capsule/geometry/radial_parametrisation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/spherical_harmonics.h"

namespace ehd {

RadialParametrisation MakeRadialParametrisation(const TriangleMesh& mesh) {
  const int nv = mesh.vertex_count();
  if (mesh.triangle_count() == 0) {
    throw std::invalid_argument("MakeRadialParametrisation: a mesh without triangles");
  }
  const double volume = EnclosedVolume(mesh);
  if (!(std::abs(volume) > 0)) {
    throw std::invalid_argument("MakeRadialParametrisation: the mesh encloses no volume");
  }
  RadialParametrisation p;
  p.center = Centroid(mesh);
  const Eigen::Matrix3Xd& x = mesh.vertices();
  // The second moment of the enclosed volume about the centroid, summed over the tetrahedra
  // (c, a, b, d) of the triangles: int y y^T dV = V/20 (sum_i y_i y_i^T + s s^T), s = sum_i y_i.
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
  for (const auto& tri : mesh.triangles()) {
    const Eigen::Vector3d a = x.col(tri[0]) - p.center, b = x.col(tri[1]) - p.center,
                          d = x.col(tri[2]) - p.center;
    const double v = a.dot(b.cross(d)) / 6.0;
    const Eigen::Vector3d s = a + b + d;
    moment +=
        v / 20.0 * (a * a.transpose() + b * b.transpose() + d * d.transpose() + s * s.transpose());
  }
  moment /= volume;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(moment);
  if (!(eigen.eigenvalues().minCoeff() > 0)) {
    throw std::invalid_argument("MakeRadialParametrisation: a degenerate second moment");
  }
  p.shape = eigen.operatorSqrt();
  const Eigen::Matrix3d inverse = eigen.operatorInverseSqrt();
  p.direction.resize(3, nv);
  p.radius.resize(nv);
  for (int i = 0; i < nv; ++i) {
    const Eigen::Vector3d d = inverse * (x.col(i) - p.center);
    p.radius(i) = d.norm();
    p.direction.col(i) = p.radius(i) > 0 ? Eigen::Vector3d(d / p.radius(i)) : d;
  }
  // Each triangle's solid angle from the center must have the volume's sign (seen from the front).
  // The triple product of the unit directions is the sine-like measure of that solid angle; a
  // relative 1e-12 of it is rounding, not a front face.
  const double orientation = volume > 0 ? 1.0 : -1.0;
  const auto& triangles = mesh.triangles();
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const double det =
        p.direction.col(tri[0]).dot(p.direction.col(tri[1]).cross(p.direction.col(tri[2])));
    if (!(orientation * det > 1e-12) || p.radius(tri[0]) == 0 || p.radius(tri[1]) == 0 ||
        p.radius(tri[2]) == 0) {
      p.folded_triangle = static_cast<int>(t);
      break;
    }
  }
  const std::vector<double> area = VertexThirdAreas(p.direction, triangles, nv);
  p.solid_angle = Eigen::Map<const Eigen::VectorXd>(area.data(), nv);
  return p;
}

Eigen::VectorXd RadialSurfaceWeights(const RadialParametrisation& p, int degree) {
  const int nv = static_cast<int>(p.direction.cols());
  if (!p.star_shaped()) {
    throw std::invalid_argument("RadialSurfaceWeights: the surface is not star-shaped (triangle " +
                                std::to_string(p.folded_triangle) + ")");
  }
  if (degree < 0 || SphericalHarmonicCount(degree) > nv) {
    throw std::invalid_argument("RadialSurfaceWeights: degree " + std::to_string(degree) + " for " +
                                std::to_string(nv) + " vertices");
  }
  const Eigen::MatrixXd y = RealSphericalHarmonics(p.direction, degree);
  const Eigen::MatrixXd weighted = p.solid_angle.asDiagonal() * y;  // Omega Y
  const Eigen::LDLT<Eigen::MatrixXd> gram(y.transpose() * weighted);
  // r's expansion (weighted least squares) and its gradient at each vertex: central differences
  // along two tangents by an angle eps (error eps^2 |r'''|, rounding 1e-16 / eps). The surface is
  // x = c + S r(u) u, so dA = |det S| |S^-1 r (r u - grad r)| dOmega.
  const Eigen::VectorXd radius_coefficients = gram.solve(weighted.transpose() * p.radius);
  constexpr double kEps = 1e-5;
  constexpr int kChunk = 256;
  const Eigen::Matrix3d inverse = p.shape.inverse();
  const double determinant = std::abs(p.shape.determinant());
  Eigen::VectorXd jacobian(nv);
  std::vector<Eigen::Vector3d> t1(kChunk), t2(kChunk);
  for (int start = 0; start < nv; start += kChunk) {
    const int count = std::min(kChunk, nv - start);
    Eigen::Matrix3Xd shifted(3, 4 * count);
    const double c = std::cos(kEps), s = std::sin(kEps);
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector3d u = p.direction.col(start + k);
      const Eigen::Vector3d axis =
          std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      t1[k] = u.cross(axis).normalized();
      t2[k] = u.cross(t1[k]);
      shifted.col(4 * k + 0) = c * u + s * t1[k];
      shifted.col(4 * k + 1) = c * u - s * t1[k];
      shifted.col(4 * k + 2) = c * u + s * t2[k];
      shifted.col(4 * k + 3) = c * u - s * t2[k];
    }
    const Eigen::VectorXd r = RealSphericalHarmonics(shifted, degree) * radius_coefficients;
    for (int k = 0; k < count; ++k) {
      const double d1 = (r(4 * k + 0) - r(4 * k + 1)) / (2 * kEps);
      const double d2 = (r(4 * k + 2) - r(4 * k + 3)) / (2 * kEps);
      const double rk = p.radius(start + k);
      const Eigen::Vector3d u = p.direction.col(start + k);
      jacobian(start + k) =
          determinant * rk * (inverse * (rk * u - d1 * t1[k] - d2 * t2[k])).norm();
    }
  }
  // The solid angles corrected to integrate every Y_lm, l <= degree, exactly: the least change
  // w - omega = Omega Y lambda with Y^T w = sqrt(4 pi) e_00.
  Eigen::VectorXd moments = -y.transpose() * p.solid_angle;
  moments(0) += std::sqrt(4.0 * 3.14159265358979323846);
  const Eigen::VectorXd w = p.solid_angle + weighted * gram.solve(moments);
  return w.cwiseProduct(jacobian);
}

}  // namespace ehd
