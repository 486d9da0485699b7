// Least-squares solution of the CFM local Cauchy problem, song2019 eq. (18); see the header for
// the functional, the two bases and where the code departs from the text.

#include "ehd_capsule/reference/cfm_local_cauchy.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "ehd_capsule/geometry/gauss_legendre.h"

namespace ehd {
namespace {

// Legendre polynomials P_0..P_3 with first and second derivatives.
inline void Legendre3(double t, double* p, double* dp, double* ddp) {
  p[0] = 1.0;
  p[1] = t;
  p[2] = 0.5 * (3.0 * t * t - 1.0);
  p[3] = 0.5 * (5.0 * t * t * t - 3.0 * t);
  dp[0] = 0.0;
  dp[1] = 1.0;
  dp[2] = 3.0 * t;
  dp[3] = 0.5 * (15.0 * t * t - 3.0);
  ddp[0] = 0.0;
  ddp[1] = 0.0;
  ddp[2] = 3.0;
  ddp[3] = 15.0 * t;
}

}  // namespace

CfmLocalCauchy::CfmLocalCauchy(CfmBasis basis, double penalty)
    : basis_(basis),
      basis_size_(basis == CfmBasis::kBicubic ? 16 : 5),
      penalty_(penalty),
      rows_(kMaxRows, kMaxBasis),
      rhs_(kMaxRows),
      coefficients_(kMaxBasis),
      qr_(kMaxRows, kMaxBasis) {
  if (!(penalty > 0.0) || !std::isfinite(penalty)) {
    throw std::invalid_argument("CfmLocalCauchy: penalty c_p = " + std::to_string(penalty) +
                                " must be finite and > 0");
  }
  coefficients_.setZero(basis_size_);
}

std::array<Eigen::Vector2d, CfmLocalCauchy::kAreaPoints> CfmLocalCauchy::AreaPoints(
    const CfmPatch& patch) {
  std::array<Eigen::Vector2d, kAreaPoints> points;
  for (int b = 0; b < 4; ++b) {
    for (int a = 0; a < 4; ++a) {
      points[b * 4 + a] = patch.Global({kGauss4Node[a], kGauss4Node[b]});
    }
  }
  return points;
}

void CfmLocalCauchy::EvaluateBasis(double xi, double eta, double* value, double* d_p, double* d_q,
                                   double* laplacian) const {
  const double hp = patch_.half_p, hq = patch_.half_q;
  if (basis_ == CfmBasis::kBicubic) {
    double px[4], dpx[4], ddpx[4], py[4], dpy[4], ddpy[4];
    Legendre3(xi, px, dpx, ddpx);
    Legendre3(eta, py, dpy, ddpy);
    for (int b = 0; b < 4; ++b) {
      for (int a = 0; a < 4; ++a) {
        const int k = b * 4 + a;
        value[k] = px[a] * py[b];
        d_p[k] = dpx[a] * py[b] / hp;
        d_q[k] = px[a] * dpy[b] / hq;
        laplacian[k] = ddpx[a] * py[b] / (hp * hp) + px[a] * ddpy[b] / (hq * hq);
      }
    }
    return;
  }
  // Modified bilinear: corners 1..4 at (xi, eta) = (-1,-1), (1,-1), (1,1), (-1,1) (eqs. (30)-(33)).
  constexpr double kCornerXi[4] = {-1.0, 1.0, 1.0, -1.0};
  constexpr double kCornerEta[4] = {-1.0, -1.0, 1.0, 1.0};
  for (int k = 0; k < 4; ++k) {
    const double fx = 1.0 + kCornerXi[k] * xi, fy = 1.0 + kCornerEta[k] * eta;
    value[k] = 0.25 * fx * fy;
    d_p[k] = 0.25 * kCornerXi[k] * fy / hp;
    d_q[k] = 0.25 * fx * kCornerEta[k] / hq;
    laplacian[k] = 0.0;
  }
  value[4] = -0.25 * (hp * hp * (1.0 - xi * xi) + hq * hq * (1.0 - eta * eta));
  d_p[4] = 0.5 * hp * xi;  // d/dp = (1/hp) d/dxi of -(1/4) hp^2 (1 - xi^2)
  d_q[4] = 0.5 * hq * eta;
  laplacian[4] = 1.0;
}

bool CfmLocalCauchy::Solve(const CfmPatch& patch, const double* f_jump,
                           const CfmInterfaceSample* samples, int n_samples) {
  if (n_samples < 1 || n_samples > kMaxInterfaceSamples) {
    throw std::invalid_argument("CfmLocalCauchy::Solve: n_samples = " + std::to_string(n_samples) +
                                " must be in [1, " + std::to_string(kMaxInterfaceSamples) + "]");
  }
  patch_ = patch;
  const int n = basis_size_;
  coefficients_.setZero(n);
  if (!(patch.half_p > 0.0) || !(patch.half_q > 0.0)) return false;
  const double length = 2.0 * std::min(patch.half_p, patch.half_q);  // l_c^ij
  const int n_rows = kAreaPoints + 2 * n_samples;
  rows_.resize(n_rows, n);
  rhs_.resize(n_rows);
  double value[kMaxBasis], d_p[kMaxBasis], d_q[kMaxBasis], lap[kMaxBasis];
  // Area term: sqrt(l^3 w) (Laplace D - f_D) at the 4 x 4 Gauss points, w = w_a w_b hp hq.
  const double area_scale = length * length * length * patch.half_p * patch.half_q;
  for (int b = 0; b < 4; ++b) {
    for (int a = 0; a < 4; ++a) {
      const int r = b * 4 + a;
      EvaluateBasis(kGauss4Node[a], kGauss4Node[b], value, d_p, d_q, lap);
      const double s = std::sqrt(area_scale * kGauss4Weight[a] * kGauss4Weight[b]);
      for (int k = 0; k < n; ++k) rows_(r, k) = s * lap[k];
      rhs_(r) = s * f_jump[r];
    }
  }
  // Interface terms: sqrt(c_p w) (D - a) and sqrt(c_p l^2 w) (dD/dn - b).
  for (int m = 0; m < n_samples; ++m) {
    const CfmInterfaceSample& sample = samples[m];
    const Eigen::Vector2d local = patch.Local(sample.position);
    EvaluateBasis(local.x(), local.y(), value, d_p, d_q, lap);
    const double n_p = sample.normal.dot(patch.axis_p), n_q = sample.normal.dot(patch.axis_q);
    const double s_value = std::sqrt(penalty_ * sample.weight);
    const double s_normal = s_value * length;
    const int r_value = kAreaPoints + 2 * m, r_normal = r_value + 1;
    for (int k = 0; k < n; ++k) {
      rows_(r_value, k) = s_value * value[k];
      rows_(r_normal, k) = s_normal * (d_p[k] * n_p + d_q[k] * n_q);
    }
    rhs_(r_value) = s_value * sample.jump_value;
    rhs_(r_normal) = s_normal * sample.jump_normal;
  }
  qr_.compute(rows_);
  if (qr_.rank() < n) return false;
  coefficients_ = qr_.solve(rhs_);
  return coefficients_.allFinite();
}

double CfmLocalCauchy::Value(const Eigen::Vector2d& x) const {
  double value[kMaxBasis], d_p[kMaxBasis], d_q[kMaxBasis], lap[kMaxBasis];
  const Eigen::Vector2d local = patch_.Local(x);
  EvaluateBasis(local.x(), local.y(), value, d_p, d_q, lap);
  double d = 0.0;
  for (int k = 0; k < basis_size_; ++k) d += coefficients_(k) * value[k];
  return d;
}

Eigen::Vector2d CfmLocalCauchy::Gradient(const Eigen::Vector2d& x) const {
  double value[kMaxBasis], d_p[kMaxBasis], d_q[kMaxBasis], lap[kMaxBasis];
  const Eigen::Vector2d local = patch_.Local(x);
  EvaluateBasis(local.x(), local.y(), value, d_p, d_q, lap);
  double gp = 0.0, gq = 0.0;
  for (int k = 0; k < basis_size_; ++k) {
    gp += coefficients_(k) * d_p[k];
    gq += coefficients_(k) * d_q[k];
  }
  return gp * patch_.axis_p + gq * patch_.axis_q;
}

double CfmLocalCauchy::Laplacian(const Eigen::Vector2d& x) const {
  double value[kMaxBasis], d_p[kMaxBasis], d_q[kMaxBasis], lap[kMaxBasis];
  const Eigen::Vector2d local = patch_.Local(x);
  EvaluateBasis(local.x(), local.y(), value, d_p, d_q, lap);
  double l = 0.0;
  for (int k = 0; k < basis_size_; ++k) l += coefficients_(k) * lap[k];
  return l;
}

}  // namespace ehd
