// song2019 eqs. (104) and (106) with the cosine kernel (103), or the roma3 kernel, as a tensor
// product in 2 or 3 dimensions; see immersed_boundary.h.
#include "ehd_capsule/ib/immersed_boundary.h"

#include <algorithm>
#include <cmath>
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
template <DeltaKernel K>
DeltaStencil AxisStencil(double xi) {
  if constexpr (K == DeltaKernel::kCosine4) {
    return CosineDeltaStencil(xi);
  } else if constexpr (K == DeltaKernel::kRoma3) {
    return Roma3DeltaStencil(xi);
  } else {
    return Trapezoid3DeltaStencil(xi);
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
      InterpolateEvenOdd(u, X, U);
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
  const Eigen::Index m = X.cols();
  if (U.cols() != m) U.resize(D, m);
  const double inv_h = 1.0 / grid_.h;
  const int nx = grid_.extent(0), ny = grid_.extent(1);
  const int nz = D == 3 ? grid_.extent(D - 1) : 1;
  const double* __restrict up[D];
  for (int d = 0; d < D; ++d) up[d] = u[d]->data();
  for (Eigen::Index c = 0; c < m; ++c) {
    // Node i sits at origin + (i + 1/2) h, so the fractional node coordinate is (x - o)/h - 1/2.
    DeltaStencil s[D];
    for (int a = 0; a < D; ++a) {
      s[a] = AxisStencil<K>((X(a, c) - grid_.origin(a)) * inv_h - 0.5);
    }
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
          for (int d = 0; d < D; ++d) in_row[d] += s[0].weight[a] * up[d][row + ix[a]];
        }
        for (int d = 0; d < D; ++d) in_plane[d] += s[1].weight[b] * in_row[d];
      }
      if constexpr (D == 3) {
        for (int d = 0; d < D; ++d) total[d] += s[D - 1].weight[zc] * in_plane[d];
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
      SpreadEvenOdd(X, F, f);
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
  const double inv_h = 1.0 / grid_.h;
  double inv_volume = inv_h * inv_h;  // 1 / h^D
  if constexpr (D == 3) inv_volume *= inv_h;
  const int nx = grid_.extent(0), ny = grid_.extent(1);
  const int nz = D == 3 ? grid_.extent(D - 1) : 1;
  double* __restrict fp[D];
  for (int d = 0; d < D; ++d) fp[d] = f[d]->data();
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    DeltaStencil s[D];
    for (int a = 0; a < D; ++a) {
      s[a] = AxisStencil<K>((X(a, c) - grid_.origin(a)) * inv_h - 0.5);
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
        for (int a = 0; a < W; ++a) {
          if (ix[a] < 0) continue;
          const double w = s[0].weight[a] * wyz;
          for (int d = 0; d < D; ++d) fp[d][row + ix[a]] += w * g[d];
        }
      }
    }
  }
}

// roma3_even_odd: component d's kernel is trapezoid3 along axis d and roma3 along the others
// (delta_kernel.h). Both have 3 nodes with the same first node, so only the weights differ.
template <int D>
void ImmersedBoundaryTransfer<D>::ComponentWeights(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                   int first[D], double w[D][D][3]) const {
  for (int a = 0; a < D; ++a) {
    const double xi = (x(a) - grid_.origin(a)) / grid_.h - 0.5;
    const DeltaStencil roma = Roma3DeltaStencil(xi);
    const DeltaStencil even_odd = Trapezoid3DeltaStencil(xi);
    first[a] = roma.first;
    for (int d = 0; d < D; ++d) {
      for (int i = 0; i < 3; ++i) w[d][a][i] = (d == a ? even_odd : roma).weight[i];
    }
  }
}

template <int D>
void ImmersedBoundaryTransfer<D>::InterpolateEvenOdd(
    const std::array<const std::vector<double>*, D>& u, const Points& X, Points& U) const {
  if (U.cols() != X.cols()) U.resize(D, X.cols());
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    int first[D];
    double w[D][D][3];
    ComponentWeights(X.col(c), first, w);
    double total[D] = {};
    for (int n = 0; n < (D == 3 ? 27 : 9); ++n) {
      const int i[3] = {n % 3, (n / 3) % 3, n / 9};
      std::size_t node = 0, stride = 1;
      bool inside = true;
      for (int a = 0; a < D; ++a) {
        const int k = WrapIndex(first[a] + i[a], grid_.extent(a), periodic_[a]);
        inside = inside && k >= 0;
        node += static_cast<std::size_t>(std::max(k, 0)) * stride;
        stride *= static_cast<std::size_t>(grid_.extent(a));
      }
      if (!inside) continue;
      for (int d = 0; d < D; ++d) {
        double weight = 1.0;
        for (int a = 0; a < D; ++a) weight *= w[d][a][i[a]];
        total[d] += weight * (*u[d])[node];
      }
    }
    for (int d = 0; d < D; ++d) U(d, c) = total[d];
  }
}

template <int D>
void ImmersedBoundaryTransfer<D>::SpreadEvenOdd(
    const Points& X, const Points& F, const std::array<std::vector<double>*, D>& f) const {
  const double inv_volume = std::pow(grid_.h, -D);
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    int first[D];
    double w[D][D][3];
    ComponentWeights(X.col(c), first, w);
    for (int n = 0; n < (D == 3 ? 27 : 9); ++n) {
      const int i[3] = {n % 3, (n / 3) % 3, n / 9};
      std::size_t node = 0, stride = 1;
      bool inside = true;
      for (int a = 0; a < D; ++a) {
        const int k = WrapIndex(first[a] + i[a], grid_.extent(a), periodic_[a]);
        inside = inside && k >= 0;
        node += static_cast<std::size_t>(std::max(k, 0)) * stride;
        stride *= static_cast<std::size_t>(grid_.extent(a));
      }
      if (!inside) continue;
      for (int d = 0; d < D; ++d) {
        double weight = inv_volume;
        for (int a = 0; a < D; ++a) weight *= w[d][a][i[a]];
        (*f[d])[node] += weight * F(d, c);
      }
    }
  }
}

template class ImmersedBoundaryTransfer<2>;
template class ImmersedBoundaryTransfer<3>;

}  // namespace ehd
