// D2Q9 multiple-relaxation-time collision of one node with a body force (song2019 eq. (97) and
// section 3.1.1; forcing by eqs. (107)-(108)).
//
//   m = M f,   j' = j + F/2                                             (107)
//   m*_k = m_k - s_k (m_k - m_k^eq(rho, j'))   for the non-conserved moments
//   j*   = j'' = j' + F/2 = j + F                                       (108)
//   f*   = M^-1 m*
// Equilibria (song2019 section 3.1.1, incompressible form with rho_0 = 1, so u = j'):
//   e^eq = -2 rho + 3 |j'|^2,  epsilon^eq = rho - 3 |j'|^2,  q^eq = -j',
//   p_xx^eq = j'_x^2 - j'_y^2,  p_xy^eq = j'_x j'_y.
// The text writes delta-rho in e^eq and epsilon^eq; with populations that carry the full density
// (sum f = rho) the weights' own moments make that -2 rho and rho (Lallemand & Luo 2000).
//
// Forcing. ForcingScheme::kSplitMomentum is eqs. (107)-(108) as written. Compared with Guo's
// forcing written in moment space (Guo, Zheng & Shi, PRE 65 046308 (2002); for MRT e.g. Yu & Fan
// 2010), it omits the source (1 - s_k/2) S_k of the non-conserved moments, with
//   S = M F_i,  F_i = w_i [3 c_i.F + 9 (c_i.u)(c_i.F) - 3 u.F]:
//   S_e = 6 u.F, S_epsilon = -6 u.F, S_qx = -F_x, S_qy = -F_y,
//   S_pxx = 2 (u_x F_x - u_y F_y), S_pxy = u_x F_y + u_y F_x.
// The q and epsilon terms do not reach the Navier-Stokes level; the stress terms do: without them
// the momentum equation carries the spurious stress -(1/s_nu - 1/2)(u F + F u) (and a bulk part
// from S_e). That error is quadratic in the flow amplitude (u F), so it vanishes at second order
// under diffusive scaling but is an O(Ma) relative error at fixed Mach number.
// ForcingScheme::kGuo adds the full Guo source (every non-conserved moment).
#pragma once

namespace ehd {

enum class ForcingScheme {
  kSplitMomentum,  // song2019 eqs. (107)-(108): j' = j + F/2 in m^eq, j'' = j + F after collision
  kGuo,            // eqs. (107)-(108) plus Guo's (1 - s_k/2) S_k for the non-conserved moments
};

// Relaxation rates that are the same at every node (the shear rate s_nu may vary per node).
struct MrtRates {
  double s_e;         // e (bulk viscosity), reference's s_1
  double s_epsilon;   // epsilon, reference's s_2
  double s_q;         // q_x, q_y (, q_z), reference's s_4 = s_6 (= s_8 in 3D)
  double s_pi = 1.8;  // D3Q19 only: 3pi_xx, pi_ww (reference's s_10, s_12)
  double s_m = 1.8;   // D3Q19 only: m_x, m_y, m_z (reference's s_16..s_18)
};

// Collides the nine populations f0..f8 of one node in place. (fx, fy) is the body-force density,
// s_nu the shear relaxation rate (reference's s_7 = s_8). Returns rho and u = j + F/2 (rho_0 = 1).
// Written with scalar references so a loop over nodes calling it vectorises.
template <ForcingScheme kForcing>
inline void MrtCollideNode(double& f0, double& f1, double& f2, double& f3, double& f4, double& f5,
                           double& f6, double& f7, double& f8, double fx, double fy, double s_nu,
                           const MrtRates& rates, double& rho_out, double& ux_out, double& uy_out) {
  const double axis_sum = f1 + f2 + f3 + f4;
  const double diagonal_sum = f5 + f6 + f7 + f8;
  const double rho = f0 + axis_sum + diagonal_sum;
  const double e = -4.0 * f0 - axis_sum + 2.0 * diagonal_sum;
  const double epsilon = 4.0 * f0 - 2.0 * axis_sum + diagonal_sum;
  const double diag_x = f5 - f6 - f7 + f8;
  const double diag_y = f5 + f6 - f7 - f8;
  const double jx = f1 - f3 + diag_x;
  const double jy = f2 - f4 + diag_y;
  const double qx = 2.0 * (f3 - f1) + diag_x;
  const double qy = 2.0 * (f4 - f2) + diag_y;
  const double pxx = f1 - f2 + f3 - f4;
  const double pxy = f5 - f6 + f7 - f8;

  // eq. (107): half the force enters the momentum used for the equilibria (and the output u).
  const double ux = jx + 0.5 * fx;
  const double uy = jy + 0.5 * fy;
  const double u2 = ux * ux + uy * uy;

  // m* - m for every moment.
  double d_e = -rates.s_e * (e - (-2.0 * rho + 3.0 * u2));
  double d_epsilon = -rates.s_epsilon * (epsilon - (rho - 3.0 * u2));
  double d_qx = -rates.s_q * (qx + ux);
  double d_qy = -rates.s_q * (qy + uy);
  double d_pxx = -s_nu * (pxx - (ux * ux - uy * uy));
  double d_pxy = -s_nu * (pxy - ux * uy);
  if constexpr (kForcing == ForcingScheme::kGuo) {
    const double u_dot_f = ux * fx + uy * fy;
    d_e += (1.0 - 0.5 * rates.s_e) * 6.0 * u_dot_f;
    d_epsilon -= (1.0 - 0.5 * rates.s_epsilon) * 6.0 * u_dot_f;
    d_qx -= (1.0 - 0.5 * rates.s_q) * fx;
    d_qy -= (1.0 - 0.5 * rates.s_q) * fy;
    d_pxx += (1.0 - 0.5 * s_nu) * 2.0 * (ux * fx - uy * fy);
    d_pxy += (1.0 - 0.5 * s_nu) * (ux * fy + uy * fx);
  }
  // eq. (108): j'' = j' + F/2, i.e. d_j = F. Back to populations with M^-1 = M^T / |row|^2.
  const double a = d_e * (1.0 / 36.0);
  const double b = d_epsilon * (1.0 / 36.0);
  const double cx = fx * (1.0 / 6.0);
  const double cy = fy * (1.0 / 6.0);
  const double dx = d_qx * (1.0 / 12.0);
  const double dy = d_qy * (1.0 / 12.0);
  const double p = d_pxx * 0.25;
  const double r = d_pxy * 0.25;
  const double axis_common = -a - 2.0 * b;
  const double diagonal_common = 2.0 * a + b;
  const double axis_x = cx - 2.0 * dx;
  const double axis_y = cy - 2.0 * dy;
  const double diagonal_x = cx + dx;
  const double diagonal_y = cy + dy;
  f0 += 4.0 * (b - a);
  f1 += axis_common + axis_x + p;
  f2 += axis_common + axis_y - p;
  f3 += axis_common - axis_x + p;
  f4 += axis_common - axis_y - p;
  f5 += diagonal_common + diagonal_x + diagonal_y + r;
  f6 += diagonal_common - diagonal_x + diagonal_y - r;
  f7 += diagonal_common - diagonal_x - diagonal_y + r;
  f8 += diagonal_common + diagonal_x - diagonal_y - r;

  rho_out = rho;
  ux_out = ux;
  uy_out = uy;
}

}  // namespace ehd
