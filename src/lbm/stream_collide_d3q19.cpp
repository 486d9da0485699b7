// Fused pull stream + MRT collide for the D3Q19 lattice (song2019 sec. 3.1.2, eqs. (97),
// (100)-(101), forcing eqs. (107)-(108)) with the half-way bounce-back walls.
//
// Collision in moment space with the moment matrix of lattice_descriptors.h. The forward
// (m = M f) and backward (f += M^-1 dm) transforms are unrolled at compile time over the non-zero
// entries of M only (fold expressions over the index pack; a zero coefficient generates no
// instruction), so the kernel does what a hand-written one does without 361-entry loops.
// Equilibria (d'Humieres et al. 2002 with the LBGK-consistent coefficients; they are the moments
// of the incompressible polynomial equilibrium, tested against generic_mrt_collision.h):
//   e^eq = -11 rho + 19 |j'|^2,  eps^eq = 3 rho - 11/2 |j'|^2,  q^eq = -2/3 j',
//   3p_xx^eq = 3 j'_x^2 - |j'|^2,  p_ww^eq = j'_y^2 - j'_z^2,  p_xy^eq = j'_x j'_y, ...,
//   3pi_xx^eq = -3p_xx^eq / 2,  pi_ww^eq = -p_ww^eq / 2,  m^eq = 0,
// with j' = j + F/2 (eq. (107)) and j* = j + F (eq. (108)).
//
// Streaming: structure of arrays f[q * n + node], node = (k ny + j) nx + i, two buffers; rows
// (j, k) away from the y walls (and z walls in a closed box) stream their interior i = 1..nx-2
// from 19 row pointers shifted by -c_x (z wraps by row, periodic); the first and last node of a
// row and the wall rows gather node by node with wrap and bounce-back. OpenMP over rows.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include "ehd_capsule/lbm/generic_mrt_collision.h"
#include "ehd_capsule/lbm/lattice_descriptors.h"
#include "stream_collide.h"

namespace ehd {
namespace {

using L = D3Q19;
constexpr int kQ = L::kQ;
using Indices = std::make_index_sequence<kQ>;
constexpr int kChunk = 32;                  // nodes per interior block
constexpr int kPrefetchAhead = 4 * kChunk;  // nodes ahead of the block fetched into cache

// The 18 moving velocities form 9 opposite pairs (a_p, b_p = opp(a_p)). Every moment row is even
// (M[k][a] = M[k][opp(a)]: rho, e, eps, the stresses) or odd (M[k][opp(a)] = -M[k][a]: j, q,
// m), so with the pair sums s_p = f_a + f_b and differences d_p = f_a - f_b each moment needs
// half the terms, and the back transform gives f_a = E + O, f_b = E - O from the even and odd
// parts: half the arithmetic of the plain matrix products. The zero entries of M generate no
// code (if constexpr in fold expressions).
constexpr int kPairs = 9;
using PairIndices = std::make_index_sequence<kPairs>;

constexpr std::array<int, kPairs> PairFirsts() {
  std::array<int, kPairs> out{};
  int n = 0;
  for (int i = 1; i < kQ; ++i)
    if (i < L::kOpposite[i]) out[n++] = i;
  return out;
}
constexpr std::array<int, kPairs> kPairFirst = PairFirsts();

constexpr bool EvenMoment(int k) {
  for (int i = 1; i < kQ; ++i)
    if (L::kMomentMatrix[k][i] != L::kMomentMatrix[k][L::kOpposite[i]]) return false;
  return true;
}

// m_K from the rest population f0 and the pair sums s or differences d.
template <int K, std::size_t... P>
__attribute__((always_inline)) inline double Moment(double f0, const double* s, const double* d,
                                                    std::index_sequence<P...>) {
  constexpr bool even = EvenMoment(K);
  double v = 0.0;
  if constexpr (even && L::kMomentMatrix[K][0] != 0.0) v = L::kMomentMatrix[K][0] * f0;
  (
      [&]() __attribute__((always_inline)) {
        constexpr double c = L::kMomentMatrix[K][kPairFirst[P]];
        const double x = even ? s[P] : d[P];
        if constexpr (c == 1.0) {
          v += x;
        } else if constexpr (c == -1.0) {
          v -= x;
        } else if constexpr (c != 0.0) {
          v += c * x;
        }
      }(),
      ...);
  return v;
}

template <std::size_t... K>
__attribute__((always_inline)) inline void AllMoments(const double* f, double* m,
                                                      std::index_sequence<K...>) {
  double s[kPairs], d[kPairs];
  for (int p = 0; p < kPairs; ++p) {
    const double a = f[kPairFirst[p]], b = f[L::kOpposite[kPairFirst[p]]];
    s[p] = a + b;
    d[p] = a - b;
  }
  ((m[K] = Moment<static_cast<int>(K)>(f[0], s, d, PairIndices{})), ...);
}

// sum_k M[k][I] / |M_k|^2 dm_k over the moments of one parity (dm_rho = 0).
template <int I, bool kEven, std::size_t... K>
__attribute__((always_inline)) inline double BackPart(const double* dm, std::index_sequence<K...>) {
  double v = 0.0;
  (
      [&]() __attribute__((always_inline)) {
        constexpr double c = L::kMomentMatrix[K][I];
        if constexpr (c != 0.0 && K != 0 && EvenMoment(K) == kEven) {
          v += (c / L::kMomentNorm[K]) * dm[K];
        }
      }(),
      ...);
  return v;
}

template <std::size_t... P>
__attribute__((always_inline)) inline void AddBack(double* f, const double* dm,
                                                   std::index_sequence<P...>) {
  f[0] += BackPart<0, true>(dm, Indices{});
  (
      [&]() __attribute__((always_inline)) {
        constexpr int a = kPairFirst[P];
        const double even = BackPart<a, true>(dm, Indices{});
        const double odd = BackPart<a, false>(dm, Indices{});
        f[a] += even + odd;
        f[L::kOpposite[a]] += even - odd;
      }(),
      ...);
}

template <ForcingScheme kForcing>
__attribute__((always_inline)) inline void CollideD3Q19(double* f, double fx, double fy, double fz,
                                                        double s_nu, const MrtRates& r,
                                                        double& rho_out, double& ux_out,
                                                        double& uy_out, double& uz_out) {
  double m[kQ];
  AllMoments(f, m, Indices{});
  const double rho = m[0];
  const double ux = m[3] + 0.5 * fx, uy = m[5] + 0.5 * fy, uz = m[7] + 0.5 * fz;
  const double ux2 = ux * ux, uy2 = uy * uy, uz2 = uz * uz;
  const double u2 = ux2 + uy2 + uz2;
  const double pxx_eq = 3.0 * ux2 - u2, pww_eq = uy2 - uz2;
  double dm[kQ];
  dm[0] = 0.0;
  dm[1] = -r.s_e * (m[1] - (-11.0 * rho + 19.0 * u2));
  dm[2] = -r.s_epsilon * (m[2] - (3.0 * rho - 5.5 * u2));
  dm[3] = fx;
  dm[4] = -r.s_q * (m[4] + (2.0 / 3.0) * ux);
  dm[5] = fy;
  dm[6] = -r.s_q * (m[6] + (2.0 / 3.0) * uy);
  dm[7] = fz;
  dm[8] = -r.s_q * (m[8] + (2.0 / 3.0) * uz);
  dm[9] = -s_nu * (m[9] - pxx_eq);
  dm[10] = -r.s_pi * (m[10] + 0.5 * pxx_eq);
  dm[11] = -s_nu * (m[11] - pww_eq);
  dm[12] = -r.s_pi * (m[12] + 0.5 * pww_eq);
  dm[13] = -s_nu * (m[13] - ux * uy);
  dm[14] = -s_nu * (m[14] - uy * uz);
  dm[15] = -s_nu * (m[15] - ux * uz);
  dm[16] = -r.s_m * m[16];
  dm[17] = -r.s_m * m[17];
  dm[18] = -r.s_m * m[18];
  if constexpr (kForcing == ForcingScheme::kGuo) {
    // (1 - s_k/2) S_k with S = M F_i, F_i = w_i [3 c.F + 9 (c.u)(c.F) - 3 u.F].
    double source[kQ], s[kQ];
    const double uf = ux * fx + uy * fy + uz * fz;
    for (int i = 0; i < kQ; ++i) {
      const double cu = L::kC[i][0] * ux + L::kC[i][1] * uy + L::kC[i][2] * uz;
      const double cf = L::kC[i][0] * fx + L::kC[i][1] * fy + L::kC[i][2] * fz;
      source[i] = L::kWeight[i] * (3.0 * cf + 9.0 * cu * cf - 3.0 * uf);
    }
    AllMoments(source, s, Indices{});
    for (int k = 0; k < kQ; ++k) {
      if (L::kRateGroup[k] == RateGroup::kConserved) continue;
      dm[k] += (1.0 - 0.5 * MrtRate(L::kRateGroup[k], s_nu, r)) * s[k];
    }
  }
  AddBack(f, dm, PairIndices{});
  rho_out = rho;
  ux_out = ux;
  uy_out = uy;
  uz_out = uz;
}

// The half-way bounce-back population of a wall moving at u_w along x: f*_opp(q) + 6 w_q c_qx
// u_w, as one explicit fused multiply-add so both kernels round it the same way.
inline double MovingWallCoefficient(int q) { return 6.0 * L::kWeight[q] * L::kC[q][0]; }
inline double BounceBack(double reflected, int q, double wall_u) {
  return std::fma(MovingWallCoefficient(q), wall_u, reflected);
}

// The moving-wall term of the links of a wall row that come from beyond the wall: incoming
// population q is fma(coefficient[q], wall_u, stored value), the BounceBack of the general node
// (coefficient 6 w_q c_qx for those links, 0 for the others: fma(0, u, x) = x).
struct WallLinkTerms {
  double coefficient[kQ];
  double wall_u;
};

// One block of nodes i0 .. i0 + len - 1; kLength > 0 fixes len at compile time (the full blocks:
// the copies become straight vector moves), 0 takes it from the argument (the tail). With wall
// terms (a row next to a y wall), the incoming links get them.
template <ForcingScheme kForcing, bool kVariableViscosity, int kLength, bool kWallTerms>
__attribute__((always_inline)) inline void CollideBlock(const lbm_kernels::StreamCollideArgs& a,
                                                        const double* const* gather,
                                                        double* const* scatter, std::size_t row,
                                                        std::size_t i0, int tail_length,
                                                        const WallLinkTerms* wall) {
  const int len = kLength > 0 ? kLength : tail_length;
  alignas(64) double block[kQ][kChunk];
  alignas(64) double out_rho[kChunk], out_u[3][kChunk];
  for (int q = 0; q < kQ; ++q) {
    const double* __restrict src = gather[q] + i0;
    // 38 streams are more than the hardware prefetchers follow: fetch ahead by hand (a
    // prefetch past the end of an array does not fault).
    for (int l = 0; l < kChunk; l += 8) {
      __builtin_prefetch(src + kPrefetchAhead + l, 0, 3);
      __builtin_prefetch(scatter[q] + i0 + kPrefetchAhead + l, 1, 3);
    }
    if constexpr (kWallTerms) {
      const double coefficient = wall->coefficient[q], wall_u = wall->wall_u;
      for (int i = 0; i < len; ++i) block[q][i] = std::fma(coefficient, wall_u, src[i]);
    } else {
      for (int i = 0; i < len; ++i) block[q][i] = src[i];
    }
  }
  const std::size_t c = row + i0;
  const double* __restrict fx = a.force[0] + c;
  const double* __restrict fy = a.force[1] + c;
  const double* __restrict fz = a.force[2] + c;
  const double* __restrict nu = kVariableViscosity ? a.s_nu_field + c : nullptr;
  for (int i = 0; i < len; ++i) {
    double p[kQ];
#pragma GCC unroll 19
    for (int q = 0; q < kQ; ++q) p[q] = block[q][i];
    const double s_nu = kVariableViscosity ? nu[i] : a.s_nu_uniform;
    CollideD3Q19<kForcing>(p, fx[i], fy[i], fz[i], s_nu, a.rates, out_rho[i], out_u[0][i],
                           out_u[1][i], out_u[2][i]);
#pragma GCC unroll 19
    for (int q = 0; q < kQ; ++q) block[q][i] = p[q];
  }
  for (int q = 0; q < kQ; ++q) {
    double* __restrict dst = scatter[q] + i0;
    for (int i = 0; i < len; ++i) dst[i] = block[q][i];
  }
  for (int i = 0; i < len; ++i) a.rho[c + i] = out_rho[i];
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i < len; ++i) a.u[d][c + i] = out_u[d][i];
  }
}

// The nodes first .. last - 1 of a stretch, in blocks: the 19 incoming streams (gather[q] + i)
// are copied into an L1-resident block, the collision runs over the block (one SIMD loop over
// nodes, every access at a constant offset) and the block is copied to the outgoing streams
// (scatter[q] + i); rho and u go to the nodes row + i. Both kernels use it: they differ only in
// where the streams point.
template <ForcingScheme kForcing, bool kVariableViscosity, bool kWallTerms = false>
void InteriorChunks(const lbm_kernels::StreamCollideArgs& a, const double* const* gather,
                    double* const* scatter, std::size_t row, std::size_t first, std::size_t last,
                    const WallLinkTerms* wall = nullptr) {
  std::size_t i0 = first;
  for (; i0 + kChunk <= last; i0 += kChunk) {
    CollideBlock<kForcing, kVariableViscosity, kChunk, kWallTerms>(a, gather, scatter, row, i0,
                                                                   kChunk, wall);
  }
  if (i0 < last) {
    CollideBlock<kForcing, kVariableViscosity, 0, kWallTerms>(a, gather, scatter, row, i0,
                                                              static_cast<int>(last - i0), wall);
  }
}

template <ForcingScheme kForcing, bool kVariableViscosity>
void StreamCollideRows(const lbm_kernels::StreamCollideArgs& a) {
  const int nx = a.nx, ny = a.ny, nz = a.nz;
  const std::size_t n = a.stream_stride;
  const std::size_t plane = static_cast<std::size_t>(nx) * ny;
  auto wrap = [](int v, int period) { return (v % period + period) % period; };
  // General node: gather with wrap and bounce-back, then collide.
  auto boundary_node = [&](int i, int j, int k) {
    const std::size_t node =
        static_cast<std::size_t>(k) * plane + static_cast<std::size_t>(j) * nx + i;
    double f[kQ];
    for (int q = 0; q < kQ; ++q) {
      int si = i - L::kC[q][0], sj = j - L::kC[q][1], sk = k - L::kC[q][2];
      if (sj < 0 || sj >= ny) {
        if (a.periodic_y) {
          sj = wrap(sj, ny);
        } else {
          const double wall_u = sj < 0 ? a.wall_u_bottom : a.wall_u_top;
          f[q] = BounceBack(a.src[L::kOpposite[q] * n + node], q, wall_u);
          continue;
        }
      }
      if (si < 0 || si >= nx || sk < 0 || sk >= nz) {
        if (a.side_walls) {
          f[q] = a.src[L::kOpposite[q] * n + node];  // resting wall
          continue;
        }
        si = wrap(si, nx);
        sk = wrap(sk, nz);
      }
      f[q] = a.src[q * n + static_cast<std::size_t>(sk) * plane +
                   static_cast<std::size_t>(sj) * nx + si];
    }
    const double s_nu = kVariableViscosity ? a.s_nu_field[node] : a.s_nu_uniform;
    double r, ux, uy, uz;
    CollideD3Q19<kForcing>(f, a.force[0][node], a.force[1][node], a.force[2][node], s_nu, a.rates,
                           r, ux, uy, uz);
    for (int q = 0; q < kQ; ++q) a.dst[q * n + node] = f[q];
    a.rho[node] = r;
    a.u[0][node] = ux;
    a.u[1][node] = uy;
    a.u[2][node] = uz;
  };
  const long rows = static_cast<long>(ny) * nz;
#pragma omp parallel for schedule(static) num_threads(a.threads) if (a.threads != 1)
  for (long row_index = 0; row_index < rows; ++row_index) {
    const int j = static_cast<int>(row_index % ny), k = static_cast<int>(row_index / ny);
    const bool wall_row =
        (!a.periodic_y && (j == 0 || j == ny - 1)) || (a.side_walls && (k == 0 || k == nz - 1));
    if (wall_row || nx < 3) {
      for (int i = 0; i < nx; ++i) boundary_node(i, j, k);
      continue;
    }
    boundary_node(0, j, k);
    const std::size_t row = static_cast<std::size_t>(k) * plane + static_cast<std::size_t>(j) * nx;
    const double* s[kQ];
    for (int q = 0; q < kQ; ++q) {
      const int sj = wrap(j - L::kC[q][1], ny), sk = wrap(k - L::kC[q][2], nz);
      s[q] = a.src + q * n + static_cast<std::size_t>(sk) * plane +
             static_cast<std::size_t>(sj) * nx - L::kC[q][0];
    }
    double* d[kQ];
    for (int q = 0; q < kQ; ++q) d[q] = a.dst + q * n + row;
    InteriorChunks<kForcing, kVariableViscosity>(a, s, d, row, 1, nx - 1);
    boundary_node(nx - 1, j, k);
  }
}

// ---------------------------------------------------------------------------------------------
// In-place streaming on one population array (the AA pattern, Bailey et al. 2009). Two kinds of
// step alternate:
//   even: node x reads f_i(x) from its own slot i, collides and writes f*_i(x) into its own slot
//         opp(i) (no streaming);
//   odd:  node x reads f_i(x) = f*_i(x - c_i) from slot opp(i) of node x - c_i, collides, and
//         writes f*_i(x) into slot i of node x + c_i.
// Every location is read and written by one node only in either step, so the update is race-free
// in place. Half-way bounce-back: a link whose source lies beyond a wall reads f*_opp(i) of its
// own node (slot i of x after an even step, slot i of x written by the odd step) plus the moving
// wall's 6 w_i c_i.u_w, added when it is read (so the stored values stay the exact f* and the
// canonical post-collision state is recovered exactly); a link leaving through a wall in an odd
// step writes f*_i(x) into slot opp(i) of x. The arithmetic is that of the two-lattice kernel,
// so both give identical results (a test).
template <ForcingScheme kForcing, bool kVariableViscosity, bool kOdd>
void InPlaceRows(const lbm_kernels::StreamCollideArgs& a) {
  const int nx = a.nx, ny = a.ny, nz = a.nz;
  const std::size_t n = a.stream_stride;
  const std::size_t plane = static_cast<std::size_t>(nx) * ny;
  double* const f = a.dst;  // the single array (src == dst)
  auto wrap = [](int v, int period) { return (v % period + period) % period; };
  auto index = [&](int i, int j, int k) {
    return static_cast<std::size_t>(k) * plane + static_cast<std::size_t>(j) * nx + i;
  };
  // Where the link of direction q at node (i, j, k) comes from (sign = -1) or goes to (+1):
  // the node index, or -1 beyond a y wall (bottom: -1, top: -2) or a side wall (-3).
  auto neighbour = [&](int i, int j, int k, int q, int sign, long* node) {
    int si = i + sign * L::kC[q][0], sj = j + sign * L::kC[q][1], sk = k + sign * L::kC[q][2];
    if (sj < 0 || sj >= ny) {
      if (!a.periodic_y) return sj < 0 ? -1 : -2;
      sj = wrap(sj, ny);
    }
    if (si < 0 || si >= nx || sk < 0 || sk >= nz) {
      if (a.side_walls) return -3;
      si = wrap(si, nx);
      sk = wrap(sk, nz);
    }
    *node = static_cast<long>(index(si, sj, sk));
    return 0;
  };

  auto collide = [&](double* p, std::size_t node) {
    const double s_nu = kVariableViscosity ? a.s_nu_field[node] : a.s_nu_uniform;
    double r, ux, uy, uz;
    CollideD3Q19<kForcing>(p, a.force[0][node], a.force[1][node], a.force[2][node], s_nu, a.rates,
                           r, ux, uy, uz);
    a.rho[node] = r;
    a.u[0][node] = ux;
    a.u[1][node] = uy;
    a.u[2][node] = uz;
  };
  auto general_node = [&](int i, int j, int k) {
    const std::size_t node = index(i, j, k);
    double p[kQ];
    for (int q = 0; q < kQ; ++q) {
      long from = 0;
      const int wall = neighbour(i, j, k, q, -1, &from);
      if (wall != 0) {
        // f*_opp(q)(x) + 6 w c.u_w (a resting side wall: no term).
        p[q] = wall == -3
                   ? f[q * n + node]
                   : BounceBack(f[q * n + node], q, wall == -1 ? a.wall_u_bottom : a.wall_u_top);
      } else {
        p[q] = kOdd ? f[L::kOpposite[q] * n + static_cast<std::size_t>(from)] : f[q * n + node];
      }
    }
    collide(p, node);
    for (int q = 0; q < kQ; ++q) {
      if (!kOdd) {
        f[L::kOpposite[q] * n + node] = p[q];
        continue;
      }
      long to = 0;
      const int wall = neighbour(i, j, k, q, +1, &to);
      if (wall != 0) {
        f[L::kOpposite[q] * n + node] = p[q];  // bounces back into its own node
      } else {
        f[q * n + static_cast<std::size_t>(to)] = p[q];
      }
    }
  };
  // The links of wall row j (0 or ny - 1, ny >= 2) that come from beyond its wall.
  auto wall_terms = [&](int j) {
    WallLinkTerms terms;
    const int beyond = j == 0 ? 1 : -1;  // c_y of the links whose source lies beyond the wall
    terms.wall_u = j == 0 ? a.wall_u_bottom : a.wall_u_top;
    for (int q = 0; q < kQ; ++q) {
      terms.coefficient[q] = L::kC[q][1] == beyond ? MovingWallCoefficient(q) : 0.0;
    }
    return terms;
  };
  if constexpr (!kOdd) {
    // Even step: no streaming, and only the links from beyond a moving y wall differ from the
    // plain collision (a resting side wall adds nothing), so the rows between the y walls of a
    // plane are one contiguous stretch of nodes: long streams the prefetchers follow, no
    // per-row edge nodes.
    const int j_begin = a.periodic_y ? 0 : 1, j_end = a.periodic_y ? ny : ny - 1;
    // Nodes start .. start + count - 1 collide in place: slot q in, slot opp(q) out.
    auto collide_stretch = [&](std::size_t start, std::size_t count, const WallLinkTerms* terms) {
      const double* gather[kQ];
      double* scatter[kQ];
      for (int q = 0; q < kQ; ++q) {
        gather[q] = f + q * n + start;
        scatter[q] = f + L::kOpposite[q] * n + start;
      }
      if (terms != nullptr) {
        InteriorChunks<kForcing, kVariableViscosity, true>(a, gather, scatter, start, 0, count,
                                                           terms);
      } else {
        InteriorChunks<kForcing, kVariableViscosity>(a, gather, scatter, start, 0, count);
      }
    };
#pragma omp parallel for schedule(static) num_threads(a.threads) if (a.threads != 1)
    for (int k = 0; k < nz; ++k) {
      if (!a.periodic_y && ny < 2) {
        for (int i = 0; i < nx; ++i) general_node(i, 0, k);
      } else if (!a.periodic_y) {
        for (const int j : {0, ny - 1}) {
          const WallLinkTerms terms = wall_terms(j);
          collide_stretch(index(0, j, k), nx, &terms);
        }
      }
      if (j_end > j_begin) {
        collide_stretch(index(0, j_begin, k), static_cast<std::size_t>(j_end - j_begin) * nx,
                        nullptr);
      }
    }
    return;
  }
  const long rows = static_cast<long>(ny) * nz;
#pragma omp parallel for schedule(static) num_threads(a.threads) if (a.threads != 1)
  for (long row_index = 0; row_index < rows; ++row_index) {
    const int j = static_cast<int>(row_index % ny), k = static_cast<int>(row_index / ny);
    const bool y_wall_row = !a.periodic_y && (j == 0 || j == ny - 1);
    if ((a.side_walls && (k == 0 || k == nz - 1)) || nx < 3 || (y_wall_row && ny < 2)) {
      for (int i = 0; i < nx; ++i) general_node(i, j, k);
      continue;
    }
    const std::size_t row = index(0, j, k);
    if (y_wall_row) {
      // Links from beyond the wall read their own node's slot q (plus the wall term), links
      // leaving through it write their own node's slot opp(q); the others stream as inside.
      const WallLinkTerms terms = wall_terms(j);
      const double* gather[kQ];
      double* scatter[kQ];
      for (int q = 0; q < kQ; ++q) {
        const int sj = j - L::kC[q][1], dj = j + L::kC[q][1];
        gather[q] = sj < 0 || sj >= ny ? f + q * n + row
                                       : f + L::kOpposite[q] * n +
                                             index(0, sj, wrap(k - L::kC[q][2], nz)) - L::kC[q][0];
        scatter[q] = dj < 0 || dj >= ny
                         ? f + L::kOpposite[q] * n + row
                         : f + q * n + index(0, dj, wrap(k + L::kC[q][2], nz)) + L::kC[q][0];
      }
      general_node(0, j, k);
      InteriorChunks<kForcing, kVariableViscosity, true>(a, gather, scatter, row, 1, nx - 1,
                                                         &terms);
      general_node(nx - 1, j, k);
      continue;
    }
    // Odd step: node x gathers slot opp(q) of x - c_q and scatters to slot q of x + c_q. The
    // source and target rows of each direction (y, z wrapped once per row):
    const double* source_row[kQ];
    double* target_row[kQ];
    for (int q = 0; q < kQ; ++q) {
      const int sj = wrap(j - L::kC[q][1], ny), sk = wrap(k - L::kC[q][2], nz);
      source_row[q] = f + L::kOpposite[q] * n + index(0, sj, sk);
      const int dj = wrap(j + L::kC[q][1], ny), dk = wrap(k + L::kC[q][2], nz);
      target_row[q] = f + q * n + index(0, dj, dk);
    }
    // The first and last node of the row: through a side wall node by node; with periodic x
    // only the x offset wraps, read from the row pointers.
    auto edge_node = [&](int i) {
      if (a.side_walls) {
        general_node(i, j, k);
        return;
      }
      double p[kQ];
      for (int q = 0; q < kQ; ++q) p[q] = source_row[q][wrap(i - L::kC[q][0], nx)];
      collide(p, row + i);
      for (int q = 0; q < kQ; ++q) target_row[q][wrap(i + L::kC[q][0], nx)] = p[q];
    };
    edge_node(0);
    // Interior i = 1..nx-2: all 19 links stay inside the row's neighbours.
    const double* gather[kQ];
    double* scatter[kQ];
    for (int q = 0; q < kQ; ++q) {
      gather[q] = source_row[q] - L::kC[q][0];
      scatter[q] = target_row[q] + L::kC[q][0];
    }
    InteriorChunks<kForcing, kVariableViscosity>(a, gather, scatter, row, 1, nx - 1);
    edge_node(nx - 1);
  }
}

}  // namespace

namespace lbm_kernels {

void StreamCollideD3Q19(const StreamCollideArgs& a) {
  const bool guo = a.forcing == ForcingScheme::kGuo;
  const bool variable = a.s_nu_field != nullptr;
  if (guo && variable) {
    StreamCollideRows<ForcingScheme::kGuo, true>(a);
  } else if (guo) {
    StreamCollideRows<ForcingScheme::kGuo, false>(a);
  } else if (variable) {
    StreamCollideRows<ForcingScheme::kSplitMomentum, true>(a);
  } else {
    StreamCollideRows<ForcingScheme::kSplitMomentum, false>(a);
  }
}

void StreamCollideD3Q19InPlace(const StreamCollideArgs& a, bool odd) {
  const bool guo = a.forcing == ForcingScheme::kGuo;
  const bool variable = a.s_nu_field != nullptr;
  if (odd) {
    if (guo && variable) {
      InPlaceRows<ForcingScheme::kGuo, true, true>(a);
    } else if (guo) {
      InPlaceRows<ForcingScheme::kGuo, false, true>(a);
    } else if (variable) {
      InPlaceRows<ForcingScheme::kSplitMomentum, true, true>(a);
    } else {
      InPlaceRows<ForcingScheme::kSplitMomentum, false, true>(a);
    }
  } else if (guo && variable) {
    InPlaceRows<ForcingScheme::kGuo, true, false>(a);
  } else if (guo) {
    InPlaceRows<ForcingScheme::kGuo, false, false>(a);
  } else if (variable) {
    InPlaceRows<ForcingScheme::kSplitMomentum, true, false>(a);
  } else {
    InPlaceRows<ForcingScheme::kSplitMomentum, false, false>(a);
  }
}

void CollideNodeD3Q19(double* f, const double* force, double s_nu, const MrtRates& rates,
                      ForcingScheme forcing, double& rho, double* u) {
  if (forcing == ForcingScheme::kGuo) {
    CollideD3Q19<ForcingScheme::kGuo>(f, force[0], force[1], force[2], s_nu, rates, rho, u[0], u[1],
                                      u[2]);
  } else {
    CollideD3Q19<ForcingScheme::kSplitMomentum>(f, force[0], force[1], force[2], s_nu, rates, rho,
                                                u[0], u[1], u[2]);
  }
}

}  // namespace lbm_kernels
}  // namespace ehd
