// Grid points against an immersed closed curve (song2019 sec. 2.4, text after eq. (43)):
// each cell centre is inside (Omega^-, side -1) or outside (Omega^+, side +1); a point is
// irregular when its 5-point stencil has a neighbour on the other side, regular otherwise.
//
// Every grid point within band_width of the curve also gets its closest curve point: the spline
// parameter s*, the signed distance d = (x - X(s*)) . n (< 0 inside) and the curvature there.
// The jump expansions of the IIM (jump_relations.h) are taken about that closest point, where
// the local coordinates are xi = d, eta = 0.
//
// Algorithm (O(band points) + O(rows * markers), no global distance field): sample each spline
// segment at spacing <= h/2, give every grid point within band_width + h of a sample the nearest
// sample's parameter, refine it by Newton on (X(s) - x) . X'(s) = 0, keep |d| < band_width.
// Sides: inside the band sign(d); elsewhere a row scan carries the side of the last band point
// (the signed distance changes by at most h between neighbours, so a row cannot change side
// outside the band), starting each row from the polygon winding test.
#pragma once

#include <cstdint>
#include <vector>

#include "ehd_capsule/electric/interface_guarantees.h"
#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"

namespace ehd {

class InterfaceClassification {
 public:
  // band_width must be >= 1.5 h (the irregular points and their neighbours must lie in the
  // band); throws std::invalid_argument otherwise. Buffers are reused between calls.
  void Update(const Grid2D& grid, const ClosedCurve& curve, double band_width);

  const Grid2D& grid() const { return grid_; }
  double band_width() const { return band_width_; }
  // -1 inside the curve (Omega^-), +1 outside, per grid index.
  int side(std::size_t index) const { return side_[index]; }
  const std::vector<std::int8_t>& sides() const { return side_; }
  bool irregular(std::size_t index) const { return irregular_flag_[index] != 0; }
  const std::vector<int>& irregular_points() const { return irregular_points_; }

  // Band: grid points within band_width of the curve, with their closest curve points.
  int band_size() const { return static_cast<int>(band_points_.size()); }
  int band_slot(std::size_t index) const { return band_slot_[index]; }  // -1 if not in the band
  const std::vector<int>& band_points() const { return band_points_; }  // grid indices
  const std::vector<double>& band_parameter() const { return band_s_; }
  const std::vector<double>& band_distance() const { return band_d_; }
  const std::vector<double>& band_curvature() const { return band_kappa_; }

  // Stencil pairs that cross the curve: centre grid index, band slot of the neighbour across,
  // and the neighbour's side (+1: centre inside, neighbour outside; -1 the other way).
  struct CrossingPair {
    int centre;
    int neighbour_slot;
    int neighbour_side;
  };
  const std::vector<CrossingPair>& crossing_pairs() const { return pairs_; }

 private:
  Grid2D grid_;
  double band_width_ = 0.0;
  std::vector<std::int8_t> side_;
  std::vector<std::uint8_t> irregular_flag_;
  std::vector<int> irregular_points_;
  std::vector<int> band_slot_;
  std::vector<int> band_points_;
  std::vector<double> band_s_, band_d_, band_kappa_;
  std::vector<CrossingPair> pairs_;
  // Scratch for the candidate search.
  std::vector<double> best_d2_, best_s_;
  std::vector<int> touched_;
};

// A grid segment (between two neighbouring cell centres along an axis) that the curve crosses
// twice or more, nearly head-on (within 60 degrees of its normal): a part of the curve thinner
// than h along that axis (a biconcave dimple), which the 5-point stencil cannot see (both points
// on the same side). The curve is its periodic spline sampled at <= h/4 of arc (the crossings are
// those of the chords, within ~kappa h^2 / 128 of the spline's). Of all such segments, the one
// with the closest crossings; the 3D counterpart is in surface_classification_3d.h, the per-line
// search shared (ClosestDoubleCrossing, interface_guarantees.h). O(M + P / h) for perimeter P.
GridDoubleCrossing<2> FindMultipleCrossing(const Grid2D& grid, const ClosedCurve& curve);

}  // namespace ehd
