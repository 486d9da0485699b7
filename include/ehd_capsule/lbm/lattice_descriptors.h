// Lattice descriptors: what the generic lattice Boltzmann code needs to know about a velocity set
// and its MRT moment basis (velocities, weights, opposites, moment matrix M with the squared norms
// of its mutually orthogonal rows, and which relaxation rate each moment takes). The fluid class
// (lattice_boltzmann.h) and the reference collision (generic_mrt_collision.h) are written once
// over a descriptor; each lattice also has a hand-written fast kernel (mrt_collision.h for D2Q9,
// stream_collide_d3q19.cpp for D3Q19) tested against the generic collision.
//
// D2Q9: song2019 eq. (98) and the matrix after it (Lallemand & Luo, PRE 61, 6546 (2000)); the
// constants live in d2q9.h.
// D3Q19: velocities in the order of song2019 sec. 3.1.2 (c_1..c_6 the axes +x, -x, +y, -y, +z,
// -z; c_7..c_18 the face diagonals), moments of d'Humieres, Ginzburg, Krafczyk, Lallemand & Luo,
// Phil. Trans. R. Soc. A 360, 437 (2002), eq. (100) of the reference:
//   m = (rho, e, eps, j_x, q_x, j_y, q_y, j_z, q_z, 3p_xx, 3pi_xx, p_ww, pi_ww, p_xy, p_yz, p_xz,
//        m_x, m_y, m_z)
// with the rows built from their defining polynomials of c (|c|^2 = c.c):
//   e = 19|c|^2 - 30, eps = (21|c|^4 - 53|c|^2 + 24)/2, q_a = (5|c|^2 - 9) c_a,
//   3p_xx = 3c_x^2 - |c|^2, 3pi_xx = (3|c|^2 - 5)(3c_x^2 - |c|^2), p_ww = c_y^2 - c_z^2,
//   pi_ww = (3|c|^2 - 5)(c_y^2 - c_z^2), p_xy = c_x c_y, p_yz = c_y c_z, p_xz = c_x c_z,
//   m_x = (c_y^2 - c_z^2) c_x, m_y = (c_z^2 - c_x^2) c_y, m_z = (c_x^2 - c_y^2) c_z.
// (The reference's printed matrix lost entries in transcription; these polynomials reproduce its
// legible rows and are tested for orthogonality.)
#pragma once

#include <array>

#include "ehd_capsule/lbm/d2q9.h"

namespace ehd {

// Which relaxation rate a moment takes (MRT: one diagonal entry of S per moment).
enum class RateGroup {
  kConserved,     // rho, j: not relaxed (the force enters j by eqs. (107)-(108))
  kBulk,          // e: bulk viscosity (song2019 eq. (99)), rate s_e
  kEnergySquare,  // epsilon, rate s_epsilon
  kHeatFlux,      // q, rate s_q
  kShear,         // the traceless stress p: the kinematic viscosity, rate s_nu (per node)
  kHigherStress,  // pi (D3Q19 only), rate s_pi
  kGhost,         // m (D3Q19 only), rate s_m
};

struct D2Q9 {
  static constexpr int kDimension = 2;
  static constexpr int kQ = 9;
  static constexpr const char* kName = "D2Q9";
  static constexpr std::array<std::array<int, 2>, kQ> kC = {
      {{0, 0}, {1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 1}, {-1, 1}, {-1, -1}, {1, -1}}};
  static constexpr std::array<double, kQ> kWeight = d2q9::kWeight;
  static constexpr std::array<int, kQ> kOpposite = d2q9::kOpposite;
  static constexpr std::array<std::array<double, kQ>, kQ> kMomentMatrix = d2q9::kMomentMatrix;
  static constexpr std::array<double, kQ> kMomentNorm = d2q9::kMomentNorm;
  static constexpr std::array<RateGroup, kQ> kRateGroup = {
      RateGroup::kConserved, RateGroup::kBulk,     RateGroup::kEnergySquare,
      RateGroup::kConserved, RateGroup::kHeatFlux, RateGroup::kConserved,
      RateGroup::kHeatFlux,  RateGroup::kShear,    RateGroup::kShear};
  static constexpr std::array<int, kDimension> kMomentumMoment = {d2q9::kMomentumX,
                                                                  d2q9::kMomentumY};
  // The stress moments as combinations of the second-moment tensor Pi = sum f c c:
  // p_xx = Pi_xx - Pi_yy (row 7), p_xy = Pi_xy (row 8).
  static constexpr int kStressCount = 2;
  static constexpr std::array<int, kStressCount> kStressMoment = {d2q9::kStressXX, d2q9::kStressXY};
  static void StressMoments(const double pi[2][2], double out[kStressCount]) {
    out[0] = pi[0][0] - pi[1][1];
    out[1] = pi[0][1];
  }
};

namespace d3q19_detail {

constexpr int kQ = 19;
using Velocities = std::array<std::array<int, 3>, kQ>;
inline constexpr Velocities kC = {{{0, 0, 0},
                                   {1, 0, 0},
                                   {-1, 0, 0},
                                   {0, 1, 0},
                                   {0, -1, 0},
                                   {0, 0, 1},
                                   {0, 0, -1},
                                   {1, 1, 0},
                                   {1, -1, 0},
                                   {-1, 1, 0},
                                   {-1, -1, 0},
                                   {1, 0, 1},
                                   {-1, 0, 1},
                                   {1, 0, -1},
                                   {-1, 0, -1},
                                   {0, 1, 1},
                                   {0, 1, -1},
                                   {0, -1, 1},
                                   {0, -1, -1}}};

constexpr double MomentRow(int k, const std::array<int, 3>& c) {
  const double x = c[0], y = c[1], z = c[2];
  const double c2 = x * x + y * y + z * z;
  switch (k) {
    case 0:
      return 1.0;
    case 1:
      return 19.0 * c2 - 30.0;
    case 2:
      return (21.0 * c2 * c2 - 53.0 * c2 + 24.0) / 2.0;
    case 3:
      return x;
    case 4:
      return (5.0 * c2 - 9.0) * x;
    case 5:
      return y;
    case 6:
      return (5.0 * c2 - 9.0) * y;
    case 7:
      return z;
    case 8:
      return (5.0 * c2 - 9.0) * z;
    case 9:
      return 3.0 * x * x - c2;
    case 10:
      return (3.0 * c2 - 5.0) * (3.0 * x * x - c2);
    case 11:
      return y * y - z * z;
    case 12:
      return (3.0 * c2 - 5.0) * (y * y - z * z);
    case 13:
      return x * y;
    case 14:
      return y * z;
    case 15:
      return x * z;
    case 16:
      return (y * y - z * z) * x;
    case 17:
      return (z * z - x * x) * y;
    default:
      return (x * x - y * y) * z;
  }
}

constexpr std::array<std::array<double, kQ>, kQ> MomentMatrix() {
  std::array<std::array<double, kQ>, kQ> m{};
  for (int k = 0; k < kQ; ++k)
    for (int i = 0; i < kQ; ++i) m[k][i] = MomentRow(k, kC[i]);
  return m;
}

constexpr std::array<double, kQ> MomentNorms() {
  std::array<double, kQ> n{};
  for (int k = 0; k < kQ; ++k) {
    for (int i = 0; i < kQ; ++i) n[k] += MomentRow(k, kC[i]) * MomentRow(k, kC[i]);
  }
  return n;
}

constexpr std::array<int, kQ> Opposites() {
  std::array<int, kQ> o{};
  for (int i = 0; i < kQ; ++i)
    for (int j = 0; j < kQ; ++j)
      if (kC[j][0] == -kC[i][0] && kC[j][1] == -kC[i][1] && kC[j][2] == -kC[i][2]) o[i] = j;
  return o;
}

}  // namespace d3q19_detail

struct D3Q19 {
  static constexpr int kDimension = 3;
  static constexpr int kQ = 19;
  static constexpr const char* kName = "D3Q19";
  static constexpr d3q19_detail::Velocities kC = d3q19_detail::kC;
  static constexpr std::array<double, kQ> kWeight = {
      1.0 / 3,  1.0 / 18, 1.0 / 18, 1.0 / 18, 1.0 / 18, 1.0 / 18, 1.0 / 18,
      1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36,
      1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36, 1.0 / 36};
  static constexpr std::array<int, kQ> kOpposite = d3q19_detail::Opposites();
  static constexpr std::array<std::array<double, kQ>, kQ> kMomentMatrix =
      d3q19_detail::MomentMatrix();
  static constexpr std::array<double, kQ> kMomentNorm = d3q19_detail::MomentNorms();
  static constexpr std::array<RateGroup, kQ> kRateGroup = {
      RateGroup::kConserved,    RateGroup::kBulk,         RateGroup::kEnergySquare,
      RateGroup::kConserved,    RateGroup::kHeatFlux,     RateGroup::kConserved,
      RateGroup::kHeatFlux,     RateGroup::kConserved,    RateGroup::kHeatFlux,
      RateGroup::kShear,        RateGroup::kHigherStress, RateGroup::kShear,
      RateGroup::kHigherStress, RateGroup::kShear,        RateGroup::kShear,
      RateGroup::kShear,        RateGroup::kGhost,        RateGroup::kGhost,
      RateGroup::kGhost};
  static constexpr std::array<int, kDimension> kMomentumMoment = {3, 5, 7};
  // 3p_xx = 2 Pi_xx - Pi_yy - Pi_zz (row 9), p_ww = Pi_yy - Pi_zz (11), p_xy (13), p_yz (14),
  // p_xz (15).
  static constexpr int kStressCount = 5;
  static constexpr std::array<int, kStressCount> kStressMoment = {9, 11, 13, 14, 15};
  static void StressMoments(const double pi[3][3], double out[kStressCount]) {
    out[0] = 2.0 * pi[0][0] - pi[1][1] - pi[2][2];
    out[1] = pi[1][1] - pi[2][2];
    out[2] = pi[0][1];
    out[3] = pi[1][2];
    out[4] = pi[0][2];
  }
};

}  // namespace ehd
