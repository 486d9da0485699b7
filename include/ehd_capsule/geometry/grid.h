// Uniform cell-centred 2D grid shared by the fluid (LBM) and the electric solver.
//
// The domain is the rectangle [x0, x0 + nx h] x [y0, y0 + ny h]. Unknowns live at cell centres
//   x_i = x0 + (i + 1/2) h,  y_j = y0 + (j + 1/2) h,  i = 0..nx-1, j = 0..ny-1,
// stored x-fastest: index(i, j) = j * nx + i. With this layout the LBM's half-way bounce-back
// walls sit exactly on the domain edges y = y0 and y = y0 + ny h, and the electric solver's
// Dirichlet/Neumann sides are the same edges.
#pragma once

#include <cstddef>

namespace ehd {

struct Grid2D {
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
};

}  // namespace ehd
