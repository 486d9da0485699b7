// Mesh-scale filter of a membrane's deformation (see mesh_scale_filter.h).
#include "ehd_capsule/ib/mesh_scale_filter.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {

MeshScaleFilter::MeshScaleFilter(const TriangleMesh& reference, int order)
    : order_(order), triangles_(reference.triangles()), reference_(reference.vertices()) {
  if (order < 1) {
    throw std::invalid_argument("MeshScaleFilter: order must be >= 1, got " +
                                std::to_string(order));
  }
  const int n = reference.vertex_count();
  if (n < 4) {
    throw std::invalid_argument(
        "MeshScaleFilter: needs a closed mesh of at least 4 vertices, got " + std::to_string(n));
  }
  offsets_.assign(n + 1, 0);
  inverse_valence_.resize(n);
  for (int i = 0; i < n; ++i) {
    const int valence = static_cast<int>(reference.vertex_edges(i).size());
    offsets_[i + 1] = offsets_[i] + valence;
    inverse_valence_[i] = 1.0 / valence;  // every vertex of a TriangleMesh has edges
  }
  neighbors_.reserve(offsets_[n]);
  for (int i = 0; i < n; ++i) {
    for (int e : reference.vertex_edges(i)) {
      const TriangleMesh::Edge& edge = reference.edges()[e];
      neighbors_.push_back(edge.a == i ? edge.b : edge.a);
    }
  }
  // mu_max by power iteration on A in the inner product <x, y> = sum n_i x_i y_i (A is
  // self-adjoint there); the Rayleigh quotient converges from below, and the start vector (a
  // fixed pseudo-random pattern) has a component on the top mode. 1e-12 relative, or 10^4 steps.
  Eigen::Matrix3Xd x(3, n), y;
  unsigned state = 12345u;
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      state = state * 1664525u + 1013904223u;
      x(a, i) = static_cast<double>(state >> 8) / 16777216.0 - 0.5;
    }
  }
  auto weighted_dot = [&](const Eigen::Matrix3Xd& u, const Eigen::Matrix3Xd& v) {
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += u.col(i).dot(v.col(i)) / inverse_valence_[i];
    return s;
  };
  double rayleigh = 0.0;
  for (int it = 0; it < 10000; ++it) {
    x /= std::sqrt(weighted_dot(x, x));
    ApplyLaplacian(x, y);
    const double next = weighted_dot(x, y);
    x = y;
    const bool converged = it > 10 && std::abs(next - rayleigh) <= 1e-12 * next;
    rayleigh = next;
    if (converged) break;
  }
  mu_max_ = rayleigh;
  if (!(mu_max_ > 0.0 && mu_max_ <= 2.0 + 1e-9)) {
    throw std::logic_error("MeshScaleFilter: largest graph-Laplacian eigenvalue " +
                           std::to_string(mu_max_) + " outside (0, 2]");
  }
  HighPass(reference_, reference_high_);
  NormalsAndScales(reference_, reference_normals_, reference_scales_);
  reference_inverse_.resize(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d n0 = reference_scales_[i] * reference_normals_.col(i);
    Eigen::Matrix3d gram = n0 * n0.transpose();
    for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      const Eigen::Vector3d d0 = reference_.col(neighbors_[k]) - reference_.col(i);
      gram += d0 * d0.transpose();
    }
    reference_inverse_[i] = gram.inverse();
  }
}

void MeshScaleFilter::ApplyLaplacian(const Eigen::Matrix3Xd& X, Eigen::Matrix3Xd& out) const {
  const int n = static_cast<int>(inverse_valence_.size());
  out.resize(3, n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) sum += X.col(neighbors_[k]);
    out.col(i) = X.col(i) - inverse_valence_[i] * sum;
  }
}

void MeshScaleFilter::HighPass(const Eigen::Matrix3Xd& X, Eigen::Matrix3Xd& out) const {
  out = X;
  for (int pass = 0; pass < order_; ++pass) {
    work_ = out;
    ApplyLaplacian(work_, out);
    out /= mu_max_;
  }
}

void MeshScaleFilter::NormalsAndScales(const Eigen::Matrix3Xd& X, Eigen::Matrix3Xd& normals,
                                       std::vector<double>& scales) const {
  const int n = static_cast<int>(inverse_valence_.size());
  normals.setZero(3, n);
  for (const auto& t : triangles_) {
    const Eigen::Vector3d face = (X.col(t[1]) - X.col(t[0])).cross(X.col(t[2]) - X.col(t[0]));
    for (int v : t) normals.col(v) += face;  // |face| = 2 x area: area weights
  }
  scales.resize(n);
  for (int i = 0; i < n; ++i) {
    normals.col(i).normalize();
    double sum = 0.0;
    for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      sum += (X.col(neighbors_[k]) - X.col(i)).norm();
    }
    scales[i] = sum * inverse_valence_[i];
  }
}

void MeshScaleFilter::Apply(Eigen::Matrix3Xd& X) {
  const int n = static_cast<int>(inverse_valence_.size());
  if (X.cols() != n) {
    throw std::invalid_argument("MeshScaleFilter: " + std::to_string(X.cols()) +
                                " vertices given, built for " + std::to_string(n));
  }
  HighPass(X, high_);
  NormalsAndScales(X, normals_, scales_);
  for (int i = 0; i < n; ++i) {
    // M_i = (sum d d0^T + n n0^T)(sum d0 d0^T + n0 n0^T)^-1 over the ring's edges d0 -> d.
    const Eigen::Vector3d n0 = reference_scales_[i] * reference_normals_.col(i);
    const Eigen::Vector3d n1 = scales_[i] * normals_.col(i);
    Eigen::Matrix3d cross = n1 * n0.transpose();
    for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      const int j = neighbors_[k];
      cross += (X.col(j) - X.col(i)) * (reference_.col(j) - reference_.col(i)).transpose();
    }
    const Eigen::Matrix3d map = cross * reference_inverse_[i];
    work_.col(i) = high_.col(i) - map * reference_high_.col(i);
  }
  X -= work_.leftCols(n);
}

}  // namespace ehd
