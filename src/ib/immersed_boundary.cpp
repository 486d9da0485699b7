// song2019 eqs. (104) and (106) with the cosine kernel (103); see immersed_boundary.h.
#include "ehd_capsule/ib/immersed_boundary.h"

#include <stdexcept>
#include <string>

#include "ehd_capsule/ib/cosine_delta.h"

namespace ehd {
namespace {

void CheckField(const Grid2D& grid, const std::vector<double>& f, const char* name) {
  if (f.size() != grid.size()) {
    throw std::invalid_argument(std::string("ImmersedBoundary: field ") + name + " has " +
                                std::to_string(f.size()) + " entries, grid has " +
                                std::to_string(grid.size()));
  }
}

}  // namespace

ImmersedBoundary::ImmersedBoundary(const Grid2D& grid, bool periodic_x, bool periodic_y)
    : grid_(grid), periodic_x_(periodic_x), periodic_y_(periodic_y) {
  if (grid.nx < 4 || grid.ny < 4 || !(grid.h > 0.0)) {
    throw std::invalid_argument(
        "ImmersedBoundary: grid needs nx, ny >= 4 and h > 0 (got nx=" + std::to_string(grid.nx) +
        ", ny=" + std::to_string(grid.ny) + ", h=" + std::to_string(grid.h) + ")");
  }
}

void ImmersedBoundary::Interpolate(const std::vector<double>& ux, const std::vector<double>& uy,
                                   const Eigen::Matrix2Xd& X, Eigen::Matrix2Xd& U) const {
  CheckField(grid_, ux, "ux");
  CheckField(grid_, uy, "uy");
  const Eigen::Index m = X.cols();
  if (U.cols() != m) U.resize(2, m);
  const double inv_h = 1.0 / grid_.h;
  const int nx = grid_.nx, ny = grid_.ny;
  const double* __restrict ux_p = ux.data();
  const double* __restrict uy_p = uy.data();
  for (Eigen::Index c = 0; c < m; ++c) {
    // Node i sits at x0 + (i + 1/2) h, so the fractional node coordinate is (x - x0)/h - 1/2.
    const DeltaStencil sx = CosineDeltaStencil((X(0, c) - grid_.x0) * inv_h - 0.5);
    const DeltaStencil sy = CosineDeltaStencil((X(1, c) - grid_.y0) * inv_h - 0.5);
    int ix[4];
    for (int a = 0; a < 4; ++a) ix[a] = WrapIndex(sx.first + a, nx, periodic_x_);
    double u = 0.0, v = 0.0;
    for (int b = 0; b < 4; ++b) {
      const int j = WrapIndex(sy.first + b, ny, periodic_y_);
      if (j < 0) continue;
      const std::size_t row = static_cast<std::size_t>(j) * static_cast<std::size_t>(nx);
      double ru = 0.0, rv = 0.0;
      for (int a = 0; a < 4; ++a) {
        if (ix[a] < 0) continue;
        ru += sx.weight[a] * ux_p[row + ix[a]];
        rv += sx.weight[a] * uy_p[row + ix[a]];
      }
      u += sy.weight[b] * ru;
      v += sy.weight[b] * rv;
    }
    U(0, c) = u;
    U(1, c) = v;
  }
}

void ImmersedBoundary::Spread(const Eigen::Matrix2Xd& X, const Eigen::Matrix2Xd& F,
                              std::vector<double>& fx, std::vector<double>& fy) const {
  CheckField(grid_, fx, "fx");
  CheckField(grid_, fy, "fy");
  if (F.cols() != X.cols()) {
    throw std::invalid_argument("ImmersedBoundary::Spread: " + std::to_string(F.cols()) +
                                " forces for " + std::to_string(X.cols()) + " markers");
  }
  const double inv_h = 1.0 / grid_.h;
  const double inv_h2 = inv_h * inv_h;
  const int nx = grid_.nx, ny = grid_.ny;
  double* __restrict fx_p = fx.data();
  double* __restrict fy_p = fy.data();
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    const DeltaStencil sx = CosineDeltaStencil((X(0, c) - grid_.x0) * inv_h - 0.5);
    const DeltaStencil sy = CosineDeltaStencil((X(1, c) - grid_.y0) * inv_h - 0.5);
    int ix[4];
    for (int a = 0; a < 4; ++a) ix[a] = WrapIndex(sx.first + a, nx, periodic_x_);
    const double gx = F(0, c) * inv_h2, gy = F(1, c) * inv_h2;
    for (int b = 0; b < 4; ++b) {
      const int j = WrapIndex(sy.first + b, ny, periodic_y_);
      if (j < 0) continue;
      const std::size_t row = static_cast<std::size_t>(j) * static_cast<std::size_t>(nx);
      for (int a = 0; a < 4; ++a) {
        if (ix[a] < 0) continue;
        const double w = sx.weight[a] * sy.weight[b];
        fx_p[row + ix[a]] += w * gx;
        fy_p[row + ix[a]] += w * gy;
      }
    }
  }
}

}  // namespace ehd
