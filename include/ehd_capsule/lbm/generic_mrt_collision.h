// MRT collision of one node written once over a lattice descriptor (lattice_descriptors.h), in
// matrix form (song2019 eq. (97) with the forcing of eqs. (107)-(108)):
//   m = M f,  j' = j + F/2,  m^eq = M f^eq(rho, j'),
//   m*_k = m_k - s_k (m_k - m^eq_k)  (non-conserved k),  j* = j + F,
//   f* = M^-1 m* = sum_k M_ki m*_k / |M_k|^2,
// with the incompressible polynomial equilibrium (rho_0 = 1)
//   f^eq_i = w_i [rho + 3 c_i.u + 9/2 (c_i.u)^2 - 3/2 |u|^2],
// whose moments are the m^eq of song2019 sec. 3.1.1 for D2Q9 and, for D3Q19, those of
// d'Humieres et al. (2002) with the LBGK-consistent free coefficients (e^eq = -11 rho + 19 j^2,
// eps^eq = 3 rho - 11/2 j^2, q^eq = -2/3 j, pi^eq = -p^eq/2, m^eq = 0).
// ForcingScheme::kGuo adds (1 - s_k/2) S_k, S = M F_i, F_i = w_i [3 c.F + 9 (c.u)(c.F) - 3 u.F],
// to the non-conserved moments (mrt_collision.h).
//
// This is the reference: O(Q^2) per node. The fast kernels (MrtCollideNode for D2Q9, the D3Q19
// kernel) are tested against it; D3Q19 also runs through it where speed does not matter
// (initialisation).
#pragma once

#include "ehd_capsule/lbm/lattice_descriptors.h"
#include "ehd_capsule/lbm/mrt_collision.h"

namespace ehd {

inline double MrtRate(RateGroup g, double s_nu, const MrtRates& r) {
  switch (g) {
    case RateGroup::kConserved:
      return 0.0;
    case RateGroup::kBulk:
      return r.s_e;
    case RateGroup::kEnergySquare:
      return r.s_epsilon;
    case RateGroup::kHeatFlux:
      return r.s_q;
    case RateGroup::kShear:
      return s_nu;
    case RateGroup::kHigherStress:
      return r.s_pi;
    case RateGroup::kGhost:
      return r.s_m;
  }
  return 0.0;
}

// f: the node's kQ populations (in place); force: kDimension components; outputs rho and
// u = j + F/2.
template <class L, ForcingScheme kForcing>
void GenericMrtCollide(double* f, const double* force, double s_nu, const MrtRates& rates,
                       double& rho_out, double* u_out) {
  constexpr int Q = L::kQ, D = L::kDimension;
  double m[Q];
  for (int k = 0; k < Q; ++k) {
    double v = 0.0;
    for (int i = 0; i < Q; ++i) v += L::kMomentMatrix[k][i] * f[i];
    m[k] = v;
  }
  const double rho = m[0];
  double u[D], u2 = 0.0;
  for (int a = 0; a < D; ++a) {
    u[a] = m[L::kMomentumMoment[a]] + 0.5 * force[a];
    u2 += u[a] * u[a];
  }
  double feq[Q], source[Q];
  for (int i = 0; i < Q; ++i) {
    double cu = 0.0, cf = 0.0, uf = 0.0;
    for (int a = 0; a < D; ++a) {
      cu += L::kC[i][a] * u[a];
      cf += L::kC[i][a] * force[a];
      uf += u[a] * force[a];
    }
    feq[i] = L::kWeight[i] * (rho + 3.0 * cu + 4.5 * cu * cu - 1.5 * u2);
    source[i] = L::kWeight[i] * (3.0 * cf + 9.0 * cu * cf - 3.0 * uf);
  }
  double mstar[Q];
  for (int k = 0; k < Q; ++k) {
    const RateGroup g = L::kRateGroup[k];
    if (g == RateGroup::kConserved) {
      mstar[k] = m[k];
      continue;
    }
    double meq = 0.0, sk = 0.0;
    for (int i = 0; i < Q; ++i) {
      meq += L::kMomentMatrix[k][i] * feq[i];
      sk += L::kMomentMatrix[k][i] * source[i];
    }
    const double s = MrtRate(g, s_nu, rates);
    mstar[k] = m[k] - s * (m[k] - meq);
    if constexpr (kForcing == ForcingScheme::kGuo) mstar[k] += (1.0 - 0.5 * s) * sk;
  }
  for (int a = 0; a < D; ++a) mstar[L::kMomentumMoment[a]] += force[a];  // eq. (108)
  for (int i = 0; i < Q; ++i) {
    double v = 0.0;
    for (int k = 0; k < Q; ++k) v += L::kMomentMatrix[k][i] * mstar[k] / L::kMomentNorm[k];
    f[i] = v;
  }
  rho_out = rho;
  for (int a = 0; a < D; ++a) u_out[a] = u[a];
}

}  // namespace ehd
