// Weighted least-squares quadratic fit of the minus-side extension at each marker
// (song2019 sec. 2.4.2; see normal_derivative_fit.h).
#include "ehd_capsule/electric/normal_derivative_fit.h"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {

void NormalDerivativeFit::Update(const ClosedCurve& curve, const InterfaceClassification& classes,
                                 double radius) {
  const Grid2D& grid = classes.grid();
  const double h = grid.h;
  if (!(radius >= 2.0 * h) || radius > classes.band_width()) {
    throw std::invalid_argument(
        "NormalDerivativeFit: radius must be in [2h, band width] = [" + std::to_string(2.0 * h) +
        ", " + std::to_string(classes.band_width()) + "], got " + std::to_string(radius));
  }
  const int m = curve.size();
  offset_.assign(m + 1, 0);
  point_.clear();
  plus_slot_.clear();
  gamma_xi_.clear();
  gamma_eta_.clear();
  weight_.clear();
  Eigen::Matrix<double, Eigen::Dynamic, 6> a;
  Eigen::VectorXd wt;
  for (int k = 0; k < m; ++k) {
    offset_[k] = static_cast<int>(point_.size());
    const CurvePoint c = curve.AtMarker(k);
    const double px = c.position.x(), py = c.position.y();
    const int i0 = std::max(0, static_cast<int>(std::ceil((px - radius - grid.x0) / h - 0.5)));
    const int i1 =
        std::min(grid.nx - 1, static_cast<int>(std::floor((px + radius - grid.x0) / h - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::ceil((py - radius - grid.y0) / h - 0.5)));
    const int j1 =
        std::min(grid.ny - 1, static_cast<int>(std::floor((py + radius - grid.y0) / h - 0.5)));
    const int first = offset_[k];
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const Eigen::Vector2d r(grid.x(i) - px, grid.y(j) - py);
        const double dist = r.norm();
        if (dist >= radius) continue;
        const int idx = static_cast<int>(grid.index(i, j));
        point_.push_back(idx);
        plus_slot_.push_back(classes.side(idx) > 0 ? classes.band_slot(idx) : -1);
        weight_.push_back(0.5 * (1.0 + std::cos(M_PI * dist / radius)));
        // Local coordinates, stored scaled by h until the fit below.
        gamma_xi_.push_back(r.dot(c.normal) / h);
        gamma_eta_.push_back(r.dot(c.tangent) / h);
      }
    }
    const int count = static_cast<int>(point_.size()) - first;
    if (count < 6) {
      throw std::runtime_error("NormalDerivativeFit: marker " + std::to_string(k) + " has only " +
                               std::to_string(count) + " grid points within the fit radius");
    }
    a.resize(count, 6);
    wt.resize(count);
    for (int q = 0; q < count; ++q) {
      const double xi = gamma_xi_[first + q], eta = gamma_eta_[first + q];
      a.row(q) << 1.0, xi, eta, 0.5 * xi * xi, xi * eta, 0.5 * eta * eta;
      wt(q) = weight_[first + q];
      if (plus_slot_[first + q] < 0 && classes.side(point_[first + q]) > 0) {
        throw std::runtime_error("NormalDerivativeFit: an outside fit point is not in the band");
      }
    }
    // Rows 1 and 2 of (A^T W A)^{-1} A^T W, then undo the h scaling of xi and eta.
    const Eigen::Matrix<double, 6, 6> normal = a.transpose() * wt.asDiagonal() * a;
    Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(normal);
    if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-12) {
      throw std::runtime_error("NormalDerivativeFit: fit at marker " + std::to_string(k) +
                               " is rank deficient");
    }
    const Eigen::MatrixXd rows = ldlt.solve(a.transpose() * wt.asDiagonal());
    for (int q = 0; q < count; ++q) {
      gamma_xi_[first + q] = rows(1, q) / h;
      gamma_eta_[first + q] = rows(2, q) / h;
    }
  }
  offset_[m] = static_cast<int>(point_.size());
}

void NormalDerivativeFit::Evaluate(const double* phi, const double* band_jump, double* dn_minus,
                                   double* dt_minus) const {
  const int m = markers();
  for (int k = 0; k < m; ++k) {
    double dn = 0.0, dt = 0.0;
    for (int q = offset_[k]; q < offset_[k + 1]; ++q) {
      const int slot = plus_slot_[q];
      const double value = phi[point_[q]] - (slot >= 0 ? band_jump[slot] : 0.0);
      dn += gamma_xi_[q] * value;
      dt += gamma_eta_[q] * value;
    }
    dn_minus[k] = dn;
    dt_minus[k] = dt;
  }
}

void NormalDerivativeFit::EvaluateNormal(const double* phi, const double* band_jump,
                                         double* dn_minus) const {
  const int m = markers();
  for (int k = 0; k < m; ++k) {
    double dn = 0.0;
    for (int q = offset_[k]; q < offset_[k + 1]; ++q) {
      const int slot = plus_slot_[q];
      dn += gamma_xi_[q] * (phi[point_[q]] - (slot >= 0 ? band_jump[slot] : 0.0));
    }
    dn_minus[k] = dn;
  }
}

void NormalDerivativeFit::SideAverages(const double* field, double* minus_average,
                                       double* plus_average) const {
  const int m = markers();
  for (int k = 0; k < m; ++k) {
    double sm = 0, wm = 0, sp = 0, wp = 0;
    for (int q = offset_[k]; q < offset_[k + 1]; ++q) {
      // The weight at the fit centre is largest; points outside the fit carry none.
      if (plus_slot_[q] >= 0) {
        sp += weight_[q] * field[point_[q]];
        wp += weight_[q];
      } else {
        sm += weight_[q] * field[point_[q]];
        wm += weight_[q];
      }
    }
    minus_average[k] = wm > 0 ? sm / wm : 0.0;
    plus_average[k] = wp > 0 ? sp / wp : 0.0;
  }
}

}  // namespace ehd
