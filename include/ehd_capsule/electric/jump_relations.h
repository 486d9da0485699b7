// Jump of the two smooth extensions phi^+_ext - phi^-_ext near the interface (song2019 eq. (81),
// corrected in docs/electric_solver.md), expanded about the closest interface point X*, where the
// local coordinates of a grid point are xi = d (signed distance), eta = 0:
//
//   J(x) = [phi] + [phi_xi] d + 1/2 [phi_xixi] d^2 + O(d^3),
//   [phi] = w,  [phi_xi] = g,  [phi_xixi] = [f/sigma] - w'' + g chi'' = [f/sigma] - w'' - g kappa
//
// (chi'' = -kappa with kappa > 0 where Omega^- is convex; w'' is the second arc-length derivative
// of w). Taking the expansion about the closest point removes the eta terms, so [phi_eta],
// [phi_etaeta] and [phi_xieta] (whose eq. (81) coefficient v' chi'' is a typo for w' chi'') are
// not needed. We add the cubic term (1/6)[phi_xixixi] d^3, which the reference does not use
// (it lowers the O(h) local error at irregular points, most visibly for strongly curved
// interfaces). In normal coordinates (xi, s) the Laplacian is
//   phi_xixi + kappa/(1 + kappa xi) phi_xi + (1/(1 + kappa xi)) d_s((1/(1 + kappa xi)) phi_s),
// and d/dxi of it at xi = 0 gives
//   [phi_xixixi] = [d_xi(f/sigma)] - kappa [f/sigma] + 2 kappa^2 g + 3 kappa w'' + kappa' w' - g''
// (kappa', w', g'' along the arc; [f/sigma] and [d_xi(f/sigma)] come from one-sided fits of the
// grid values of F on each side, NormalDerivativeFit::SideExtrapolation).
// J is affine in g: J = J_data(w, w', w'', [f/sigma]) + g (d - kappa d^2/2 + kappa^2 d^3/3)
// - g'' d^3 / 6.
// Check (sec. 2.5 ex. 1): w = 0, g = 2, kappa = 2, f = 0 gives [phi_xixi] = -4 = phi^+_rr(1/2)
// and [phi_xixixi] = 16 = phi^+_rrr(1/2); the expansion 2(d - d^2 + 4 d^3/3) is the Taylor
// series of log(1 + 2d) = phi^+ - phi^- to O(d^4).
#pragma once

namespace ehd {

// Part of J that does not depend on g.
// f_over_sigma_jump = [f/sigma], f_over_sigma_dxi_jump = [d_xi(f/sigma)] at the closest point.
inline double JumpDataPart(double w, double w_s, double w_ss, double f_over_sigma_jump,
                           double f_over_sigma_dxi_jump, double kappa, double kappa_s, double d) {
  const double second = f_over_sigma_jump - w_ss;
  const double third =
      f_over_sigma_dxi_jump - kappa * f_over_sigma_jump + 3.0 * kappa * w_ss + kappa_s * w_s;
  return w + d * d * (0.5 * second + d * third / 6.0);
}
// Coefficient of g in J.
inline double JumpGCoefficient(double d, double kappa) {
  return d * (1.0 + d * kappa * (-0.5 + d * kappa / 3.0));
}
// Coefficient of g'' (second arc-length derivative) in J.
inline double JumpGssCoefficient(double d) { return -d * d * d / 6.0; }

}  // namespace ehd
