// Fused pull stream + MRT collide for the D2Q9 lattice (song2019 eq. (97), forcing eqs.
// (107)-(108)) with the boundary links of the half-way bounce-back walls.
//
//   f_i(x, t) = f*_i(x - c_i, t - 1)                       interior and periodic links
//   f_i(x, t) = f*_opp(i)(x, t - 1) + 6 w_i c_i.u_wall      links whose source x - c_i lies
//                                                            beyond a wall (rho_0 = 1)
//   f*(x, t)  = MrtCollideNode(f(x, t), F(x))
//
// Data layout: structure of arrays, f[q * n + j * nx + i], two buffers (read one, write the
// other), so the kernel is race-free and each row is independent (OpenMP over rows). Nodes of
// rows/columns that touch a wall or wrap in x take the general path; the rest of each row goes
// through a loop whose nine source streams are row pointers shifted by -c_x, which the compiler
// vectorises (`#pragma omp simd`, restrict pointers; check with -fopt-info-vec).
//
// StreamCollideD2Q9InPlace is the same update on one array (the AA pattern, see its section
// below), with the same collision and wall arithmetic, so the results are identical.
#include "stream_collide.h"

#include <immintrin.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "ehd_capsule/lbm/d2q9.h"

namespace ehd {
namespace {

struct KernelArgs {
  const double* src;
  double* dst;
  int nx, ny;
  std::size_t n;  // the population stream stride
  const double* fx;
  const double* fy;
  const double* s_nu_field;  // per node, or nullptr
  double s_nu_uniform;
  MrtRates rates;
  bool periodic_y;
  bool side_walls;
  double wall_u_bottom, wall_u_top;
  double* rho;
  double* ux;
  double* uy;
  double* scratch;  // kStreamChunk * 12 doubles per thread, or nullptr: plain stores
};

// With streaming stores the interior of a row is collided in chunks into an L1-resident scratch
// block and then copied out with non-temporal stores, which skip the read-for-ownership of the
// destination lines (216 -> 144 B/update for the populations, 280 -> 184 B in all).
constexpr int kStreamChunk = 256;
constexpr int kScratchStreams = 12;  // 9 populations + rho, ux, uy

inline void StreamCopy(const double* __restrict src, double* __restrict dst, int count) {
  int k = 0;
#if defined(__AVX512F__)
  for (; k < count && (reinterpret_cast<std::uintptr_t>(dst + k) & 63) != 0; ++k) dst[k] = src[k];
  for (; k + 8 <= count; k += 8) _mm512_stream_pd(dst + k, _mm512_loadu_pd(src + k));
#elif defined(__AVX__)
  for (; k < count && (reinterpret_cast<std::uintptr_t>(dst + k) & 31) != 0; ++k) dst[k] = src[k];
  for (; k + 4 <= count; k += 4) _mm256_stream_pd(dst + k, _mm256_loadu_pd(src + k));
#endif
  for (; k < count; ++k) dst[k] = src[k];
}

inline void StoreFence() {
#if defined(__SSE2__)
  _mm_sfence();  // make the non-temporal stores visible before the barrier
#endif
}

// Interior stretch [i_begin, i_end) of one row: 9 incoming streams g_q and 9 outgoing d_q (both
// kernels). The
// outgoing streams are incoming streams of other directions at the same index (d_opp(q) = g_q in
// an even step, d_q = g_opp(q) shifted in an odd one): no restrict on them. Each iteration reads
// all its populations before it writes any and no iteration touches another's locations, which
// is what `omp simd` asserts, so the loop still vectorises.
template <ForcingScheme kForcing, bool kVariableViscosity, bool kWallTerms = false>
void CollideRow(int i_begin, int i_end, const double* const* g, double* const* d,
                const double* __restrict fx, const double* __restrict fy,
                const double* __restrict s_nu_field, double s_nu_uniform, MrtRates rates,
                double* __restrict rho, double* __restrict ux, double* __restrict uy,
                const double* wall_coefficient = nullptr, double wall_u = 0.0) {
  const double *g0 = g[0], *g1 = g[1], *g2 = g[2], *g3 = g[3], *g4 = g[4];
  const double *g5 = g[5], *g6 = g[6], *g7 = g[7], *g8 = g[8];
  double *d0 = d[0], *d1 = d[1], *d2 = d[2], *d3 = d[3], *d4 = d[4];
  double *d5 = d[5], *d6 = d[6], *d7 = d[7], *d8 = d[8];
  // A wall row's links from beyond the wall: the stored f*_opp plus the moving wall's term as
  // MovingWallLink forms it (coefficient 6 w_q c_qx; 0 for the other links: fma(0, u, x) = x).
  double c[9] = {};
  if constexpr (kWallTerms) {
    for (int q = 0; q < 9; ++q) c[q] = wall_coefficient[q];
  }
#pragma omp simd
  for (int i = i_begin; i < i_end; ++i) {
    double f0 = g0[i], f1 = g1[i], f2 = g2[i], f3 = g3[i], f4 = g4[i];
    double f5 = g5[i], f6 = g6[i], f7 = g7[i], f8 = g8[i];
    if constexpr (kWallTerms) {
      f0 = std::fma(c[0], wall_u, f0);
      f1 = std::fma(c[1], wall_u, f1);
      f2 = std::fma(c[2], wall_u, f2);
      f3 = std::fma(c[3], wall_u, f3);
      f4 = std::fma(c[4], wall_u, f4);
      f5 = std::fma(c[5], wall_u, f5);
      f6 = std::fma(c[6], wall_u, f6);
      f7 = std::fma(c[7], wall_u, f7);
      f8 = std::fma(c[8], wall_u, f8);
    }
    const double s_nu = kVariableViscosity ? s_nu_field[i] : s_nu_uniform;
    double r, u, v;
    MrtCollideNode<kForcing>(f0, f1, f2, f3, f4, f5, f6, f7, f8, fx[i], fy[i], s_nu, rates, r, u,
                             v);
    d0[i] = f0;
    d1[i] = f1;
    d2[i] = f2;
    d3[i] = f3;
    d4[i] = f4;
    d5[i] = f5;
    d6[i] = f6;
    d7[i] = f7;
    d8[i] = f8;
    rho[i] = r;
    ux[i] = u;
    uy[i] = v;
  }
}

// Interior stretch [i_begin, i_end) of one row: all nine sources are inside the domain at the
// shifted row pointers s_q (s_q[i] = f*_q(i - c_qx, j - c_qy)).
template <ForcingScheme kForcing, bool kVariableViscosity>
void InteriorRow(int i_begin, int i_end, const double* __restrict s0, const double* __restrict s1,
                 const double* __restrict s2, const double* __restrict s3,
                 const double* __restrict s4, const double* __restrict s5,
                 const double* __restrict s6, const double* __restrict s7,
                 const double* __restrict s8, double* __restrict d0, double* __restrict d1,
                 double* __restrict d2, double* __restrict d3, double* __restrict d4,
                 double* __restrict d5, double* __restrict d6, double* __restrict d7,
                 double* __restrict d8, const double* __restrict fx, const double* __restrict fy,
                 const double* __restrict s_nu_field, double s_nu_uniform, MrtRates rates,
                 double* __restrict rho, double* __restrict ux, double* __restrict uy) {
  const double* g[9] = {s0, s1, s2, s3, s4, s5, s6, s7, s8};
  double* d[9] = {d0, d1, d2, d3, d4, d5, d6, d7, d8};
  CollideRow<kForcing, kVariableViscosity>(i_begin, i_end, g, d, fx, fy, s_nu_field, s_nu_uniform,
                                           rates, rho, ux, uy);
}

// The half-way bounce-back population of a y wall moving at u_w along x: f*_opp(q) + 6 w_q c_qx
// u_w. Both kernels call it, so they round it the same way.
inline double MovingWallCoefficient(int q) { return 6.0 * d2q9::kWeight[q] * d2q9::kCx[q]; }
// One explicit fused multiply-add (what the compiler contracted the plain expression to before),
// so every path rounds it the same way.
inline double MovingWallLink(double reflected, int q, double wall_u) {
  return std::fma(MovingWallCoefficient(q), wall_u, reflected);
}

// General node: gathers with wrap-around and bounce-back, then collides.
template <ForcingScheme kForcing, bool kVariableViscosity>
void BoundaryNode(const KernelArgs& a, int i, int j) {
  using namespace d2q9;
  const std::size_t node = static_cast<std::size_t>(j) * a.nx + i;
  double f[kQ];
  for (int q = 0; q < kQ; ++q) {
    int si = i - kCx[q];
    int sj = j - kCy[q];
    if (sj < 0 || sj >= a.ny) {
      if (a.periodic_y) {
        sj = (sj + a.ny) % a.ny;
      } else {
        const double wall_u = sj < 0 ? a.wall_u_bottom : a.wall_u_top;
        f[q] = MovingWallLink(a.src[kOpposite[q] * a.n + node], q, wall_u);
        continue;
      }
    }
    if (si < 0 || si >= a.nx) {
      if (a.side_walls) {
        f[q] = a.src[kOpposite[q] * a.n + node];  // resting side wall
        continue;
      }
      si = (si + a.nx) % a.nx;
    }
    f[q] = a.src[q * a.n + static_cast<std::size_t>(sj) * a.nx + si];
  }
  const double s_nu = kVariableViscosity ? a.s_nu_field[node] : a.s_nu_uniform;
  MrtCollideNode<kForcing>(f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8], a.fx[node],
                           a.fy[node], s_nu, a.rates, a.rho[node], a.ux[node], a.uy[node]);
  for (int q = 0; q < kQ; ++q) a.dst[q * a.n + node] = f[q];
}

template <ForcingScheme kForcing, bool kVariableViscosity>
void StreamCollideRows(const KernelArgs& a, int threads) {
  const int nx = a.nx, ny = a.ny;
  const std::size_t n = a.n;
#pragma omp parallel num_threads(threads) if (threads != 1)
  {
#pragma omp for schedule(static)
    for (int j = 0; j < ny; ++j) {
      const bool wall_row = !a.periodic_y && (j == 0 || j == ny - 1);
      if (wall_row || nx < 3) {
        for (int i = 0; i < nx; ++i) BoundaryNode<kForcing, kVariableViscosity>(a, i, j);
        continue;
      }
      BoundaryNode<kForcing, kVariableViscosity>(a, 0, j);
      const std::size_t row = static_cast<std::size_t>(j) * nx;
      const std::size_t row_south = static_cast<std::size_t>((j - 1 + ny) % ny) * nx;  // c_y = +1
      const std::size_t row_north = static_cast<std::size_t>((j + 1) % ny) * nx;       // c_y = -1
      const double* s = a.src;
      double* d = a.dst;
      if (a.scratch == nullptr) {
        InteriorRow<kForcing, kVariableViscosity>(
            1, nx - 1, s + row, s + n + row - 1, s + 2 * n + row_south, s + 3 * n + row + 1,
            s + 4 * n + row_north, s + 5 * n + row_south - 1, s + 6 * n + row_south + 1,
            s + 7 * n + row_north + 1, s + 8 * n + row_north - 1, d + row, d + n + row,
            d + 2 * n + row, d + 3 * n + row, d + 4 * n + row, d + 5 * n + row, d + 6 * n + row,
            d + 7 * n + row, d + 8 * n + row, a.fx + row, a.fy + row,
            kVariableViscosity ? a.s_nu_field + row : nullptr, a.s_nu_uniform, a.rates, a.rho + row,
            a.ux + row, a.uy + row);
      } else {
        double* w = a.scratch +
                    static_cast<std::size_t>(omp_get_thread_num()) * kScratchStreams * kStreamChunk;
        for (int i0 = 1; i0 < nx - 1; i0 += kStreamChunk) {
          const int len = std::min(kStreamChunk, nx - 1 - i0);
          const std::size_t c = row + i0;
          const std::size_t cs = row_south + i0, cn = row_north + i0;
          const int k = kStreamChunk;
          InteriorRow<kForcing, kVariableViscosity>(
              0, len, s + c, s + n + c - 1, s + 2 * n + cs, s + 3 * n + c + 1, s + 4 * n + cn,
              s + 5 * n + cs - 1, s + 6 * n + cs + 1, s + 7 * n + cn + 1, s + 8 * n + cn - 1, w,
              w + k, w + 2 * k, w + 3 * k, w + 4 * k, w + 5 * k, w + 6 * k, w + 7 * k, w + 8 * k,
              a.fx + c, a.fy + c, kVariableViscosity ? a.s_nu_field + c : nullptr, a.s_nu_uniform,
              a.rates, w + 9 * k, w + 10 * k, w + 11 * k);
          for (int q = 0; q < 9; ++q) StreamCopy(w + q * k, d + q * n + c, len);
          StreamCopy(w + 9 * k, a.rho + c, len);
          StreamCopy(w + 10 * k, a.ux + c, len);
          StreamCopy(w + 11 * k, a.uy + c, len);
        }
      }
      BoundaryNode<kForcing, kVariableViscosity>(a, nx - 1, j);
    }
    if (a.scratch != nullptr) StoreFence();
  }
}

// ---------------------------------------------------------------------------------------------
// In-place streaming on one population array (the AA pattern, as StreamCollideD3Q19InPlace):
//   even: node x reads f_i(x) from its own slot i, collides and writes f*_i(x) into its own slot
//         opp(i);
//   odd:  node x reads f_i(x) = f*_i(x - c_i) from slot opp(i) of x - c_i, collides and writes
//         f*_i(x) into slot i of x + c_i.
// Each location is read and written by one node only, so the update is race-free in place and the
// rows are independent. A link whose source lies beyond a wall reads slot i of its own node
// (f*_opp(i)(x) in either step) plus the moving wall's term, added when read; a link leaving
// through a wall in an odd step writes f*_i(x) into slot opp(i) of x. Same collision and wall
// arithmetic as the two-lattice kernel, so both give identical results (a test).

// Where the link q of node (i, j) comes from (sign = -1) or goes to (+1): 0 and the node index,
// or the wall it crosses (-1 bottom, -2 top, -3 side). The y walls take the corner diagonals.
inline int Neighbour(const KernelArgs& a, int i, int j, int q, int sign, std::size_t* node) {
  using namespace d2q9;
  int si = i + sign * kCx[q], sj = j + sign * kCy[q];
  if (sj < 0 || sj >= a.ny) {
    if (!a.periodic_y) return sj < 0 ? -1 : -2;
    sj = (sj + a.ny) % a.ny;
  }
  if (si < 0 || si >= a.nx) {
    if (a.side_walls) return -3;
    si = (si + a.nx) % a.nx;
  }
  *node = static_cast<std::size_t>(sj) * a.nx + si;
  return 0;
}

// General node in place: gather with wrap and bounce-back, collide, scatter.
template <ForcingScheme kForcing, bool kVariableViscosity, bool kOdd>
void InPlaceNode(const KernelArgs& a, int i, int j) {
  using namespace d2q9;
  double* const f = a.dst;
  const std::size_t n = a.n;
  const std::size_t node = static_cast<std::size_t>(j) * a.nx + i;
  double p[kQ];
  for (int q = 0; q < kQ; ++q) {
    std::size_t from = 0;
    const int wall = Neighbour(a, i, j, q, -1, &from);
    if (wall == -3) {
      p[q] = f[q * n + node];  // resting side wall
    } else if (wall != 0) {
      p[q] = MovingWallLink(f[q * n + node], q, wall == -1 ? a.wall_u_bottom : a.wall_u_top);
    } else {
      p[q] = kOdd ? f[kOpposite[q] * n + from] : f[q * n + node];
    }
  }
  const double s_nu = kVariableViscosity ? a.s_nu_field[node] : a.s_nu_uniform;
  MrtCollideNode<kForcing>(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], a.fx[node],
                           a.fy[node], s_nu, a.rates, a.rho[node], a.ux[node], a.uy[node]);
  for (int q = 0; q < kQ; ++q) {
    std::size_t to = 0;
    if (kOdd && Neighbour(a, i, j, q, +1, &to) == 0) {
      f[q * n + to] = p[q];
    } else {
      f[kOpposite[q] * n + node] = p[q];  // even step, or bounced back into its own node
    }
  }
}

// Even steps collide every row as one stretch (no streaming; a resting side wall adds nothing,
// and the y wall rows add the moving wall's term to the links from beyond it). Odd steps stream
// each row through its source and target rows; the first and last node of a periodic row go
// through the same vector loop with their x offsets wrapped, so only side-wall columns and
// degenerate grids take the node-by-node path.
template <ForcingScheme kForcing, bool kVariableViscosity, bool kOdd>
void InPlaceRows(const KernelArgs& a, int threads) {
  using namespace d2q9;
  const int nx = a.nx, ny = a.ny;
  const std::size_t n = a.n;
  double* const f = a.dst;  // the single array (src == dst)
  const bool general = nx < 3 || (!a.periodic_y && ny < 2);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads != 1)
  for (int j = 0; j < ny; ++j) {
    if (general) {
      for (int i = 0; i < nx; ++i) InPlaceNode<kForcing, kVariableViscosity, kOdd>(a, i, j);
      continue;
    }
    const bool wall_row = !a.periodic_y && (j == 0 || j == ny - 1);
    const std::size_t row = static_cast<std::size_t>(j) * nx;
    double coefficient[kQ];
    const int beyond = j == 0 ? 1 : -1;  // c_y of the links whose source lies beyond the wall
    for (int q = 0; q < kQ; ++q) {
      coefficient[q] = wall_row && kCy[q] == beyond ? MovingWallCoefficient(q) : 0.0;
    }
    const double wall_u = j == 0 ? a.wall_u_bottom : a.wall_u_top;
    // Nodes first .. last - 1 of the row, node i reading gather[q][i], writing scatter[q][i].
    auto stretch = [&](const double* const* gather, double* const* scatter, int first, int last) {
      const double* nu = kVariableViscosity ? a.s_nu_field + row : nullptr;
      if (wall_row) {
        CollideRow<kForcing, kVariableViscosity, true>(
            first, last, gather, scatter, a.fx + row, a.fy + row, nu, a.s_nu_uniform, a.rates,
            a.rho + row, a.ux + row, a.uy + row, coefficient, wall_u);
      } else {
        CollideRow<kForcing, kVariableViscosity>(first, last, gather, scatter, a.fx + row,
                                                 a.fy + row, nu, a.s_nu_uniform, a.rates,
                                                 a.rho + row, a.ux + row, a.uy + row);
      }
    };
    const double* gather[kQ];
    double* scatter[kQ];
    if constexpr (!kOdd) {
      for (int q = 0; q < kQ; ++q) {
        gather[q] = f + q * n + row;
        scatter[q] = f + kOpposite[q] * n + row;
      }
      stretch(gather, scatter, 0, nx);
      continue;
    }
    // Odd step: the source and target row of each link (y wrapped once per row) and its x
    // offset; a link from beyond a y wall reads its own node's slot q, one leaving through it
    // writes its own node's slot opp(q).
    const double* source_row[kQ];
    double* target_row[kQ];
    int gather_dx[kQ], scatter_dx[kQ];
    for (int q = 0; q < kQ; ++q) {
      const int sj = j - kCy[q], dj = j + kCy[q];
      if (!a.periodic_y && (sj < 0 || sj >= ny)) {
        source_row[q] = f + q * n + row;
        gather_dx[q] = 0;
      } else {
        source_row[q] =
            f + kOpposite[q] * n + static_cast<std::size_t>(lbm_kernels::WrapOnce(sj, ny)) * nx;
        gather_dx[q] = -kCx[q];
      }
      if (!a.periodic_y && (dj < 0 || dj >= ny)) {
        target_row[q] = f + kOpposite[q] * n + row;
        scatter_dx[q] = 0;
      } else {
        target_row[q] = f + q * n + static_cast<std::size_t>(lbm_kernels::WrapOnce(dj, ny)) * nx;
        scatter_dx[q] = kCx[q];
      }
    }
    // `edge`: node `first` alone, its x offsets wrapped (the interior never wraps).
    auto odd_stretch = [&](int first, int last, bool edge) {
      for (int q = 0; q < kQ; ++q) {
        gather[q] = source_row[q] +
                    (edge ? lbm_kernels::WrapOnce(first + gather_dx[q], nx) - first : gather_dx[q]);
        scatter[q] =
            target_row[q] +
            (edge ? lbm_kernels::WrapOnce(first + scatter_dx[q], nx) - first : scatter_dx[q]);
      }
      stretch(gather, scatter, first, last);
    };
    if (a.side_walls) {
      InPlaceNode<kForcing, kVariableViscosity, kOdd>(a, 0, j);
    } else {
      odd_stretch(0, 1, true);
    }
    odd_stretch(1, nx - 1, false);
    if (a.side_walls) {
      InPlaceNode<kForcing, kVariableViscosity, kOdd>(a, nx - 1, j);
    } else {
      odd_stretch(nx - 1, nx, true);
    }
  }
}

KernelArgs MakeKernelArgs(const lbm_kernels::StreamCollideArgs& g) {
  KernelArgs a;
  a.src = g.src;
  a.dst = g.dst;
  a.nx = g.nx;
  a.ny = g.ny;
  a.n = g.stream_stride;
  a.fx = g.force[0];
  a.fy = g.force[1];
  a.s_nu_field = g.s_nu_field;
  a.s_nu_uniform = g.s_nu_uniform;
  a.rates = g.rates;
  a.periodic_y = g.periodic_y;
  a.side_walls = g.side_walls;
  a.wall_u_bottom = g.wall_u_bottom;
  a.wall_u_top = g.wall_u_top;
  a.rho = g.rho;
  a.ux = g.u[0];
  a.uy = g.u[1];
  a.scratch = g.scratch;
  return a;
}

}  // namespace

namespace lbm_kernels {

const std::size_t kD2Q9ScratchDoublesPerThread =
    static_cast<std::size_t>(kScratchStreams) * kStreamChunk;

void StreamCollideD2Q9(const StreamCollideArgs& g) {
  const KernelArgs a = MakeKernelArgs(g);
  const bool guo = g.forcing == ForcingScheme::kGuo;
  const bool variable = g.s_nu_field != nullptr;
  if (guo && variable) {
    StreamCollideRows<ForcingScheme::kGuo, true>(a, g.threads);
  } else if (guo) {
    StreamCollideRows<ForcingScheme::kGuo, false>(a, g.threads);
  } else if (variable) {
    StreamCollideRows<ForcingScheme::kSplitMomentum, true>(a, g.threads);
  } else {
    StreamCollideRows<ForcingScheme::kSplitMomentum, false>(a, g.threads);
  }
}

template <bool kOdd>
void InPlaceRowsFor(const KernelArgs& a, bool guo, bool variable, int threads) {
  if (guo && variable) {
    InPlaceRows<ForcingScheme::kGuo, true, kOdd>(a, threads);
  } else if (guo) {
    InPlaceRows<ForcingScheme::kGuo, false, kOdd>(a, threads);
  } else if (variable) {
    InPlaceRows<ForcingScheme::kSplitMomentum, true, kOdd>(a, threads);
  } else {
    InPlaceRows<ForcingScheme::kSplitMomentum, false, kOdd>(a, threads);
  }
}

void StreamCollideD2Q9InPlace(const StreamCollideArgs& g, bool odd) {
  KernelArgs a = MakeKernelArgs(g);
  a.src = a.dst;
  const bool guo = g.forcing == ForcingScheme::kGuo;
  const bool variable = g.s_nu_field != nullptr;
  if (odd) {
    InPlaceRowsFor<true>(a, guo, variable, g.threads);
  } else {
    InPlaceRowsFor<false>(a, guo, variable, g.threads);
  }
}

void CollideNodeD2Q9(double* p, const double* force, double s_nu, const MrtRates& rates,
                     ForcingScheme forcing, double& rho, double* u) {
  auto kernel = forcing == ForcingScheme::kGuo ? &MrtCollideNode<ForcingScheme::kGuo>
                                               : &MrtCollideNode<ForcingScheme::kSplitMomentum>;
  kernel(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], force[0], force[1], s_nu, rates, rho,
         u[0], u[1]);
}

}  // namespace lbm_kernels
}  // namespace ehd
