// Inside/outside, regular/irregular classification and closest curve points of the grid points
// near the interface (see interface_classification.h).
#include "ehd_capsule/electric/interface_classification.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ehd {

void InterfaceClassification::Update(const Grid2D& grid, const ClosedCurve& curve,
                                     double band_width) {
  const double h = grid.h;
  if (!(band_width >= 1.5 * h)) {
    throw std::invalid_argument("InterfaceClassification: band_width must be >= 1.5 h = " +
                                std::to_string(1.5 * h) + ", got " + std::to_string(band_width));
  }
  if (curve.size() < 3) {
    throw std::invalid_argument("InterfaceClassification: curve needs >= 3 markers");
  }
  grid_ = grid;
  band_width_ = band_width;
  const std::size_t n = grid.size();
  if (side_.size() != n) {
    touched_.clear();
    irregular_points_.clear();
    side_.assign(n, 1);
    irregular_flag_.assign(n, 0);
    band_slot_.assign(n, -1);
    best_d2_.assign(n, std::numeric_limits<double>::infinity());
    best_s_.assign(n, 0.0);
  }
  // Reset what the previous call touched.
  for (int idx : touched_) {
    best_d2_[idx] = std::numeric_limits<double>::infinity();
    band_slot_[idx] = -1;
  }
  for (int idx : irregular_points_) irregular_flag_[idx] = 0;
  touched_.clear();
  irregular_points_.clear();
  band_points_.clear();
  band_s_.clear();
  band_d_.clear();
  band_kappa_.clear();
  pairs_.clear();

  // 1. Candidates: nearest spline sample within band_width + h.
  const PeriodicCubicSpline& xs = curve.x_spline();
  const PeriodicCubicSpline& ys = curve.y_spline();
  const double reach = band_width + h;
  const int m = curve.size();
  for (int k = 0; k < m; ++k) {
    const double s0 = curve.knot(k);
    const double s1 = (k + 1 < m) ? curve.knot(k + 1) : curve.period();
    const int samples = std::max(2, static_cast<int>(std::ceil((s1 - s0) / (0.5 * h))));
    for (int q = 0; q < samples; ++q) {
      const double s = s0 + (s1 - s0) * q / samples;
      const double px = xs.Value(s), py = ys.Value(s);
      const int i0 = std::max(0, static_cast<int>(std::ceil((px - reach - grid.x0) / h - 0.5)));
      const int i1 =
          std::min(grid.nx - 1, static_cast<int>(std::floor((px + reach - grid.x0) / h - 0.5)));
      const int j0 = std::max(0, static_cast<int>(std::ceil((py - reach - grid.y0) / h - 0.5)));
      const int j1 =
          std::min(grid.ny - 1, static_cast<int>(std::floor((py + reach - grid.y0) / h - 0.5)));
      for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
          const int idx = static_cast<int>(grid.index(i, j));
          const double dx = grid.x(i) - px, dy = grid.y(j) - py;
          const double d2 = dx * dx + dy * dy;
          if (d2 < best_d2_[idx]) {
            if (best_d2_[idx] == std::numeric_limits<double>::infinity()) touched_.push_back(idx);
            best_d2_[idx] = d2;
            best_s_[idx] = s;
          }
        }
      }
    }
  }
  // 2. Newton refinement of the closest point; keep |d| < band_width.
  const double period = curve.period();
  const double max_step = 0.5 * h;
  for (int idx : touched_) {
    const int i = idx % grid.nx, j = idx / grid.nx;
    const Eigen::Vector2d p(grid.x(i), grid.y(j));
    double s = best_s_[idx];
    for (int it = 0; it < 12; ++it) {
      const Eigen::Vector2d x(xs.Value(s), ys.Value(s));
      const Eigen::Vector2d d1(xs.Derivative(s), ys.Derivative(s));
      const Eigen::Vector2d d2(xs.SecondDerivative(s), ys.SecondDerivative(s));
      const double g = (x - p).dot(d1);
      const double dg = d1.squaredNorm() + (x - p).dot(d2);
      if (!(dg > 0.0)) break;
      const double step = std::clamp(g / dg, -max_step, max_step);
      s -= step;
      if (std::abs(step) < 1e-13 * period) break;
    }
    s = std::fmod(s, period);
    if (s < 0.0) s += period;
    const CurvePoint c = curve.At(s);
    const double d = (p - c.position).dot(c.normal);
    if (std::abs(d) >= band_width) continue;
    band_slot_[idx] = static_cast<int>(band_points_.size());
    band_points_.push_back(idx);
    band_s_.push_back(s);
    band_d_.push_back(d);
    band_kappa_.push_back(c.curvature);
  }
  // 3. Sides: sign of d in the band, row scan elsewhere. Points outside the markers' bounding
  // box grown by a chord length (more than the spline's bulge beyond its polygon) are outside.
  double max_chord = 0.0;
  for (int k = 0; k < m; ++k) {
    max_chord =
        std::max(max_chord, (curve.markers().col((k + 1) % m) - curve.markers().col(k)).norm());
  }
  const Eigen::Vector2d box_lo = curve.markers().rowwise().minCoeff().array() - max_chord;
  const Eigen::Vector2d box_hi = curve.markers().rowwise().maxCoeff().array() + max_chord;
  auto inside_box = [&](double x, double y) {
    return x > box_lo.x() && x < box_hi.x() && y > box_lo.y() && y < box_hi.y();
  };
  for (int j = 0; j < grid.ny; ++j) {
    int current = 0;
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t idx = grid.index(i, j);
      const int slot = band_slot_[idx];
      if (slot >= 0) {
        current = band_d_[slot] < 0.0 ? -1 : 1;
      } else if (current == 0) {
        const double x = grid.x(i), y = grid.y(j);
        current = inside_box(x, y) && curve.Contains(Eigen::Vector2d(x, y)) ? -1 : 1;
      }
      side_[idx] = static_cast<std::int8_t>(current);
    }
  }
  // 4. Irregular points and crossing stencil pairs (only band points can have them).
  for (int idx : band_points_) {
    const int i = idx % grid.nx, j = idx / grid.nx;
    const int me = side_[idx];
    const int nbr[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
    bool irregular = false;
    for (const auto& q : nbr) {
      if (q[0] < 0 || q[0] >= grid.nx || q[1] < 0 || q[1] >= grid.ny) continue;
      const int nidx = static_cast<int>(grid.index(q[0], q[1]));
      if (side_[nidx] == me) continue;
      irregular = true;
      const int slot = band_slot_[nidx];
      if (slot < 0) {
        throw std::runtime_error(
            "InterfaceClassification: a neighbour across the curve is outside the band "
            "(curve under-resolved by its markers?)");
      }
      pairs_.push_back(CrossingPair{idx, slot, side_[nidx]});
    }
    if (irregular) {
      irregular_flag_[idx] = 1;
      irregular_points_.push_back(idx);
    }
  }
}

GridDoubleCrossing<2> FindMultipleCrossing(const Grid2D& grid, const ClosedCurve& curve) {
  const double h = grid.h;
  // The spline sampled at <= h/4 of arc per segment (the chords' sagitta is kappa (h/4)^2 / 8).
  std::vector<Eigen::Vector2d> p;
  const int m = curve.size();
  for (int k = 0; k < m; ++k) {
    const double s0 = curve.knot(k);
    const double s1 = k + 1 < m ? curve.knot(k + 1) : curve.period();
    const int pieces =
        std::max(1, static_cast<int>(std::ceil(curve.SegmentArcLength(k) / (0.25 * h))));
    for (int q = 0; q < pieces; ++q) {
      const double s = s0 + (s1 - s0) * q / pieces;
      p.emplace_back(curve.x_spline().Value(s), curve.y_spline().Value(s));
    }
  }
  GridDoubleCrossing<2> out;
  const int n = static_cast<int>(p.size());
  for (int axis = 0; axis < 2; ++axis) {
    // Lines along `axis` through the cell centres of the other axis b; a chord crosses line j
    // where (a_j = coordinate(b, j)) lies between its ends (half-open, so a sample on a line
    // counts once); |cos| between the line and the chord's normal = |chord_b| / |chord|.
    const int b = 1 - axis;
    const int lines = grid.extent(b);
    std::vector<std::vector<std::pair<double, double>>> crossings(lines);
    for (int q = 0; q < n; ++q) {
      const Eigen::Vector2d& a0 = p[q];
      const Eigen::Vector2d& a1 = p[q + 1 < n ? q + 1 : 0];
      const double lo = std::min(a0[b], a1[b]), hi = std::max(a0[b], a1[b]);
      const int j0 = std::max(0, static_cast<int>(std::ceil((lo - grid.origin(b)) / h - 0.5)));
      const int j1 =
          std::min(lines - 1, static_cast<int>(std::floor((hi - grid.origin(b)) / h - 0.5)));
      const double length = (a1 - a0).norm();
      for (int j = j0; j <= j1; ++j) {
        const double c = grid.coordinate(b, j);
        if ((a0[b] < c) == (a1[b] < c)) continue;
        const double t = a0[axis] + (c - a0[b]) / (a1[b] - a0[b]) * (a1[axis] - a0[axis]);
        crossings[j].emplace_back(t, std::abs(a1[b] - a0[b]) / length);
      }
    }
    for (int j = 0; j < lines; ++j) {
      const LineDoubleCrossing c =
          ClosestDoubleCrossing(crossings[j], grid.origin(axis), h, grid.extent(axis));
      if (!c.found || (out.found && c.gap_h >= out.gap_h)) continue;
      out.found = true;
      out.axis = axis;
      out.gap_h = c.gap_h;
      out.node[axis] = c.node;
      out.node[b] = j;
    }
  }
  return out;
}

}  // namespace ehd
