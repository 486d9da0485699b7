// Uniform cell-centred grids in 2 and 3 dimensions, shared by the fluid (LBM), the immersed
// boundary and the electric solver.
//
// The domain is the box [x0, x0 + nx h] x [y0, y0 + ny h] (x [z0, z0 + nz h]). Unknowns live at
// cell centres
//   x_i = x0 + (i + 1/2) h,  y_j = y0 + (j + 1/2) h,  z_k = z0 + (k + 1/2) h,
// stored x-fastest: index(i, j) = j nx + i, index(i, j, k) = (k ny + j) nx + i. With this layout
// the LBM's half-way bounce-back walls sit exactly on the domain faces y = y0 and y = y0 + ny h,
// and the electric solver's Dirichlet/Neumann sides are the same faces.
//
// Grid<2> (= Grid2D) and Grid<3> (= Grid3D) keep named members (nx, x0, ...) and aggregate
// initialisation ({nx, ny, h, x0, y0}); code written for any dimension uses the axis accessors
// extent(a), origin(a), coordinate(a, i) and kDimension.
#pragma once

#include <array>
#include <cstddef>

namespace ehd {

template <int D>
struct Grid;

template <>
struct Grid<2> {
  static constexpr int kDimension = 2;
  int nx = 0;
  int ny = 0;
  double h = 1.0;
  double x0 = 0.0;
  double y0 = 0.0;

  double x(int i) const { return x0 + (i + 0.5) * h; }
  double y(int j) const { return y0 + (j + 0.5) * h; }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
  }
  std::size_t size() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
  double width() const { return nx * h; }
  double height() const { return ny * h; }
  double x_max() const { return x0 + nx * h; }
  double y_max() const { return y0 + ny * h; }

  int extent(int axis) const { return axis == 0 ? nx : ny; }
  double origin(int axis) const { return axis == 0 ? x0 : y0; }
  double coordinate(int axis, int i) const { return origin(axis) + (i + 0.5) * h; }
  // Distance between two nodes that differ by one along `axis` in the flat index.
  std::size_t stride(int axis) const { return axis == 0 ? 1 : static_cast<std::size_t>(nx); }
};

template <>
struct Grid<3> {
  static constexpr int kDimension = 3;
  int nx = 0;
  int ny = 0;
  int nz = 0;
  double h = 1.0;
  double x0 = 0.0;
  double y0 = 0.0;
  double z0 = 0.0;

  double x(int i) const { return x0 + (i + 0.5) * h; }
  double y(int j) const { return y0 + (j + 0.5) * h; }
  double z(int k) const { return z0 + (k + 0.5) * h; }
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(ny) +
            static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(nx) +
           static_cast<std::size_t>(i);
  }
  std::size_t size() const {
    return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) *
           static_cast<std::size_t>(nz);
  }
  double x_max() const { return x0 + nx * h; }
  double y_max() const { return y0 + ny * h; }
  double z_max() const { return z0 + nz * h; }

  int extent(int axis) const { return axis == 0 ? nx : axis == 1 ? ny : nz; }
  double origin(int axis) const { return axis == 0 ? x0 : axis == 1 ? y0 : z0; }
  double coordinate(int axis, int i) const { return origin(axis) + (i + 0.5) * h; }
  std::size_t stride(int axis) const {
    return axis == 0   ? 1
           : axis == 1 ? static_cast<std::size_t>(nx)
                       : static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  }
};

using Grid2D = Grid<2>;
using Grid3D = Grid<3>;

}  // namespace ehd
