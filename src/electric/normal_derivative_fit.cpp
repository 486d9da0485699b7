// Weighted least-squares quadratic fit of the minus-side extension at each marker
// (song2019 sec. 2.4.2; see normal_derivative_fit.h).
#include "ehd_capsule/electric/normal_derivative_fit.h"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {
namespace {

// Rows (value at the origin, xi-derivative there) of the weighted least-squares fit through the
// points xi, eta (in units of h) with weights wt: quadratic if >= 9 points and well
// conditioned, else linear if >= 4 points and well conditioned, else the weighted mean (zero
// derivative).
void OneSidedRows(const std::vector<double>& xi, const std::vector<double>& eta,
                  const std::vector<double>& wt, double h, std::vector<double>& value_row,
                  std::vector<double>& dxi_row) {
  const int count = static_cast<int>(xi.size());
  value_row.assign(count, 0.0);
  dxi_row.assign(count, 0.0);
  if (count == 0) return;
  for (int terms : {6, 3}) {
    if (count < (terms == 6 ? 9 : 4)) continue;
    Eigen::MatrixXd a(count, terms);
    Eigen::VectorXd w(count);
    for (int q = 0; q < count; ++q) {
      if (terms == 6) {
        a.row(q) << 1.0, xi[q], eta[q], 0.5 * xi[q] * xi[q], xi[q] * eta[q], 0.5 * eta[q] * eta[q];
      } else {
        a.row(q) << 1.0, xi[q], eta[q];
      }
      w(q) = wt[q];
    }
    const Eigen::MatrixXd normal = a.transpose() * w.asDiagonal() * a;
    Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
    if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-8) continue;
    const Eigen::MatrixXd rows = ldlt.solve(a.transpose() * w.asDiagonal());
    for (int q = 0; q < count; ++q) {
      value_row[q] = rows(0, q);
      dxi_row[q] = rows(1, q) / h;
    }
    return;
  }
  double total = 0.0;
  for (int q = 0; q < count; ++q) total += wt[q];
  for (int q = 0; q < count; ++q) value_row[q] = wt[q] / total;
}

}  // namespace

void NormalDerivativeFit::Update(const ClosedCurve& curve, const InterfaceClassification& classes,
                                 double radius, int degree) {
  const Grid2D& grid = classes.grid();
  const double h = grid.h;
  if (!(radius >= 2.0 * h) || radius > classes.band_width()) {
    throw std::invalid_argument(
        "NormalDerivativeFit: radius must be in [2h, band width] = [" + std::to_string(2.0 * h) +
        ", " + std::to_string(classes.band_width()) + "], got " + std::to_string(radius));
  }
  if (degree != 2 && degree != 3) {
    throw std::invalid_argument("NormalDerivativeFit: degree must be 2 or 3, got " +
                                std::to_string(degree));
  }
  const int m = curve.size();
  offset_.assign(m + 1, 0);
  point_.clear();
  plus_slot_.clear();
  gamma_xi_.clear();
  gamma_eta_.clear();
  gamma_check_.clear();
  weight_.clear();
  side_value_.clear();
  side_dxi_.clear();
  Eigen::MatrixXd a;
  Eigen::VectorXd wt;
  std::vector<double> side_xi, side_eta, side_wt, value_row, dxi_row;
  std::vector<int> side_entry;
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
    for (int q = first; q < first + count; ++q) {
      if (plus_slot_[q] < 0 && classes.side(point_[q]) > 0) {
        throw std::runtime_error("NormalDerivativeFit: an outside fit point is not in the band");
      }
    }
    // One-sided fits, one per side.
    side_value_.resize(point_.size());
    side_dxi_.resize(point_.size());
    for (int side : {-1, 1}) {
      side_xi.clear();
      side_eta.clear();
      side_wt.clear();
      side_entry.clear();
      for (int q = first; q < first + count; ++q) {
        if ((plus_slot_[q] >= 0 ? 1 : -1) != side) continue;
        side_xi.push_back(gamma_xi_[q]);
        side_eta.push_back(gamma_eta_[q]);
        side_wt.push_back(weight_[q]);
        side_entry.push_back(q);
      }
      OneSidedRows(side_xi, side_eta, side_wt, h, value_row, dxi_row);
      for (std::size_t e = 0; e < side_entry.size(); ++e) {
        side_value_[side_entry[e]] = value_row[e];
        side_dxi_[side_entry[e]] = dxi_row[e];
      }
    }
    // Rows 1 and 2 of (A^T W A)^{-1} A^T W (cubic if possible, else quadratic), then undo the
    // h scaling of xi and eta.
    Eigen::MatrixXd rows;
    int used_terms = 0;
    for (int terms : {10, 6}) {
      if (terms == 10 && degree < 3) continue;
      if (count < (terms == 10 ? 14 : 6)) continue;  // cubic: keep it overdetermined
      a.resize(count, terms);
      wt.resize(count);
      for (int q = 0; q < count; ++q) {
        const double xi = gamma_xi_[first + q], eta = gamma_eta_[first + q];
        a(q, 0) = 1.0;
        a(q, 1) = xi;
        a(q, 2) = eta;
        a(q, 3) = 0.5 * xi * xi;
        a(q, 4) = xi * eta;
        a(q, 5) = 0.5 * eta * eta;
        if (terms == 10) {
          a(q, 6) = xi * xi * xi / 6.0;
          a(q, 7) = 0.5 * xi * xi * eta;
          a(q, 8) = 0.5 * xi * eta * eta;
          a(q, 9) = eta * eta * eta / 6.0;
        }
        wt(q) = weight_[first + q];
      }
      const Eigen::MatrixXd normal = a.transpose() * wt.asDiagonal() * a;
      Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
      if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-12) continue;
      rows = ldlt.solve(a.transpose() * wt.asDiagonal());
      used_terms = terms;
      break;
    }
    if (rows.rows() == 0) {
      throw std::runtime_error("NormalDerivativeFit: fit at marker " + std::to_string(k) +
                               " is rank deficient (" + std::to_string(count) + " points)");
    }
    // The check rows (FastIimSolver's fit-agreement guarantee): the quadratic's xi-row beside
    // the cubic (its normal matrix is the cubic's leading 6 x 6 block); without the cubic, the
    // quadratic is the fit and its own check.
    Eigen::VectorXd check = rows.row(1).transpose();
    if (used_terms == 10) {
      const Eigen::MatrixXd quadratic = a.leftCols(6);
      Eigen::LDLT<Eigen::MatrixXd> ldlt(quadratic.transpose() * wt.asDiagonal() * quadratic);
      if (ldlt.info() == Eigen::Success && ldlt.rcond() >= 1e-12) {
        check = ldlt.solve(quadratic.transpose() * wt.asDiagonal()).row(1).transpose();
      }
    }
    gamma_check_.resize(point_.size());
    for (int q = 0; q < count; ++q) {
      gamma_xi_[first + q] = rows(1, q) / h;
      gamma_eta_[first + q] = rows(2, q) / h;
      gamma_check_[first + q] = check(q) / h;
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

void NormalDerivativeFit::EvaluateNormalWith(const std::vector<double>& gamma, const double* phi,
                                             const double* band_jump, double* dn_minus) const {
  const int m = markers();
  for (int k = 0; k < m; ++k) {
    double dn = 0.0;
    for (int q = offset_[k]; q < offset_[k + 1]; ++q) {
      const int slot = plus_slot_[q];
      dn += gamma[q] * (phi[point_[q]] - (slot >= 0 ? band_jump[slot] : 0.0));
    }
    dn_minus[k] = dn;
  }
}

void NormalDerivativeFit::EvaluateNormal(const double* phi, const double* band_jump,
                                         double* dn_minus) const {
  EvaluateNormalWith(gamma_xi_, phi, band_jump, dn_minus);
}

void NormalDerivativeFit::EvaluateNormalCheck(const double* phi, const double* band_jump,
                                              double* dn_minus) const {
  EvaluateNormalWith(gamma_check_, phi, band_jump, dn_minus);
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

void NormalDerivativeFit::SideExtrapolation(const double* field, double* minus_value,
                                            double* plus_value, double* minus_dxi,
                                            double* plus_dxi) const {
  const int m = markers();
  for (int k = 0; k < m; ++k) {
    double value[2] = {0.0, 0.0}, dxi[2] = {0.0, 0.0};
    for (int q = offset_[k]; q < offset_[k + 1]; ++q) {
      const int side = plus_slot_[q] >= 0 ? 1 : 0;
      value[side] += side_value_[q] * field[point_[q]];
      dxi[side] += side_dxi_[q] * field[point_[q]];
    }
    if (minus_value) minus_value[k] = value[0];
    if (plus_value) plus_value[k] = value[1];
    if (minus_dxi) minus_dxi[k] = dxi[0];
    if (plus_dxi) plus_dxi[k] = dxi[1];
  }
}

}  // namespace ehd
