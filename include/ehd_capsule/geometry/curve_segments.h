// Direct evaluation of a ClosedCurve's periodic cubic splines on a known segment.
//
// ClosedCurve::At(s) locates the segment of s by a binary search (plus fmod) for every call; the
// per-step kernels (membrane forces, arc elements, the viscosity band) always know the segment,
// so they evaluate the cubic directly. On segment k, t in [0, h_k], u = h_k - t (natural form of
// the spline of periodic_spline.h, M = knot second derivatives):
//   S(t) = (M_k u^3 + M_{k+1} t^3)/(6 h) + (y_k/h - M_k h/6) u + (y_{k+1}/h - M_{k+1} h/6) t.
// Segment arc lengths use the same 5-point Gauss-Legendre rule as ClosedCurve::SegmentArcLength,
// and marker frames the same formulas as ClosedCurve::At, so results agree to rounding.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ehd_capsule/geometry/closed_curve.h"

namespace ehd {

struct SplineDerivatives {
  double x, y, dx, dy, ddx, ddy;  // position and derivatives in the chord-length parameter
};

class CurveSegments {
 public:
  // Caches knot spacing, values and second derivatives (no allocation once sized).
  void Update(const ClosedCurve& c);

  int size() const { return static_cast<int>(h_.size()); }
  int orientation() const { return orientation_; }
  double segment_parameter_length(int k) const { return h_[k]; }

  SplineDerivatives Evaluate(int k, double t) const;
  double SegmentArcLength(int k) const;
  // Position, unit tangent (counter-clockwise), outward normal and curvature at marker k.
  CurvePoint AtMarker(int k) const;

 private:
  std::vector<double> h_, x_, y_, mx_, my_;
  int orientation_ = 1;
};

}  // namespace ehd
