// A closed smooth curve through M Lagrangian markers: the membrane or drop interface.
//
// The curve is the periodic cubic spline X(s) = (x(s), y(s)) through the markers, parametrised by
// cumulative chord length s in [0, P) (P = perimeter of the marker polygon). Any orientation of
// the markers is accepted; the unit normal always points out of the enclosed region (Omega^-)
// into the outer fluid (Omega^+), as in song2019 sec. 2.1. Geometry at parameter s:
//   tangent t = X'/|X'|, oriented counter-clockwise about the enclosed region,
//   normal  n = (t_y, -t_x) (outward for a counter-clockwise tangent),
//   curvature kappa = (x' y'' - y' x'') / |X'|^3 for the counter-clockwise orientation, so that
//   kappa = 1/r > 0 on a circle of radius r.
// Derivatives of marker scalars along the arc length l use d/dl = (1/|X'|) d/ds.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ehd_capsule/geometry/periodic_spline.h"

namespace ehd {

struct CurvePoint {
  Eigen::Vector2d position;
  Eigen::Vector2d tangent;  // unit, counter-clockwise about the enclosed region
  Eigen::Vector2d normal;   // unit, out of the enclosed region
  double curvature = 0.0;   // > 0 where the enclosed region is convex
  double speed = 0.0;       // |dX/ds|, ~1 for chord-length parametrisation
  double s = 0.0;           // spline parameter
};

class ClosedCurve {
 public:
  ClosedCurve() = default;
  explicit ClosedCurve(const Eigen::Matrix2Xd& markers) { Update(markers); }

  // Refits the splines to new marker positions (at least 3 markers, no two coincident).
  void Update(const Eigen::Matrix2Xd& markers);

  int size() const { return static_cast<int>(markers_.cols()); }
  const Eigen::Matrix2Xd& markers() const { return markers_; }
  double knot(int k) const { return knots_[k]; }
  const std::vector<double>& knots() const { return knots_; }
  double period() const { return period_; }
  // +1 if the markers run counter-clockwise, -1 if clockwise.
  int orientation() const { return orientation_; }

  CurvePoint At(double s) const;
  CurvePoint AtMarker(int k) const { return At(knots_[k]); }

  // Spline arc length between knots k and k+1 (periodic), and of the whole curve
  // (5-point Gauss-Legendre per segment).
  double SegmentArcLength(int k) const;
  double ArcLength() const;
  // Enclosed area and centroid of the spline curve, 1/2 \oint (x dy - y dx) by quadrature.
  double Area() const;
  Eigen::Vector2d Centroid() const;

  // Closest point of the curve to p: returns its parameter s; distance is |p - X(s)|.
  double ClosestParameter(const Eigen::Vector2d& p) const;
  // Signed distance to the curve: negative inside (Omega^-), positive outside.
  double SignedDistance(const Eigen::Vector2d& p) const;
  // True if p is strictly inside. Far from the curve the marker polygon's winding number decides;
  // within about two segment lengths the side of the closest spline point decides, so the answer
  // is consistent with the spline everywhere.
  bool Contains(const Eigen::Vector2d& p) const;

  // Fits a periodic spline to one scalar per marker over the same knots.
  PeriodicCubicSpline FitScalar(const std::vector<double>& values) const;
  // First and second derivatives of a fitted marker scalar along the arc length at parameter s.
  void ArcLengthDerivatives(const PeriodicCubicSpline& f, double s, double* d1, double* d2) const;

  const PeriodicCubicSpline& x_spline() const { return x_; }
  const PeriodicCubicSpline& y_spline() const { return y_; }

 private:
  bool PolygonContains(const Eigen::Vector2d& p) const;
  Eigen::Matrix2Xd markers_;
  std::vector<double> knots_;
  double period_ = 0.0;
  double max_chord_ = 0.0;
  int orientation_ = 1;
  PeriodicCubicSpline x_, y_;
};

}  // namespace ehd
