// Smoothed-Heaviside viscosity field, song2019 eqs. (117)-(118); see viscosity_field.h.
#include "ehd_capsule/coupling/viscosity_field.h"

#include <algorithm>
#include <cmath>

namespace ehd {

double SmoothedHeaviside(double d, double h) {
  if (d <= -2.0 * h) return 0.0;
  if (d >= 2.0 * h) return 1.0;
  return 0.5 * (1.0 + d / (2.0 * h) + std::sin(M_PI * d / (2.0 * h)) / M_PI);
}

ViscosityField::ViscosityField(const Grid2D& grid, bool periodic_x)
    : grid_(grid), periodic_x_(periodic_x), heaviside_(grid.size()), in_band_(grid.size()) {}

void ViscosityField::Update(const ClosedCurve& curve, double nu_inside, double nu_outside,
                            std::vector<double>& nu) {
  const int nx = grid_.nx, ny = grid_.ny;
  const double h = grid_.h;
  const Eigen::Matrix2Xd& X = curve.markers();
  const int m = static_cast<int>(X.cols());
  auto wrap = [&](int i) { return ((i % nx) + nx) % nx; };

  // Outside everywhere, then fill the polygon interior row by row (even-odd crossings).
  std::fill(heaviside_.begin(), heaviside_.end(), 1.0);
  for (int j = 0; j < ny; ++j) {
    const double y = grid_.y(j);
    crossings_.clear();
    for (int k = 0, km = m - 1; k < m; km = k++) {
      const double yi = X(1, k), yj = X(1, km);
      if ((yi > y) != (yj > y)) {
        crossings_.push_back(X(0, k) + (X(0, km) - X(0, k)) * (y - yi) / (yj - yi));
      }
    }
    std::sort(crossings_.begin(), crossings_.end());
    for (std::size_t c = 0; c + 1 < crossings_.size(); c += 2) {
      // Nodes with x in (x_a, x_b): i from ceil((x_a - x0)/h - 1/2) to floor((x_b - x0)/h - 1/2).
      const int i0 = static_cast<int>(std::ceil((crossings_[c] - grid_.x0) / h - 0.5));
      const int i1 = static_cast<int>(std::floor((crossings_[c + 1] - grid_.x0) / h - 0.5));
      for (int i = i0; i <= i1; ++i) {
        const int iw = periodic_x_ ? wrap(i) : i;
        if (iw >= 0 && iw < nx) heaviside_[grid_.index(iw, j)] = 0.0;
      }
    }
  }

  // Band: nodes within 2h + the longest chord of a marker get the exact signed distance.
  double max_chord = 0.0;
  for (int k = 0; k < m; ++k)
    max_chord = std::max(max_chord, (X.col((k + 1) % m) - X.col(k)).norm());
  const double reach = 2.0 * h + max_chord;
  const int r = static_cast<int>(std::ceil(reach / h)) + 1;
  band_nodes_.clear();
  for (int k = 0; k < m; ++k) {
    const int ic = static_cast<int>(std::floor((X(0, k) - grid_.x0) / h));
    const int jc = static_cast<int>(std::floor((X(1, k) - grid_.y0) / h));
    for (int j = std::max(0, jc - r); j <= std::min(ny - 1, jc + r); ++j) {
      for (int i = ic - r; i <= ic + r; ++i) {
        const int iw = periodic_x_ ? wrap(i) : i;
        if (iw < 0 || iw >= nx) continue;
        const std::size_t n = grid_.index(iw, j);
        if (in_band_[n]) continue;
        // Position of the node's image nearest to the marker (periodic in x).
        const Eigen::Vector2d p(grid_.x0 + (i + 0.5) * h, grid_.y(j));
        if ((p - X.col(k)).norm() > reach) continue;
        in_band_[n] = 1;
        band_nodes_.push_back(static_cast<int>(n));
        heaviside_[n] = SmoothedHeaviside(curve.SignedDistance(p), h);
      }
    }
  }
  for (int n : band_nodes_) in_band_[n] = 0;

  nu.resize(grid_.size());
  for (std::size_t n = 0; n < nu.size(); ++n) {
    nu[n] = nu_inside + (nu_outside - nu_inside) * heaviside_[n];
  }
}

}  // namespace ehd
