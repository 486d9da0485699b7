// Immersed boundary transfer between the Eulerian grid and the Lagrangian markers.
//
// song2019 sec. 3.2, eqs. (102), (104), (106), with the cosine kernel of eq. (103):
//   interpolation  U(X_c) = sum_j delta_h(X_c - x_j) u(x_j) h^2                       (104)
//   spreading      p(x_j) += sum_c delta_h(X_c - x_j) P(X_c)                            (106)
// where P(X_c) is the force carried by marker c (force density times its arc element dl_c, the
// "area of the element already incorporated", see MarkerArcElements) and p is a force per unit
// area on the grid. With delta_h(x) delta_h(y) = phi(x/h) phi(y/h) / h^2 the two operators are
// adjoint: <Spread(F), u> h^2 = <F, Interpolate(u)>, and Spread conserves the total force:
// sum_j p(x_j) h^2 = sum_c P(X_c).
//
// Boundaries: with periodic_x (periodic_y) the node index wraps modulo nx (ny), so marker
// positions may be stored unwrapped (a curve crossing x = x_max keeps continuous coordinates);
// without it the part of the 4x4 support outside the grid is dropped. For the shear-flow walls at
// y = y0 and y = y0 + ny h this truncation is NOT renormalised: a marker closer than 2h to a wall
// loses part of its spread force and sees a weighted velocity with weights summing to < 1.
// Keep markers at least 2h from the walls (the coupling should check this).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/ib/marker_update.h"

namespace ehd {

class ImmersedBoundary {
 public:
  ImmersedBoundary(const Grid2D& grid, bool periodic_x, bool periodic_y);

  const Grid2D& grid() const { return grid_; }
  bool periodic_x() const { return periodic_x_; }
  bool periodic_y() const { return periodic_y_; }

  // U(:, c) = sum_j phi phi u(x_j): eq. (104). ux, uy have grid.size() entries (index j*nx+i).
  // U is resized to 2 x M (no allocation when it already has that size).
  void Interpolate(const std::vector<double>& ux, const std::vector<double>& uy,
                   const Eigen::Matrix2Xd& X, Eigen::Matrix2Xd& U) const;

  // fx, fy += sum_c phi phi F(:, c) / h^2: eq. (106). F is the force per marker (not density).
  // ADDS to fx, fy (grid.size() entries each), so several force sources can be accumulated.
  void Spread(const Eigen::Matrix2Xd& X, const Eigen::Matrix2Xd& F, std::vector<double>& fx,
              std::vector<double>& fy) const;

 private:
  // Node index along one axis after wrap; -1 if outside a non-periodic axis.
  static int WrapIndex(int i, int n, bool periodic) {
    if (periodic) {
      i %= n;
      return i < 0 ? i + n : i;
    }
    return (i >= 0 && i < n) ? i : -1;
  }
  Grid2D grid_;
  bool periodic_x_;
  bool periodic_y_;
};

}  // namespace ehd
