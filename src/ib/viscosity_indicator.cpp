// Smoothed-Heaviside viscosity field, song2019 eqs. (117)-(118), (153)-(154), updated in a band
// around the membrane; see viscosity_indicator.h.
#include "ehd_capsule/ib/viscosity_indicator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ehd {
namespace {

constexpr double kPi = 3.141592653589793;

int WrapIndex(int i, int n, bool periodic) {
  if (periodic) {
    i %= n;
    return i < 0 ? i + n : i;
  }
  return (i >= 0 && i < n) ? i : -1;
}

}  // namespace

double ViscosityIndicator::SmoothedHeaviside(double d, double h) {
  if (d <= -2.0 * h) return 0.0;
  if (d >= 2.0 * h) return 1.0;
  const double x = d / (2.0 * h);
  return 0.5 * (1.0 + x + std::sin(kPi * x) / kPi);
}

ViscosityIndicator::ViscosityIndicator(const Grid2D& grid, bool periodic_x, bool periodic_y,
                                       double viscosity_inside, double viscosity_outside,
                                       double margin)
    : grid_(grid),
      periodic_x_(periodic_x),
      periodic_y_(periodic_y),
      nu_in_(viscosity_inside),
      nu_out_(viscosity_outside) {
  if (!(viscosity_inside > 0.0) || !(viscosity_outside > 0.0)) {
    throw std::invalid_argument("ViscosityIndicator: viscosities must be > 0, got inside=" +
                                std::to_string(viscosity_inside) +
                                ", outside=" + std::to_string(viscosity_outside));
  }
  if (!(margin >= 0.5)) {
    throw std::invalid_argument("ViscosityIndicator: margin must be >= 0.5 (cells), got " +
                                std::to_string(margin));
  }
  if (grid.nx < 1 || grid.ny < 1 || !(grid.h > 0.0)) {
    throw std::invalid_argument("ViscosityIndicator: empty grid or h <= 0");
  }
  margin_ = margin * grid.h;
  band_radius_ = 2.0 * grid.h + margin_;
  const std::size_t n = grid.size();
  viscosity_.assign(n, nu_out_);
  heaviside_.assign(n, 1.0);
  last_distance_.assign(n, std::numeric_limits<double>::infinity());
  stamp_.assign(n, 0);
  best_d2_.assign(n, 0.0);
  best_sample_.assign(n, 0);
}

void ViscosityIndicator::Set(std::size_t node, double h_value) {
  heaviside_[node] = h_value;
  viscosity_[node] = nu_in_ * (1.0 - h_value) + nu_out_ * h_value;  // exact at H = 0 and 1
}

void ViscosityIndicator::Sample(const ClosedCurve& curve) {
  segments_.Update(curve);
  const int m = curve.size();
  sample_x_.clear();
  sample_y_.clear();
  sample_t_.clear();
  sample_k_.clear();
  const double spacing = 0.5 * grid_.h;
  for (int k = 0; k < m; ++k) {
    // Chord-length parameter: hk is the chord; the spline segment is at most slightly
    // longer for a resolved curve, so one more sample than chord / spacing keeps gaps < h/2.
    const double hk = segments_.segment_parameter_length(k);
    const int n = static_cast<int>(std::ceil(hk / spacing)) + 1;
    for (int q = 0; q < n; ++q) {
      const double t = hk * q / n;
      const SplineDerivatives p = segments_.Evaluate(k, t);
      sample_x_.push_back(p.x);
      sample_y_.push_back(p.y);
      sample_t_.push_back(t);
      sample_k_.push_back(k);
    }
  }
}

void ViscosityIndicator::FullFill() {
  // Scanline inside/outside test on the polygon of the dense samples (a closed polygon; the
  // spline lies within O(h^2 kappa) of it, inside the smooth band that is recomputed anyway).
  const int ns = static_cast<int>(sample_x_.size());
  std::fill(heaviside_.begin(), heaviside_.end(), 1.0);
  std::fill(viscosity_.begin(), viscosity_.end(), nu_out_);
  double ymin = sample_y_[0], ymax = sample_y_[0];
  for (int q = 0; q < ns; ++q) {
    ymin = std::min(ymin, sample_y_[q]);
    ymax = std::max(ymax, sample_y_[q]);
  }
  const double h = grid_.h;
  const int j_lo = static_cast<int>(std::floor((ymin - grid_.y0) / h - 0.5));
  const int j_hi = static_cast<int>(std::ceil((ymax - grid_.y0) / h - 0.5));
  for (int ju = j_lo; ju <= j_hi; ++ju) {
    const int j = WrapIndex(ju, grid_.ny, periodic_y_);
    if (j < 0) continue;
    const double y = grid_.y0 + (ju + 0.5) * h;
    crossings_.clear();
    for (int q = 0; q < ns; ++q) {
      const int r = (q + 1 == ns) ? 0 : q + 1;
      const double ya = sample_y_[q], yb = sample_y_[r];
      if ((ya > y) != (yb > y)) {
        crossings_.push_back(sample_x_[q] + (y - ya) * (sample_x_[r] - sample_x_[q]) / (yb - ya));
      }
    }
    std::sort(crossings_.begin(), crossings_.end());
    for (std::size_t c = 0; c + 1 < crossings_.size(); c += 2) {
      const int i_lo = static_cast<int>(std::ceil((crossings_[c] - grid_.x0) / h - 0.5));
      const int i_hi = static_cast<int>(std::floor((crossings_[c + 1] - grid_.x0) / h - 0.5));
      for (int iu = i_lo; iu <= i_hi; ++iu) {
        const int i = WrapIndex(iu, grid_.nx, periodic_x_);
        if (i >= 0) Set(grid_.index(i, j), 0.0);
      }
    }
  }
  for (std::size_t node = 0; node < grid_.size(); ++node) {
    last_distance_[node] = heaviside_[node] > 0.5 ? std::numeric_limits<double>::infinity()
                                                  : -std::numeric_limits<double>::infinity();
  }
}

double ViscosityIndicator::LocalSignedDistance(int k, double t, const Eigen::Vector2d& p) const {
  // Newton on g(s) = (X(s) - p) . X'(s) from the nearest sample (within ~h/4 of the foot
  // point), steps limited to h/2, moving to the neighbouring segment when t leaves [0, h_k];
  // stops at 1e-9 h, far below what H can resolve.
  const int m = segments_.size();
  SplineDerivatives c = segments_.Evaluate(k, t);
  for (int it = 0; it < 6; ++it) {
    const double rx = c.x - p.x(), ry = c.y - p.y();
    const double g = rx * c.dx + ry * c.dy;
    const double dg = c.dx * c.dx + c.dy * c.dy + rx * c.ddx + ry * c.ddy;
    if (!(dg > 0.0)) break;
    const double step = std::clamp(g / dg, -0.5 * grid_.h, 0.5 * grid_.h);
    t -= step;
    while (t < 0.0) {
      k = (k == 0) ? m - 1 : k - 1;
      t += segments_.segment_parameter_length(k);
    }
    while (t > segments_.segment_parameter_length(k)) {
      t -= segments_.segment_parameter_length(k);
      k = (k + 1 == m) ? 0 : k + 1;
    }
    c = segments_.Evaluate(k, t);
    if (std::abs(step) < 1e-9 * grid_.h) break;
  }
  // Outward normal n = o (t_y, -t_x) for the spline direction X' (closed_curve.h).
  const double rx = p.x() - c.x, ry = p.y() - c.y;
  const double dist = std::hypot(rx, ry);
  const double outward = segments_.orientation() * (rx * c.dy - ry * c.dx);
  return outward >= 0.0 ? dist : -dist;
}

void ViscosityIndicator::Update(const ClosedCurve& curve) {
  const Eigen::Matrix2Xd& markers = curve.markers();
  bool full = !has_state_ || previous_markers_.cols() != markers.cols();
  if (!full) {
    double moved2 = 0.0;
    for (Eigen::Index k = 0; k < markers.cols(); ++k) {
      moved2 = std::max(moved2, (markers.col(k) - previous_markers_.col(k)).squaredNorm());
    }
    full = moved2 > margin_ * margin_;
  }
  Sample(curve);
  if (full) FullFill();
  ++counter_;
  if (counter_ == 0) {  // wrap-around of the stamp counter: clear the stamps
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    counter_ = 1;
  }
  previous_band_.swap(band_);
  band_.clear();
  const double h = grid_.h, r = band_radius_, r2 = r * r;
  const int ns = static_cast<int>(sample_x_.size());
  for (int q = 0; q < ns; ++q) {
    const double px = sample_x_[q], py = sample_y_[q];
    const int i_lo = static_cast<int>(std::ceil((px - r - grid_.x0) / h - 0.5));
    const int i_hi = static_cast<int>(std::floor((px + r - grid_.x0) / h - 0.5));
    const int j_lo = static_cast<int>(std::ceil((py - r - grid_.y0) / h - 0.5));
    const int j_hi = static_cast<int>(std::floor((py + r - grid_.y0) / h - 0.5));
    for (int ju = j_lo; ju <= j_hi; ++ju) {
      const int j = WrapIndex(ju, grid_.ny, periodic_y_);
      if (j < 0) continue;
      const double dy = grid_.y0 + (ju + 0.5) * h - py;
      for (int iu = i_lo; iu <= i_hi; ++iu) {
        const int i = WrapIndex(iu, grid_.nx, periodic_x_);
        if (i < 0) continue;
        const double dx = grid_.x0 + (iu + 0.5) * h - px;
        const double d2 = dx * dx + dy * dy;
        if (d2 > r2) continue;
        const std::size_t node = grid_.index(i, j);
        if (stamp_[node] != counter_) {
          stamp_[node] = counter_;
          band_.push_back(node);
          best_d2_[node] = d2;
          best_sample_[node] = q;
        } else if (d2 < best_d2_[node]) {
          best_d2_[node] = d2;
          best_sample_[node] = q;
        }
      }
    }
  }
  updated_.clear();
  const double width = grid_.width(), height = grid_.height();
  for (std::size_t node : band_) {
    const int i = static_cast<int>(node % static_cast<std::size_t>(grid_.nx));
    const int j = static_cast<int>(node / static_cast<std::size_t>(grid_.nx));
    const int q = best_sample_[node];
    // Periodic image of the node nearest to the sample (markers may be unwrapped).
    Eigen::Vector2d p(grid_.x(i), grid_.y(j));
    if (periodic_x_) p.x() += width * std::round((sample_x_[q] - p.x()) / width);
    if (periodic_y_) p.y() += height * std::round((sample_y_[q] - p.y()) / height);
    const double d = LocalSignedDistance(sample_k_[q], sample_t_[q], p);
    last_distance_[node] = d;
    Set(node, SmoothedHeaviside(d, h));
    if (!full) updated_.push_back(node);
  }
  // Nodes that left the band keep their side.
  for (std::size_t node : previous_band_) {
    if (stamp_[node] == counter_) continue;
    Set(node, last_distance_[node] > 0.0 ? 1.0 : 0.0);
    if (!full) updated_.push_back(node);
  }
  if (full) {
    updated_.resize(grid_.size());
    for (std::size_t node = 0; node < grid_.size(); ++node) updated_[node] = node;
  }
  previous_markers_ = markers;
  has_state_ = true;
  last_full_ = full;
}

}  // namespace ehd
