// song2019 eqs. (104) and (106) with the cosine kernel (103), or the roma3 kernel, as a tensor
// product in 2 or 3 dimensions; see immersed_boundary.h.
#include "ehd_capsule/ib/immersed_boundary.h"

#include <stdexcept>
#include <string>

#include "ehd_capsule/ib/delta_kernel.h"

namespace ehd {
namespace {

template <int D>
void CheckField(const Grid<D>& grid, const std::vector<double>& f, int component) {
  if (f.size() != grid.size()) {
    throw std::invalid_argument("ImmersedBoundary: field component " + std::to_string(component) +
                                " has " + std::to_string(f.size()) + " entries, grid has " +
                                std::to_string(grid.size()));
  }
}

// The point's stencil along one axis for the kernel, and its nodes per axis.
// (roma3_even_odd: roma3's; the loops use trapezoid3's along each component's own axis.)
template <DeltaKernel K>
DeltaStencil AxisStencil(double xi) {
  if constexpr (K == DeltaKernel::kCosine4) {
    return CosineDeltaStencil(xi);
  } else if constexpr (K == DeltaKernel::kTrapezoid3) {
    return Trapezoid3DeltaStencil(xi);
  } else {
    return Roma3DeltaStencil(xi);
  }
}
template <DeltaKernel K>
constexpr int kWidth = K == DeltaKernel::kCosine4 ? 4 : 3;

}  // namespace

template <int D>
ImmersedBoundaryTransfer<D>::ImmersedBoundaryTransfer(const Grid<D>& grid,
                                                      const std::array<bool, D>& periodic,
                                                      DeltaKernel kernel)
    : grid_(grid), periodic_(periodic), kernel_(kernel) {
  bool ok = grid.h > 0.0;
  std::string extents;
  for (int a = 0; a < D; ++a) {
    ok = ok && grid.extent(a) >= 4;
    extents += (a ? ", " : "") + std::string(1, "xyz"[a]) + "=" + std::to_string(grid.extent(a));
  }
  if (!ok) {
    throw std::invalid_argument("ImmersedBoundary: grid needs every extent >= 4 and h > 0 (got n" +
                                extents + ", h=" + std::to_string(grid.h) + ")");
  }
}

template <int D>
void ImmersedBoundaryTransfer<D>::Interpolate(const std::array<const std::vector<double>*, D>& u,
                                              const Points& X, Points& U) const {
  for (int d = 0; d < D; ++d) CheckField(grid_, *u[d], d);
  switch (kernel_) {
    case DeltaKernel::kRoma3:
      InterpolateWith<DeltaKernel::kRoma3>(u, X, U);
      break;
    case DeltaKernel::kTrapezoid3:
      InterpolateWith<DeltaKernel::kTrapezoid3>(u, X, U);
      break;
    case DeltaKernel::kRoma3EvenOdd:
      InterpolateWith<DeltaKernel::kRoma3EvenOdd>(u, X, U);
      break;
    default:
      InterpolateWith<DeltaKernel::kCosine4>(u, X, U);
  }
}

template <int D>
template <DeltaKernel K>
void ImmersedBoundaryTransfer<D>::InterpolateWith(
    const std::array<const std::vector<double>*, D>& u, const Points& X, Points& U) const {
  constexpr int W = kWidth<K>;
  constexpr bool kMixed = K == DeltaKernel::kRoma3EvenOdd;
  const Eigen::Index m = X.cols();
  if (U.cols() != m) U.resize(D, m);
  const double inv_h = 1.0 / grid_.h;
  const int nx = grid_.extent(0), ny = grid_.extent(1);
  const int nz = D == 3 ? grid_.extent(D - 1) : 1;
  const double* __restrict up[D];
  for (int d = 0; d < D; ++d) up[d] = u[d]->data();
  for (Eigen::Index c = 0; c < m; ++c) {
    // Node i sits at origin + (i + 1/2) h, so the fractional node coordinate is (x - o)/h - 1/2.
    DeltaStencil s[D], e[D];
    for (int a = 0; a < D; ++a) {
      const double xi = (X(a, c) - grid_.origin(a)) * inv_h - 0.5;
      s[a] = AxisStencil<K>(xi);
      if constexpr (kMixed) e[a] = Trapezoid3DeltaStencil(xi);
    }
    // Component d's weights along axis a: trapezoid3 along its own axis for roma3_even_odd.
    auto wt = [&](int d, int a) -> const double* {
      if constexpr (kMixed) {
        if (d == a) return e[a].weight;
      }
      return s[a].weight;
    };
    int ix[W];
    for (int a = 0; a < W; ++a) ix[a] = WrapIndex(s[0].first + a, nx, periodic_[0]);
    double total[D] = {};
    for (int zc = 0; zc < (D == 3 ? W : 1); ++zc) {
      std::size_t plane = 0;
      if constexpr (D == 3) {
        const int k = WrapIndex(s[D - 1].first + zc, nz, periodic_[D - 1]);
        if (k < 0) continue;
        plane = static_cast<std::size_t>(k) * static_cast<std::size_t>(ny) *
                static_cast<std::size_t>(nx);
      }
      double in_plane[D] = {};
      for (int b = 0; b < W; ++b) {
        const int j = WrapIndex(s[1].first + b, ny, periodic_[1]);
        if (j < 0) continue;
        const std::size_t row = plane + static_cast<std::size_t>(j) * static_cast<std::size_t>(nx);
        double in_row[D] = {};
        for (int a = 0; a < W; ++a) {
          if (ix[a] < 0) continue;
          if constexpr (kMixed) {
            for (int d = 0; d < D; ++d) in_row[d] += wt(d, 0)[a] * up[d][row + ix[a]];
          } else {
            for (int d = 0; d < D; ++d) in_row[d] += s[0].weight[a] * up[d][row + ix[a]];
          }
        }
        if constexpr (kMixed) {
          for (int d = 0; d < D; ++d) in_plane[d] += wt(d, 1)[b] * in_row[d];
        } else {
          for (int d = 0; d < D; ++d) in_plane[d] += s[1].weight[b] * in_row[d];
        }
      }
      if constexpr (D == 3) {
        if constexpr (kMixed) {
          for (int d = 0; d < D; ++d) total[d] += wt(d, D - 1)[zc] * in_plane[d];
        } else {
          for (int d = 0; d < D; ++d) total[d] += s[D - 1].weight[zc] * in_plane[d];
        }
      } else {
        for (int d = 0; d < D; ++d) total[d] = in_plane[d];
      }
    }
    for (int d = 0; d < D; ++d) U(d, c) = total[d];
  }
}

template <int D>
void ImmersedBoundaryTransfer<D>::Spread(const Points& X, const Points& F,
                                         const std::array<std::vector<double>*, D>& f) const {
  for (int d = 0; d < D; ++d) CheckField(grid_, *f[d], d);
  if (F.cols() != X.cols()) {
    throw std::invalid_argument("ImmersedBoundary::Spread: " + std::to_string(F.cols()) +
                                " forces for " + std::to_string(X.cols()) + " points");
  }
  switch (kernel_) {
    case DeltaKernel::kRoma3:
      SpreadWith<DeltaKernel::kRoma3>(X, F, f);
      break;
    case DeltaKernel::kTrapezoid3:
      SpreadWith<DeltaKernel::kTrapezoid3>(X, F, f);
      break;
    case DeltaKernel::kRoma3EvenOdd:
      SpreadWith<DeltaKernel::kRoma3EvenOdd>(X, F, f);
      break;
    default:
      SpreadWith<DeltaKernel::kCosine4>(X, F, f);
  }
}

template <int D>
template <DeltaKernel K>
void ImmersedBoundaryTransfer<D>::SpreadWith(const Points& X, const Points& F,
                                             const std::array<std::vector<double>*, D>& f) const {
  constexpr int W = kWidth<K>;
  constexpr bool kMixed = K == DeltaKernel::kRoma3EvenOdd;
  const double inv_h = 1.0 / grid_.h;
  double inv_volume = inv_h * inv_h;  // 1 / h^D
  if constexpr (D == 3) inv_volume *= inv_h;
  const int nx = grid_.extent(0), ny = grid_.extent(1);
  const int nz = D == 3 ? grid_.extent(D - 1) : 1;
  double* __restrict fp[D];
  for (int d = 0; d < D; ++d) fp[d] = f[d]->data();
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    DeltaStencil s[D], e[D];
    for (int a = 0; a < D; ++a) {
      const double xi = (X(a, c) - grid_.origin(a)) * inv_h - 0.5;
      s[a] = AxisStencil<K>(xi);
      if constexpr (kMixed) e[a] = Trapezoid3DeltaStencil(xi);
    }
    int ix[W];
    for (int a = 0; a < W; ++a) ix[a] = WrapIndex(s[0].first + a, nx, periodic_[0]);
    double g[D];
    for (int d = 0; d < D; ++d) g[d] = F(d, c) * inv_volume;
    for (int zc = 0; zc < (D == 3 ? W : 1); ++zc) {
      std::size_t plane = 0;
      double wz = 1.0;
      if constexpr (D == 3) {
        const int k = WrapIndex(s[D - 1].first + zc, nz, periodic_[D - 1]);
        if (k < 0) continue;
        plane = static_cast<std::size_t>(k) * static_cast<std::size_t>(ny) *
                static_cast<std::size_t>(nx);
        wz = s[D - 1].weight[zc];
      }
      for (int b = 0; b < W; ++b) {
        const int j = WrapIndex(s[1].first + b, ny, periodic_[1]);
        if (j < 0) continue;
        const std::size_t row = plane + static_cast<std::size_t>(j) * static_cast<std::size_t>(nx);
        // 2D: w = phi_x phi_y exactly as before; 3D: phi_x (phi_y phi_z).
        const double wyz = D == 3 ? s[1].weight[b] * wz : s[1].weight[b];
        if constexpr (kMixed) {
          // Component d: trapezoid3 along axis d, roma3 along the others.
          double wzd[D], wyzd[D];
          for (int d = 0; d < D; ++d) {
            wzd[d] = D == 3 ? (d == D - 1 ? e : s)[D - 1].weight[zc] : 1.0;
            wyzd[d] = (d == 1 ? e : s)[1].weight[b] * wzd[d];
          }
          for (int a = 0; a < W; ++a) {
            if (ix[a] < 0) continue;
            for (int d = 0; d < D; ++d) {
              fp[d][row + ix[a]] += (d == 0 ? e : s)[0].weight[a] * wyzd[d] * g[d];
            }
          }
        } else {
          for (int a = 0; a < W; ++a) {
            if (ix[a] < 0) continue;
            const double w = s[0].weight[a] * wyz;
            for (int d = 0; d < D; ++d) fp[d][row + ix[a]] += w * g[d];
          }
        }
      }
    }
  }
}

template class ImmersedBoundaryTransfer<2>;
template class ImmersedBoundaryTransfer<3>;

}  // namespace ehd
