// Finite-element membrane: the laws as W(I, J) and the element forces -A_0 P D^-T; see
// surface_elasticity.h.
#include "ehd_capsule/membrane/surface_elasticity.h"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ehd {

const char* ToString(SurfaceLaw law) {
  switch (law) {
    case SurfaceLaw::kNeoHookean:
      return "neo-Hookean";
    case SurfaceLaw::kZeroThickness:
      return "zero-thickness";
    case SurfaceLaw::kSkalak:
      return "Skalak";
  }
  return "?";
}

StrainEnergyDensity EvaluateSurfaceLaw(const SurfaceLawParameters& p, double i, double j) {
  const double g = p.shear_modulus;
  switch (p.law) {
    case SurfaceLaw::kNeoHookean: {
      const double inv_j2 = 1.0 / (j * j);
      return {0.5 * g * (i - 3.0 + inv_j2), 0.5 * g, -g * inv_j2 / j};
    }
    case SurfaceLaw::kZeroThickness: {
      const double l = std::log(j);
      return {0.5 * g * (i - 2.0 - 2.0 * l + 2.0 * l * l), 0.5 * g, g * (2.0 * l - 1.0) / j};
    }
    case SurfaceLaw::kSkalak: {
      const double i1 = i - 2.0, i2 = j * j - 1.0, c = p.area_dilation;
      return {0.25 * g * (i1 * i1 + 2.0 * i1 - 2.0 * i2 + c * i2 * i2), 0.5 * g * (i1 + 1.0),
              g * j * (c * i2 - 1.0)};
    }
  }
  return {0, 0, 0};
}

Eigen::Vector2d PrincipalTensions(const SurfaceLawParameters& p, double l1, double l2) {
  // tau_1 = (1/l2) dW/dl1 with dW/dl1 = W_I 2 l1 + W_J l2.
  const StrainEnergyDensity w = EvaluateSurfaceLaw(p, l1 * l1 + l2 * l2, l1 * l2);
  return {(2.0 * w.w_i * l1 + w.w_j * l2) / l2, (2.0 * w.w_i * l2 + w.w_j * l1) / l1};
}

SurfaceElasticity::SurfaceElasticity(const SurfaceLawParameters& p, const TriangleMesh& reference)
    : params_(p), triangles_(reference.triangles()) {
  if (!(p.shear_modulus > 0.0)) {
    throw std::invalid_argument("SurfaceElasticity: shear modulus G_s = " +
                                std::to_string(p.shear_modulus) + " must be > 0");
  }
  if (p.law == SurfaceLaw::kSkalak && !(p.area_dilation > 0.0)) {
    throw std::invalid_argument("SurfaceElasticity: Skalak area dilation C = " +
                                std::to_string(p.area_dilation) + " must be > 0");
  }
  const Eigen::Matrix3Xd& x = reference.vertices();
  d_inverse_.reserve(triangles_.size());
  area0_.reserve(triangles_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const auto& tri = triangles_[t];
    const Eigen::Vector3d u = x.col(tri[1]) - x.col(tri[0]), v = x.col(tri[2]) - x.col(tri[0]);
    const double area = 0.5 * u.cross(v).norm();
    if (!(area > 1e-14 * u.squaredNorm())) {
      throw std::invalid_argument("SurfaceElasticity: reference triangle " + std::to_string(t) +
                                  " is degenerate");
    }
    const Eigen::Vector3d e1 = u.normalized();
    const Eigen::Vector3d e2 = (v - v.dot(e1) * e1).normalized();
    Eigen::Matrix2d d;
    d << u.norm(), v.dot(e1), 0.0, v.dot(e2);
    d_inverse_.push_back(d.inverse());
    area0_.push_back(area);
    reference_area_ += area;
  }
}

namespace {

struct ElementKinematics {
  Eigen::Matrix<double, 3, 2> f;
  Eigen::Matrix2d c;
  double i, j;
};

ElementKinematics Kinematics(const Eigen::Matrix3Xd& X, const TriangleMesh::Triangle& tri,
                             const Eigen::Matrix2d& d_inverse, std::size_t t) {
  Eigen::Matrix<double, 3, 2> e;
  e.col(0) = X.col(tri[1]) - X.col(tri[0]);
  e.col(1) = X.col(tri[2]) - X.col(tri[0]);
  ElementKinematics k;
  k.f = e * d_inverse;
  k.c = k.f.transpose() * k.f;
  k.i = k.c.trace();
  const double det = k.c.determinant();
  // C = F^T F cannot see a flip; a triangle whose area fell below 1e-6 of its reference area is
  // treated as collapsed.
  if (!(det > 1e-12) || !std::isfinite(det)) {
    throw std::runtime_error("SurfaceElasticity: deformed triangle " + std::to_string(t) +
                             " has collapsed (area stretch J^2 = " + std::to_string(det) + ")");
  }
  k.j = std::sqrt(det);
  return k;
}

}  // namespace

double SurfaceElasticity::ComputeForces(const Eigen::Matrix3Xd& X, Eigen::Matrix3Xd& forces) const {
  forces.setZero(3, X.cols());
  double energy = 0.0;
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const auto& tri = triangles_[t];
    const ElementKinematics k = Kinematics(X, tri, d_inverse_[t], t);
    const StrainEnergyDensity w = EvaluateSurfaceLaw(params_, k.i, k.j);
    energy += area0_[t] * w.w;
    // P = 2 W_I F + W_J J F C^-1; dW/dE = P D^-T.
    const Eigen::Matrix<double, 3, 2> p = 2.0 * w.w_i * k.f + (w.w_j * k.j) * (k.f * k.c.inverse());
    const Eigen::Matrix<double, 3, 2> de = -area0_[t] * p * d_inverse_[t].transpose();
    forces.col(tri[1]) += de.col(0);
    forces.col(tri[2]) += de.col(1);
    forces.col(tri[0]) -= de.col(0) + de.col(1);
  }
  return energy;
}

double SurfaceElasticity::Energy(const Eigen::Matrix3Xd& X) const {
  double energy = 0.0;
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const ElementKinematics k = Kinematics(X, triangles_[t], d_inverse_[t], t);
    energy += area0_[t] * EvaluateSurfaceLaw(params_, k.i, k.j).w;
  }
  return energy;
}

std::vector<Eigen::Vector2d> SurfaceElasticity::Stretches(const Eigen::Matrix3Xd& X) const {
  std::vector<Eigen::Vector2d> out(triangles_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const ElementKinematics k = Kinematics(X, triangles_[t], d_inverse_[t], t);
    // Eqs. (131)-(132).
    const double root = std::sqrt(std::pow(k.c(0, 0) - k.c(1, 1), 2) + 4.0 * k.c(0, 1) * k.c(0, 1));
    out[t] = Eigen::Vector2d(std::sqrt(0.5 * (k.i + root)), std::sqrt(0.5 * (k.i - root)));
  }
  return out;
}

std::vector<double> SurfaceElasticity::VertexMeanTension(const Eigen::Matrix3Xd& X) const {
  const std::vector<Eigen::Vector2d> stretches = Stretches(X);
  std::vector<double> sum(X.cols(), 0.0), weight(X.cols(), 0.0);
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const auto& tri = triangles_[t];
    const double area =
        0.5 * (X.col(tri[1]) - X.col(tri[0])).cross(X.col(tri[2]) - X.col(tri[0])).norm();
    const double mean = PrincipalTensions(params_, stretches[t](0), stretches[t](1)).mean();
    for (int c = 0; c < 3; ++c) {
      sum[tri[c]] += area * mean;
      weight[tri[c]] += area;
    }
  }
  for (std::size_t v = 0; v < sum.size(); ++v) sum[v] = weight[v] > 0.0 ? sum[v] / weight[v] : 0.0;
  return sum;
}

std::string SurfaceElasticity::Describe() const {
  std::ostringstream o;
  o << ToString(params_.law) << " finite elements (" << triangles_.size()
    << " triangles), G_s = " << params_.shear_modulus;
  if (params_.law == SurfaceLaw::kSkalak) o << ", C = " << params_.area_dilation;
  return o.str();
}

}  // namespace ehd
