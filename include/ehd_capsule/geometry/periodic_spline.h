// Periodic cubic spline of a scalar over a closed parameter interval [0, period).
//
// Interpolates values y_k at increasing knots s_k (s_0 = 0, s_{M-1} < period) with C2 continuity
// and periodic wrap. The knot second derivatives M_k solve the cyclic tridiagonal system
//   h_{k-1} M_{k-1} + 2 (h_{k-1} + h_k) M_k + h_k M_{k+1}
//     = 6 [ (y_{k+1} - y_k)/h_k - (y_k - y_{k-1})/h_{k-1} ],   h_k = s_{k+1} - s_k,
// (the standard natural-form spline, song2019 sec. 3.3 uses it for the membrane curvature),
// solved by the Thomas algorithm with a Sherman-Morrison correction for the corner entries.
#pragma once

#include <vector>

namespace ehd {

class PeriodicCubicSpline {
 public:
  PeriodicCubicSpline() = default;

  // Fits the spline. knots must be strictly increasing, start at 0 and stay below period;
  // at least 3 knots. Throws std::invalid_argument otherwise.
  void Fit(const std::vector<double>& knots, double period, const std::vector<double>& values);

  int size() const { return static_cast<int>(values_.size()); }
  double period() const { return period_; }

  double Value(double s) const;
  double Derivative(double s) const;
  double SecondDerivative(double s) const;

  // Derivatives at knot k (exact spline values, no evaluation search).
  double DerivativeAtKnot(int k) const;
  double SecondDerivativeAtKnot(int k) const { return second_[k]; }

  // Segment containing s (after periodic wrap) and the local offset t = s - s_k.
  int Locate(double s, double* t) const;

  // Quadrature weights w_k with sum_k w_k y_k = integral over [0, period) of S_y(s) rho(s) ds,
  // S_y the periodic spline through values y at `knots`, the integral taken with the 5-point
  // Gauss rule of gauss_legendre.h on each segment: rho_at_nodes[5 k + q] is rho at node q of
  // segment k. S_y is linear in y (through the knot second derivatives M = T^-1 R y, T and R the
  // symmetric matrices of the file comment), so w = alpha + R T^-1 beta with alpha, beta the
  // weights of y and M in the segment integrals: one cyclic tridiagonal solve, O(M).
  static std::vector<double> IntegralWeights(const std::vector<double>& knots, double period,
                                             const std::vector<double>& rho_at_nodes);

 private:
  // Local cubic a + b t + c t^2 + d t^3 of the segment holding s, with t = s - s_k.
  struct Segment {
    double a, b, c, d, t;
  };
  Segment SegmentAt(double s) const;
  double Wrap(double s) const;
  std::vector<double> knots_;
  std::vector<double> values_;
  std::vector<double> second_;  // M_k
  double period_ = 0.0;
};

}  // namespace ehd
