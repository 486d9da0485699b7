// Jump of the two smooth extensions phi^+_ext - phi^-_ext near the interface (song2019 eq. (81),
// corrected in notes/fast-iim.md), expanded about the closest interface point X*, where the local
// coordinates of a grid point are xi = d (signed distance), eta = 0:
//
//   J(x) = [phi] + [phi_xi] d + 1/2 [phi_xixi] d^2 + O(d^3),
//   [phi] = w,  [phi_xi] = g,  [phi_xixi] = [f/sigma] - w'' + g chi'' = [f/sigma] - w'' - g kappa
//
// (chi'' = -kappa with kappa > 0 where Omega^- is convex; w'' is the second arc-length derivative
// of w). Taking the expansion about the closest point removes the eta terms, so [phi_eta],
// [phi_etaeta] and [phi_xieta] (whose eq. (81) coefficient v' chi'' is a typo for w' chi'') are
// not needed. J is affine in g: J = J_data(w, w'', [f/sigma]) + g (d - kappa d^2 / 2).
// Check (sec. 2.5 ex. 1): w = 0, g = 2, kappa = 2, f = 0 gives [phi_xixi] = -4 = phi^+_rr(1/2).
#pragma once

namespace ehd {

// Part of J that does not depend on g.
inline double JumpDataPart(double w, double w_ss, double f_over_sigma_jump, double d) {
  return w + 0.5 * (f_over_sigma_jump - w_ss) * d * d;
}
// Coefficient of g in J.
inline double JumpGCoefficient(double d, double kappa) { return d - 0.5 * kappa * d * d; }

}  // namespace ehd
