// Weighted least-squares interpolation of phi_n^- and phi_eta^- at the markers from grid values
// (song2019 sec. 2.4.2, eq. (66)-(87), written as a fit as in docs/electric_solver.md).
//
// At marker X_c with unit normal n and tangent t, take the grid points x within alpha of X_c,
// local coordinates xi = (x - X_c).n, eta = (x - X_c).t, and fit
//   p(xi, eta) = c0 + c1 xi + c2 eta + c3 xi^2/2 + c4 xi eta + c5 eta^2/2
//                + c6 xi^3/6 + c7 xi^2 eta/2 + c8 xi eta^2/2 + c9 eta^3/6
// to the values of the minus-side extension: phi(x) for x in Omega^-, phi(x) - J(x) for x in
// Omega^+ (J from jump_relations.h), with weights d_alpha(r) = (1 + cos(pi r / alpha)) / 2,
// eq. (67). Then phi_n^- = c1, phi_eta^- = c2, phi_n^+ = phi_n^- + g (eq. (87)).
// Departure: the reference fits a quadratic (c0..c5), whose first derivatives are O(h^2) with
// the large constant of the one-sided third derivatives; the cubic makes them O(h^3) given a J
// that is O(d^4) (the cubic jump expansion with [d_xi(f/sigma)]), which cut the error of the
// Schur unknown G 2-5x on the sec. 2.5 examples and the sigma sweep (docs/electric_solver.md).
// A marker with < 14 points or an ill-conditioned cubic falls back to the quadratic.
// The fit's rows gamma_xi, gamma_eta (c1 = sum gamma_xi,i value_i) are computed once per curve.
//
// One-sided extrapolation (for [f/sigma] and [d_xi(f/sigma)] in the jump expansion): for each
// marker and each side, the same points of that side only, the same weights, and a weighted
// least-squares polynomial in (xi, eta), quadratic where that side has >= 9 points and the fit
// is well conditioned, else linear (>= 4 points), else the weighted average. Its value at
// (0, 0) and its xi-coefficient estimate the side's limit u^{+-}(X_c) to O(h^3) (quadratic) or
// O(h^2) (linear), and d_xi u^{+-} to O(h^2) / O(h). The previous side averages were O(h).
#pragma once

#include <vector>

#include "ehd_capsule/electric/interface_classification.h"
#include "ehd_capsule/geometry/closed_curve.h"

namespace ehd {

class NormalDerivativeFit {
 public:
  // radius alpha (>= 2 h and <= the classification's band width); degree 3 (cubic where
  // possible, the default) or 2 (the reference's quadratic). Throws std::invalid_argument for a
  // bad radius or degree and std::runtime_error if a marker's fit is rank deficient.
  void Update(const ClosedCurve& curve, const InterfaceClassification& classes, double radius,
              int degree = 3);

  // phi_n^- and phi_eta^- (derivative along the counter-clockwise tangent) at every marker.
  // band_jump holds J at every band point (only the outside ones are read).
  void Evaluate(const double* phi, const double* band_jump, double* dn_minus,
                double* dt_minus) const;
  // Same for the normal derivative only.
  void EvaluateNormal(const double* phi, const double* band_jump, double* dn_minus) const;
  // phi_n^- from the fit one degree lower (the quadratic where the fit is the cubic; else the
  // fit itself), for the fit-agreement check (interface_guarantees.h).
  void EvaluateNormalCheck(const double* phi, const double* band_jump, double* dn_minus) const;

  // Weighted averages, over each side's fit points of every marker, of a grid field (an O(h)
  // estimate of its one-sided limits). Sides without points give 0.
  void SideAverages(const double* field, double* minus_average, double* plus_average) const;

  // One-sided extrapolation of a grid field that is smooth on each side (see above): the limits
  // u^-(X_k), u^+(X_k) and the normal derivatives d_xi u^-(X_k), d_xi u^+(X_k) at every marker
  // (sides without points give 0). Any output pointer may be null.
  void SideExtrapolation(const double* field, double* minus_value, double* plus_value,
                         double* minus_dxi, double* plus_dxi) const;

  int markers() const { return static_cast<int>(offset_.size()) - 1; }
  // Entries of marker k: [offset(k), offset(k+1)).
  int offset(int k) const { return offset_[k]; }
  const std::vector<int>& points() const { return point_; }
  const std::vector<double>& gamma_xi() const { return gamma_xi_; }
  const std::vector<double>& gamma_eta() const { return gamma_eta_; }

 private:
  // phi_n^- from the fit rows `gamma` (gamma_xi_ or gamma_check_).
  void EvaluateNormalWith(const std::vector<double>& gamma, const double* phi,
                          const double* band_jump, double* dn_minus) const;

  std::vector<int> offset_;
  std::vector<int> point_;      // grid index
  std::vector<int> plus_slot_;  // band slot if the point is outside, -1 inside
  std::vector<double> gamma_xi_, gamma_eta_, gamma_check_, weight_;
  // Rows of the one-sided fits: value and xi-derivative at the marker of the fit of the side
  // the point is on.
  std::vector<double> side_value_, side_dxi_;
};

}  // namespace ehd
