// Immersed boundary transfer between the Eulerian grid and the Lagrangian points, in 2 and 3
// dimensions.
//
// song2019 sec. 3.2, eqs. (102), (104), (106), with the cosine kernel of eq. (103) or the roma3
// kernel (ib/delta_kernel.h, numerics.ib_kernel), in D
// dimensions the tensor product of the 1D kernel, delta_h(x) = prod_a phi(x_a / h) / h^D:
//   interpolation  U(X_c) = sum_j delta_h(X_c - x_j) u(x_j) h^D                       (104)
//   spreading      p(x_j) += sum_c delta_h(X_c - x_j) P(X_c)                            (106)
// where P(X_c) is the force carried by point c (force density times its arc element dl_c in 2D,
// see MarkerArcElements, or its area element in 3D) and p is a force per unit area (2D) or volume
// (3D) on the grid. The two operators are adjoint, <Spread(F), u> h^D = <F, Interpolate(u)>, and
// Spread conserves the total force: sum_j p(x_j) h^D = sum_c P(X_c).
//
// Boundaries: along a periodic axis the node index wraps, so point positions may be stored
// unwrapped (a curve crossing x = x_max keeps continuous coordinates); along a bounded axis the
// part of the 4^D support outside the grid is dropped. For the shear-flow walls this truncation
// is NOT renormalised: a point closer than 2h to a wall loses part of its spread force and sees
// a weighted velocity with weights summing to < 1. Keep points at least 2h from the walls (the
// coupling checks this).
//
// Summation order: x innermost, then y, then z (each partial sum weighted by the next axis), the
// order of the original 2D code, so 2D results are unchanged bit for bit.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/ib/delta_kernel.h"
#include "ehd_capsule/ib/marker_update.h"

namespace ehd {

template <int D>
class ImmersedBoundaryTransfer {
 public:
  using Points = Eigen::Matrix<double, D, Eigen::Dynamic>;
  // Throws std::invalid_argument unless every extent >= 4 and h > 0. kernel: the discrete delta
  // (ib/delta_kernel.h; the cosine kernel of song2019 by default).
  ImmersedBoundaryTransfer(const Grid<D>& grid, const std::array<bool, D>& periodic,
                           DeltaKernel kernel = DeltaKernel::kCosine4);

  const Grid<D>& grid() const { return grid_; }
  bool periodic(int axis) const { return periodic_[axis]; }
  DeltaKernel kernel() const { return kernel_; }

  // U(:, c) = sum_j delta u_j h^D (eq. (104)); u[a] is the a-th velocity component, grid.size()
  // entries each. U is resized to D x M (no allocation when it already has that size).
  void Interpolate(const std::array<const std::vector<double>*, D>& u, const Points& X,
                   Points& U) const;
  // f[a] += sum_c delta F(a, c) (eq. (106)); F is the force per point (not a density). ADDS, so
  // several force sources can be accumulated.
  void Spread(const Points& X, const Points& F, const std::array<std::vector<double>*, D>& f) const;

 protected:
  // Node index along one axis after wrap; -1 if outside a bounded axis.
  static int WrapIndex(int i, int n, bool periodic) {
    if (periodic) {
      i %= n;
      return i < 0 ? i + n : i;
    }
    return (i >= 0 && i < n) ? i : -1;
  }
  Grid<D> grid_;
  std::array<bool, D> periodic_;
  DeltaKernel kernel_ = DeltaKernel::kCosine4;

 private:
  // The loops for kernel K.
  template <DeltaKernel K>
  void InterpolateWith(const std::array<const std::vector<double>*, D>& u, const Points& X,
                       Points& U) const;
  template <DeltaKernel K>
  void SpreadWith(const Points& X, const Points& F,
                  const std::array<std::vector<double>*, D>& f) const;
};

extern template class ImmersedBoundaryTransfer<2>;
extern template class ImmersedBoundaryTransfer<3>;

// The 2D transfer with the per-component signatures the 2D coupling uses.
class ImmersedBoundary : public ImmersedBoundaryTransfer<2> {
 public:
  ImmersedBoundary(const Grid2D& grid, bool periodic_x, bool periodic_y)
      : ImmersedBoundaryTransfer<2>(grid, {periodic_x, periodic_y}) {}
  bool periodic_x() const { return periodic_[0]; }
  bool periodic_y() const { return periodic_[1]; }

  // U(:, c) = sum_j phi phi u(x_j): eq. (104). ux, uy have grid.size() entries (index j*nx+i).
  void Interpolate(const std::vector<double>& ux, const std::vector<double>& uy,
                   const Eigen::Matrix2Xd& X, Eigen::Matrix2Xd& U) const {
    ImmersedBoundaryTransfer<2>::Interpolate({&ux, &uy}, X, U);
  }
  // fx, fy += sum_c phi phi F(:, c) / h^2: eq. (106).
  void Spread(const Eigen::Matrix2Xd& X, const Eigen::Matrix2Xd& F, std::vector<double>& fx,
              std::vector<double>& fy) const {
    ImmersedBoundaryTransfer<2>::Spread(X, F, {&fx, &fy});
  }
};

using ImmersedBoundary3D = ImmersedBoundaryTransfer<3>;

}  // namespace ehd
