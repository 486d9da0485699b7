// Per-node fluid viscosity for a viscosity contrast across the membrane.
//
// song2019 eqs. (117)-(118) and (153)-(154): with d the signed distance from a grid node to the
// membrane (d < 0 inside the capsule, > 0 outside), the smoothed Heaviside
//   H(d) = 0                                            d <= -2h
//        = (1/2) (1 + d/(2h) + (1/pi) sin(pi d/(2h)))  |d| <= 2h
//        = 1                                            d >= 2h
// (C1, monotone, H(0) = 1/2) blends the viscosities:
//   nu(x) = nu_in + (nu_out - nu_in) H(d(x))            (eq. (118): mu_c + (mu_a - mu_c) H).
// (The same as nu_out + (nu_in - nu_out)(1 - H); note H is the OUTSIDE indicator.)
//
// Cost: only the band of nodes within R = 2h + margin of the curve is recomputed each update,
// O(band) = O(M R / h) work. The curve is sampled at spacing <= h/2, each sample visits the nodes
// of its (2R)^2 box keeping the nearest sample per node, then a local Newton projection on the
// spline gives d (the sign from the outward normal at the foot point, as in sec. 5.4). Nodes that
// leave the band keep the side of their last d (0 or 1). This is valid while the markers move by
// less than `margin` between updates; otherwise (and on the first call, or after a change of the
// marker count) the whole field is refilled by a scanline inside/outside test, O(N^2) once.
// Periodic x (and y): markers may be unwrapped; node indices wrap. Non-periodic y: rows outside
// the grid are skipped.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/curve_segments.h"
#include "ehd_capsule/geometry/grid.h"

namespace ehd {

class ViscosityIndicator {
 public:
  // H(d) of eq. (117); h > 0. (A static member so it cannot clash with another free function.)
  static double SmoothedHeaviside(double signed_distance, double h);

  // margin in units of h (>= 0.5); throws std::invalid_argument for bad values.
  ViscosityIndicator(const Grid2D& grid, bool periodic_x, bool periodic_y, double viscosity_inside,
                     double viscosity_outside, double margin = 1.0);

  void Update(const ClosedCurve& curve);

  const std::vector<double>& viscosity() const { return viscosity_; }
  const std::vector<double>& heaviside() const { return heaviside_; }
  // Nodes whose value the last Update wrote (all nodes after a full refill).
  const std::vector<std::size_t>& updated_nodes() const { return updated_; }
  std::size_t band_size() const { return band_.size(); }
  bool last_update_was_full() const { return last_full_; }
  double viscosity_inside() const { return nu_in_; }
  double viscosity_outside() const { return nu_out_; }

 private:
  void Sample(const ClosedCurve& curve);
  void FullFill();
  void Set(std::size_t node, double h_value);
  double LocalSignedDistance(int k, double t, const Eigen::Vector2d& p) const;

  Grid2D grid_;
  bool periodic_x_, periodic_y_;
  double nu_in_, nu_out_;
  double band_radius_;  // 2h + margin h
  double margin_;       // in length units

  std::vector<double> viscosity_, heaviside_;
  std::vector<double> last_distance_;  // signed distance at the last band visit
  std::vector<std::uint32_t> stamp_;   // update counter when a node was last touched
  std::vector<double> best_d2_;
  std::vector<int> best_sample_;
  std::vector<std::size_t> band_, previous_band_, updated_;
  std::uint32_t counter_ = 0;
  bool has_state_ = false;
  bool last_full_ = false;
  Eigen::Matrix2Xd previous_markers_;
  CurveSegments segments_;  // the curve's splines, evaluated per segment
  // Dense samples of the spline (position, segment, offset in the segment), rebuilt per update.
  std::vector<double> sample_x_, sample_y_, sample_t_;
  std::vector<int> sample_k_;
  std::vector<double> crossings_;
};

}  // namespace ehd
