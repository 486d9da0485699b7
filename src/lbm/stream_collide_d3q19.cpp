// Fused pull stream + MRT collide for the D3Q19 lattice (song2019 sec. 3.1.2, eqs. (97),
// (100)-(101), forcing eqs. (107)-(108)) with the half-way bounce-back walls.
//
// Collision in moment space with the moment matrix of lattice_descriptors.h. The forward
// (m = M f) and backward (f += M^-1 dm) transforms are written over the velocity shells with
// shared partial sums (GroupedMoments, GroupedAddBack; checked against the descriptor's M at
// compile time).
// Equilibria (d'Humieres et al. 2002 with the LBGK-consistent coefficients; they are the moments
// of the incompressible polynomial equilibrium, tested against generic_mrt_collision.h):
//   e^eq = -11 rho + 19 |j'|^2,  eps^eq = 3 rho - 11/2 |j'|^2,  q^eq = -2/3 j',
//   3p_xx^eq = 3 j'_x^2 - |j'|^2,  p_ww^eq = j'_y^2 - j'_z^2,  p_xy^eq = j'_x j'_y, ...,
//   3pi_xx^eq = -3p_xx^eq / 2,  pi_ww^eq = -p_ww^eq / 2,  m^eq = 0,
// with j' = j + F/2 (eq. (107)) and j* = j + F (eq. (108)).
//
// Streaming: structure of arrays f[q * n + node], node = (k ny + j) nx + i; two buffers, or one
// in place (the AA pattern, below, the default). Rows stream their interior i = 1..nx-2 from 19
// row pointers shifted by -c_x (y, z wrapped once per row); in place the first and last node of
// a row and the y wall rows go through the same vector path with their pointers adjusted, and
// only side-wall rows and corners gather node by node. OpenMP over rows.
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

// The transforms m = M f and f += M^T diag(1/|M_k|^2) dm, written over the velocity shells:
// the rest population, the 3 axis pairs (+-x, +-y, +-z) and the 12 face diagonals in 3 planes
// (xy, xz, yz) of 2 opposite pairs each. Every row of M (lattice_descriptors.h, MomentRow) is a
// polynomial of c that is constant on a shell up to the signs and squares of c's components, so
// each moment is a short combination of pair sums and differences shared between moments:
// about 60 additions forward and 60 back instead of the 2 x 150 of the sparse matrix products.
// The grouping is checked against the descriptor's M at compile time (below) and the collision
// against the generic matrix form at run time (d3q19_test).
//
// Populations: 0 rest; 1, 2 = +-x; 3, 4 = +-y; 5, 6 = +-z; xy plane 7 (1,1), 8 (1,-1), 9 (-1,1),
// 10 (-1,-1); xz plane 11 (1,1), 12 (-1,1), 13 (1,-1), 14 (-1,-1); yz plane 15 (1,1), 16 (1,-1),
// 17 (-1,1), 18 (-1,-1). Moments: 0 rho, 1 e, 2 eps, 3 j_x, 4 q_x, 5 j_y, 6 q_y, 7 j_z, 8 q_z,
// 9 3p_xx, 10 3pi_xx, 11 p_ww, 12 pi_ww, 13 p_xy, 14 p_yz, 15 p_xz, 16 m_x, 17 m_y, 18 m_z.
template <typename T>
__attribute__((always_inline)) constexpr inline void GroupedMoments(const T* f, T* m) {
  // Axis pairs: sums (even moments) and differences (odd moments).
  const T sx = f[1] + f[2], dx = f[1] - f[2];
  const T sy = f[3] + f[4], dy = f[3] - f[4];
  const T sz = f[5] + f[6], dz = f[5] - f[6];
  // Each diagonal plane: the pair along (1,1) and the pair along (1,-1) of its two axes.
  const T a_xy = f[7] + f[10], b_xy = f[8] + f[9], g_xy = f[7] - f[10], h_xy = f[8] - f[9];
  const T a_xz = f[11] + f[14], b_xz = f[13] + f[12], g_xz = f[11] - f[14], h_xz = f[13] - f[12];
  const T a_yz = f[15] + f[18], b_yz = f[16] + f[17], g_yz = f[15] - f[18], h_yz = f[16] - f[17];
  const T s_xy = a_xy + b_xy, s_xz = a_xz + b_xz, s_yz = a_yz + b_yz;  // plane sums
  // First-axis and second-axis momentum of each plane: sum c_1 f = g + h, sum c_2 f = g - h.
  const T x_xy = g_xy + h_xy, y_xy = g_xy - h_xy;
  const T x_xz = g_xz + h_xz, z_xz = g_xz - h_xz;
  const T y_yz = g_yz + h_yz, z_yz = g_yz - h_yz;
  const T axis = sx + sy + sz, diagonal = s_xy + s_xz + s_yz;
  m[0] = f[0] + axis + diagonal;
  m[1] = -30.0 * f[0] - 11.0 * axis + 8.0 * diagonal;  // 19 c^2 - 30
  m[2] = 12.0 * f[0] - 4.0 * axis + diagonal;          // (21 c^4 - 53 c^2 + 24) / 2
  const T xd = x_xy + x_xz, yd = y_xy + y_yz, zd = z_xz + z_yz;
  m[3] = dx + xd;  // c_x; (5 c^2 - 9) c_x: -4 on the axes, +1 on the diagonals
  m[4] = xd - 4.0 * dx;
  m[5] = dy + yd;
  m[6] = yd - 4.0 * dy;
  m[7] = dz + zd;
  m[8] = zd - 4.0 * dz;
  // 3 c_x^2 - c^2: axes (2, -1, -1), planes (1, 1, -2); the pi rows carry 3 c^2 - 5 = -2 | 1.
  const T p_axis = 2.0 * sx - sy - sz, p_diagonal = s_xy + s_xz - 2.0 * s_yz;
  const T w_axis = sy - sz, w_diagonal = s_xy - s_xz;  // c_y^2 - c_z^2
  m[9] = p_axis + p_diagonal;
  m[10] = p_diagonal - 2.0 * p_axis;
  m[11] = w_axis + w_diagonal;
  m[12] = w_diagonal - 2.0 * w_axis;
  m[13] = a_xy - b_xy;
  m[14] = a_yz - b_yz;
  m[15] = a_xz - b_xz;
  m[16] = x_xy - x_xz;  // (c_y^2 - c_z^2) c_x
  m[17] = y_yz - y_xy;  // (c_z^2 - c_x^2) c_y
  m[18] = z_xz - z_yz;  // (c_x^2 - c_y^2) c_z
}

// f_i += sum_k M[k][i] dm_k / |M_k|^2 (dm_0 = 0: mass is conserved), the transpose of the
// grouping above.
template <typename T>
__attribute__((always_inline)) constexpr inline void GroupedAddBack(T* f, const T* dm) {
  constexpr auto& norm = L::kMomentNorm;
  const T e = dm[1] * (1.0 / norm[1]), eps = dm[2] * (1.0 / norm[2]);
  const T jx = dm[3] * (1.0 / norm[3]), jy = dm[5] * (1.0 / norm[5]), jz = dm[7] * (1.0 / norm[7]);
  const T qx = dm[4] * (1.0 / norm[4]), qy = dm[6] * (1.0 / norm[6]), qz = dm[8] * (1.0 / norm[8]);
  const T p = dm[9] * (1.0 / norm[9]), pi = dm[10] * (1.0 / norm[10]);
  const T w = dm[11] * (1.0 / norm[11]), wpi = dm[12] * (1.0 / norm[12]);
  const T xy = dm[13] * (1.0 / norm[13]), yz = dm[14] * (1.0 / norm[14]);
  const T xz = dm[15] * (1.0 / norm[15]);
  const T mx = dm[16] * (1.0 / norm[16]), my = dm[17] * (1.0 / norm[17]);
  const T mz = dm[18] * (1.0 / norm[18]);
  f[0] += 12.0 * eps - 30.0 * e;
  // Axes: even part (e, eps, the stresses), odd part (j, q).
  const T axis = -11.0 * e - 4.0 * eps;
  const T p_axis = 2.0 * pi - p, w_axis = w - 2.0 * wpi;  // the y, z axes' share of 3p_xx, p_ww
  const T ex = axis - 2.0 * p_axis, ey = axis + p_axis + w_axis, ez = axis + p_axis - w_axis;
  const T ox = jx - 4.0 * qx, oy = jy - 4.0 * qy, oz = jz - 4.0 * qz;
  f[1] += ex + ox;
  f[2] += ex - ox;
  f[3] += ey + oy;
  f[4] += ey - oy;
  f[5] += ez + oz;
  f[6] += ez - oz;
  // Diagonals: each plane's even part, +- its off-diagonal stress for the (1,1) / (1,-1) pairs;
  // the odd part from j + q and the m rows.
  const T diagonal = 8.0 * e + eps;
  const T p_diagonal = p + pi, w_diagonal = w + wpi;
  const T cx = jx + qx, cy = jy + qy, cz = jz + qz;
  const auto plane = [](T * fp, T * fm_opp, T * fm, T * fp_opp, T even, T stress, T first, T second)
      __attribute__((always_inline)) {
    // fp = (1,1), fp_opp = (-1,-1), fm = (1,-1), fm_opp = (-1,1)
    const T ep = even + stress, em = even - stress;
    const T op = first + second, om = first - second;
    *fp += ep + op;
    *fp_opp += ep - op;
    *fm += em + om;
    *fm_opp += em - om;
  };
  plane(&f[7], &f[9], &f[8], &f[10], diagonal + p_diagonal + w_diagonal, xy, cx + mx, cy - my);
  plane(&f[11], &f[12], &f[13], &f[14], diagonal + p_diagonal - w_diagonal, xz, cx - mx, cz + mz);
  plane(&f[15], &f[17], &f[16], &f[18], diagonal - 2.0 * p_diagonal, yz, cy + my, cz - mz);
}

// The grouping reproduces the descriptor: m = M e_i column by column exactly (small integers),
// and the back transform of a unit dm_k gives M[k][i] / |M_k|^2 to rounding.
constexpr bool GroupedTransformsMatchTheDescriptor() {
  for (int i = 0; i < kQ; ++i) {
    double f[kQ] = {}, m[kQ] = {};
    f[i] = 1.0;
    GroupedMoments(f, m);
    for (int k = 0; k < kQ; ++k)
      if (m[k] != L::kMomentMatrix[k][i]) return false;
  }
  for (int k = 1; k < kQ; ++k) {
    double dm[kQ] = {}, f[kQ] = {};
    dm[k] = 1.0;
    GroupedAddBack(f, dm);
    for (int i = 0; i < kQ; ++i) {
      const double expected = L::kMomentMatrix[k][i] / L::kMomentNorm[k];
      const double error = f[i] - expected;
      if (error > 1e-16 || error < -1e-16) return false;
    }
  }
  return true;
}
static_assert(GroupedTransformsMatchTheDescriptor(),
              "the grouped D3Q19 transforms do not reproduce the descriptor's moment matrix");

template <ForcingScheme kForcing>
__attribute__((always_inline)) inline void CollideD3Q19(double* f, double fx, double fy, double fz,
                                                        double s_nu, const MrtRates& r,
                                                        double& rho_out, double& ux_out,
                                                        double& uy_out, double& uz_out) {
  double m[kQ];
  GroupedMoments(f, m);
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
    GroupedMoments(source, s);
    for (int k = 0; k < kQ; ++k) {
      if (L::kRateGroup[k] == RateGroup::kConserved) continue;
      dm[k] += (1.0 - 0.5 * MrtRate(L::kRateGroup[k], s_nu, r)) * s[k];
    }
  }
  GroupedAddBack(f, dm);
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

// The 19 populations of node i of a stretch, read from / written to their streams: one
// statement per stream (no inner loop, so the loop over nodes vectorises).
template <bool kWallTerms, std::size_t... Q>
__attribute__((always_inline)) inline void GatherNode(double* p, const double* const* src, long i,
                                                      const double* coefficient, double wall_u,
                                                      std::index_sequence<Q...>) {
  if constexpr (kWallTerms) {
    ((p[Q] = std::fma(coefficient[Q], wall_u, src[Q][i])), ...);
  } else {
    ((p[Q] = src[Q][i]), ...);
  }
}
template <std::size_t... Q>
__attribute__((always_inline)) inline void ScatterNode(const double* p, double* const* dst, long i,
                                                       std::index_sequence<Q...>) {
  ((dst[Q][i] = p[Q]), ...);
}

// The nodes first .. last - 1 of a stretch: node i reads its 19 incoming populations from
// gather[q][i], collides, and writes the outgoing ones to scatter[q][i]; rho and u go to the
// nodes row + i. One SIMD loop over the nodes straight on the streams: every statement names
// its stream (GatherNode, ScatterNode), so there is no inner loop and the 38 stream pointers are
// loop invariants. `ivdep`: the streams alias (in place, an outgoing stream is an incoming one of
// another direction at the same index), but each iteration reads all of its locations before
// writing any and touches no other iteration's. With wall terms (a row next to a y wall), the
// incoming links get them. Both kernels use it: they differ only in where the streams point.
// (The eighth session's version copied the streams through an L1 block and prefetched them by
// hand; direct access, once the loop vectorised, is 1.1-1.2x faster and the prefetch gained
// nothing: docs/lbm.md.)
template <ForcingScheme kForcing, bool kVariableViscosity, bool kWallTerms = false>
void CollideStretch(const lbm_kernels::StreamCollideArgs& a, const double* const* gather,
                    double* const* scatter, std::size_t row, std::size_t first, std::size_t last,
                    const WallLinkTerms* wall = nullptr) {
  if (first >= last) return;
  const long len = static_cast<long>(last - first);
  const double* src[kQ];
  double* dst[kQ];
  double coefficient[kQ];
  for (int q = 0; q < kQ; ++q) {
    src[q] = gather[q] + first;
    dst[q] = scatter[q] + first;
    coefficient[q] = kWallTerms ? wall->coefficient[q] : 0.0;
  }
  const double wall_u = kWallTerms ? wall->wall_u : 0.0;
  const std::size_t c = row + first;
  const double* __restrict fx = a.force[0] + c;
  const double* __restrict fy = a.force[1] + c;
  const double* __restrict fz = a.force[2] + c;
  const double* __restrict nu = kVariableViscosity ? a.s_nu_field + c : nullptr;
  double* __restrict rho = a.rho + c;
  double* __restrict ux = a.u[0] + c;
  double* __restrict uy = a.u[1] + c;
  double* __restrict uz = a.u[2] + c;
#pragma GCC ivdep
  for (long i = 0; i < len; ++i) {
    double p[kQ];
    GatherNode<kWallTerms>(p, src, i, coefficient, wall_u, Indices{});
    const double s_nu = kVariableViscosity ? nu[i] : a.s_nu_uniform;
    CollideD3Q19<kForcing>(p, fx[i], fy[i], fz[i], s_nu, a.rates, rho[i], ux[i], uy[i], uz[i]);
    ScatterNode(p, dst, i, Indices{});
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
    CollideStretch<kForcing, kVariableViscosity>(a, s, d, row, 1, nx - 1);
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
        CollideStretch<kForcing, kVariableViscosity, true>(a, gather, scatter, start, 0, count,
                                                           terms);
      } else {
        CollideStretch<kForcing, kVariableViscosity>(a, gather, scatter, start, 0, count);
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
    // Odd step: node x gathers slot opp(q) of x - c_q and scatters to slot q of x + c_q. Per
    // direction: the source and target rows (y, z wrapped once per row) and the x offset of the
    // link. In a y wall row the links from beyond the wall read their own node's slot q (plus
    // the wall term) and the links leaving through it write their own node's slot opp(q).
    const double* source_row[kQ];
    double* target_row[kQ];
    int gather_dx[kQ], scatter_dx[kQ];
    for (int q = 0; q < kQ; ++q) {
      const int sj = j - L::kC[q][1], dj = j + L::kC[q][1];
      if (!a.periodic_y && (sj < 0 || sj >= ny)) {
        source_row[q] = f + q * n + row;
        gather_dx[q] = 0;
      } else {
        source_row[q] =
            f + L::kOpposite[q] * n +
            index(0, lbm_kernels::WrapOnce(sj, ny), lbm_kernels::WrapOnce(k - L::kC[q][2], nz));
        gather_dx[q] = -L::kC[q][0];
      }
      if (!a.periodic_y && (dj < 0 || dj >= ny)) {
        target_row[q] = f + L::kOpposite[q] * n + row;
        scatter_dx[q] = 0;
      } else {
        target_row[q] =
            f + q * n +
            index(0, lbm_kernels::WrapOnce(dj, ny), lbm_kernels::WrapOnce(k + L::kC[q][2], nz));
        scatter_dx[q] = L::kC[q][0];
      }
    }
    const WallLinkTerms terms = y_wall_row ? wall_terms(j) : WallLinkTerms{};
    // Nodes first .. last - 1 through the vector path; `edge` wraps the x offsets (the first and
    // last node of a periodic row), which the interior i = 1 .. nx - 2 never needs.
    auto stretch = [&](int first, int last, bool edge) {
      const double* gather[kQ];
      double* scatter[kQ];
      for (int q = 0; q < kQ; ++q) {
        const int from =
            edge ? lbm_kernels::WrapOnce(first + gather_dx[q], nx) - first : gather_dx[q];
        const int to =
            edge ? lbm_kernels::WrapOnce(first + scatter_dx[q], nx) - first : scatter_dx[q];
        gather[q] = source_row[q] + from;
        scatter[q] = target_row[q] + to;
      }
      if (y_wall_row) {
        CollideStretch<kForcing, kVariableViscosity, true>(a, gather, scatter, row, first, last,
                                                           &terms);
      } else {
        CollideStretch<kForcing, kVariableViscosity>(a, gather, scatter, row, first, last);
      }
    };
    // The first and last node of the row: through a side wall node by node.
    if (a.side_walls) {
      general_node(0, j, k);
    } else {
      stretch(0, 1, true);
    }
    stretch(1, nx - 1, false);
    if (a.side_walls) {
      general_node(nx - 1, j, k);
    } else {
      stretch(nx - 1, nx, true);
    }
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
