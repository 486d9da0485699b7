// Equivalent-ellipsoid diagnostics of a triangulated capsule; see shape_diagnostics_3d.h.
#include "ehd_capsule/diagnostics/shape_diagnostics_3d.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {

ShapeDiagnostics3D MeasureShape3D(const TriangleMesh& mesh) {
  const Eigen::Matrix3Xd& x = mesh.vertices();
  // Reference point: the vertex mean (keeps the tetrahedra small, against cancellation).
  const Eigen::Vector3d p = x.rowwise().mean();
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3d a = x.col(t[0]) - p, b = x.col(t[1]) - p, c = x.col(t[2]) - p;
    const double v = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d sum = a + b + c;
    volume += v;
    first += v * sum / 4.0;
    second += (v / 20.0) *
              (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
  }
  if (!(volume > 0.0)) {
    throw std::runtime_error("MeasureShape3D: enclosed volume " + std::to_string(volume) +
                             " is not positive (inverted or degenerate surface)");
  }
  ShapeDiagnostics3D d;
  d.volume = volume;
  d.area = SurfaceArea(mesh);
  const Eigen::Vector3d offset = first / volume;
  d.centroid = p + offset;
  const Eigen::Matrix3d s = second - volume * offset * offset.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(s);
  Eigen::Vector3d axes;
  for (int i = 0; i < 3; ++i)
    axes(i) = std::sqrt(std::max(0.0, 5.0 * eig.eigenvalues()(i) / volume));
  // Leave out the axis closest to the vorticity axis z.
  int out = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(eig.eigenvectors()(2, i)) > std::abs(eig.eigenvectors()(2, out))) out = i;
  }
  int first_in = -1, second_in = -1;
  for (int i = 0; i < 3; ++i) {
    if (i == out) continue;
    (first_in < 0 ? first_in : second_in) = i;
  }
  const int major = axes(first_in) >= axes(second_in) ? first_in : second_in;
  const int minor = major == first_in ? second_in : first_in;
  const double l = axes(major), b = axes(minor);
  d.dxy = (l + b) > 0 ? (l - b) / (l + b) : 0.0;
  const double along = axes(out), across = 0.5 * (l + b);
  d.dz = (along + across) > 0 ? (along - across) / (along + across) : 0.0;
  double theta = std::atan2(eig.eigenvectors()(1, major), eig.eigenvectors()(0, major));
  if (theta > M_PI / 2) theta -= M_PI;
  if (theta <= -M_PI / 2) theta += M_PI;
  d.inclination = theta;
  std::sort(axes.data(), axes.data() + 3, [](double u, double v) { return u > v; });
  d.semi_axes = axes;
  return d;
}

double MeasureMeridionalFlow(const TriangleMesh& mesh, const Eigen::Matrix3Xd& velocity,
                             const Eigen::Vector3d& centroid) {
  const int n = mesh.vertex_count();
  if (velocity.cols() != n) {
    throw std::invalid_argument("MeasureMeridionalFlow: " + std::to_string(velocity.cols()) +
                                " velocities for " + std::to_string(n) + " vertices");
  }
  const std::vector<double> area = VertexThirdAreas(mesh);
  const Eigen::Matrix3Xd& x = mesh.vertices();
  const Eigen::Vector3d mean = AreaWeightedMean(mesh, area, velocity);
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  double num = 0.0, den = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d r = (x.col(i) - centroid).normalized();
    const double c = r.z(), s2 = 1.0 - c * c;
    num += area[i] * c * (velocity.col(i) - mean).dot(r * c - z);
    den += area[i] * s2 * c * c;
  }
  return den > 0.0 ? num / den : 0.0;
}

}  // namespace ehd
