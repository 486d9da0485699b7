// Fast Poisson solver: 2D FFTW real-to-real transforms with the exact eigenvalues of the 5-point
// cell-centred Laplacian (see fast_poisson_solver.h for the transform table and the data folding).
#include "ehd_capsule/electric/fast_poisson_solver.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include "diagonalised_laplacian.h"
#include "poisson_axis.h"

namespace ehd {

using poisson_detail::AxisTransform;
using poisson_detail::MakeAxis;

bool IsSingular(const PoissonBoundaries& bc) {
  return bc.x_min != BoundaryKind::kDirichlet && bc.x_max != BoundaryKind::kDirichlet &&
         bc.y_min != BoundaryKind::kDirichlet && bc.y_max != BoundaryKind::kDirichlet;
}

FastPoissonSolver::FastPoissonSolver(const Grid2D& grid, const PoissonBoundaries& bc)
    : grid_(grid), bc_(bc) {
  if (grid.nx < 1 || grid.ny < 1) {
    throw std::invalid_argument("FastPoissonSolver: grid must have nx, ny >= 1, got " +
                                std::to_string(grid.nx) + " x " + std::to_string(grid.ny));
  }
  if (!(grid.h > 0.0)) {
    throw std::invalid_argument("FastPoissonSolver: grid.h must be > 0, got " +
                                std::to_string(grid.h));
  }
  const AxisTransform ax = MakeAxis(bc.x_min, bc.x_max, grid.nx, "x");
  const AxisTransform ay = MakeAxis(bc.y_min, bc.y_max, grid.ny, "y");
  // Row-major [ny][nx]: the first FFTW dimension is y, matching index = j * nx + i.
  laplacian_ = std::make_unique<poisson_detail::DiagonalisedLaplacian>(
      std::vector<const AxisTransform*>{&ay, &ax}, std::vector<int>{grid.ny, grid.nx}, grid.h,
      "FastPoissonSolver");
}

FastPoissonSolver::~FastPoissonSolver() = default;

void FastPoissonSolver::Solve(const std::vector<double>& rhs, std::vector<double>& solution) {
  const std::size_t n = grid_.size();
  if (rhs.size() != n) {
    throw std::invalid_argument("FastPoissonSolver::Solve: rhs has " + std::to_string(rhs.size()) +
                                " entries, grid has " + std::to_string(n));
  }
  laplacian_->Solve(rhs, solution);
}

void AddBoundaryDataToRhs(const Grid2D& grid, const PoissonBoundaries& bc,
                          const PoissonBoundaryData& data, std::vector<double>& rhs) {
  const double h = grid.h;
  auto fold = [&](BoundaryKind kind, const std::vector<double>& side, int count, const char* name,
                  auto index_of) {
    if (side.empty() || kind == BoundaryKind::kPeriodic) return;
    if (static_cast<int>(side.size()) != count) {
      throw std::invalid_argument(std::string("PoissonBoundaryData.") + name + " has " +
                                  std::to_string(side.size()) + " values, expected " +
                                  std::to_string(count));
    }
    const double factor = (kind == BoundaryKind::kDirichlet) ? 2.0 / (h * h) : 1.0 / h;
    for (int k = 0; k < count; ++k) rhs[index_of(k)] -= factor * side[k];
  };
  const int nx = grid.nx, ny = grid.ny;
  fold(bc.x_min, data.x_min, ny, "x_min", [&](int j) { return grid.index(0, j); });
  fold(bc.x_max, data.x_max, ny, "x_max", [&](int j) { return grid.index(nx - 1, j); });
  fold(bc.y_min, data.y_min, nx, "y_min", [&](int i) { return grid.index(i, 0); });
  fold(bc.y_max, data.y_max, nx, "y_max", [&](int i) { return grid.index(i, ny - 1); });
}

void AddDirichletGhostCorrection(const Grid2D& grid, const PoissonBoundaries& bc,
                                 const PoissonBoundaryData& data, std::vector<double>& rhs) {
  const double inv_h2 = 1.0 / (grid.h * grid.h);
  const int nx = grid.nx, ny = grid.ny;
  // F of the four corner cells before any change (two sides correct each of them).
  const std::size_t corner[4] = {grid.index(0, 0), grid.index(nx - 1, 0), grid.index(0, ny - 1),
                                 grid.index(nx - 1, ny - 1)};
  const double corner_f[4] = {rhs[corner[0]], rhs[corner[1]], rhs[corner[2]], rhs[corner[3]]};
  auto f_at = [&](std::size_t idx) {
    for (int c = 0; c < 4; ++c)
      if (idx == corner[c]) return corner_f[c];
    return rhs[idx];
  };
  auto fold = [&](BoundaryKind kind, const std::vector<double>& side, int count, auto index_of) {
    if (kind != BoundaryKind::kDirichlet || count < 3 || static_cast<int>(side.size()) != count) {
      return;
    }
    for (int k = 0; k < count; ++k) {
      const int c = std::clamp(k, 1, count - 2);
      const double g_tt = (side[c - 1] - 2.0 * side[c] + side[c + 1]) * inv_h2;
      const std::size_t idx = index_of(k);
      const double term = 0.25 * (f_at(idx) - g_tt);
      if (term != 0.0) rhs[idx] -= term;
    }
  };
  fold(bc.x_min, data.x_min, ny, [&](int j) { return grid.index(0, j); });
  fold(bc.x_max, data.x_max, ny, [&](int j) { return grid.index(nx - 1, j); });
  fold(bc.y_min, data.y_min, nx, [&](int i) { return grid.index(i, 0); });
  fold(bc.y_max, data.y_max, nx, [&](int i) { return grid.index(i, ny - 1); });
}

void AddTruncationCorrection(const Grid2D& grid, const PoissonBoundaries& bc,
                             const std::vector<double>& phi, const std::int8_t* sides,
                             const double* jump, const std::uint8_t* jump_known,
                             std::vector<double>& rhs) {
  const int nx = grid.nx, ny = grid.ny;
  const double scale = 1.0 / (12.0 * grid.h * grid.h);
  const bool x_periodic = bc.x_min == BoundaryKind::kPeriodic;
  const bool y_periodic = bc.y_min == BoundaryKind::kPeriodic;
  constexpr double kWeight[5] = {1.0, -4.0, 6.0, -4.0, 1.0};
  // Fourth difference along one axis at cell (i, j) for the centre side sc; false if a value
  // across the interface has no known jump.
  auto fourth = [&](int i, int j, int sc, bool along_x, double* out) {
    const int n = along_x ? nx : ny;
    const bool periodic = along_x ? x_periodic : y_periodic;
    const int c = along_x ? i : j;
    const int centre = periodic ? c : std::clamp(c, 2, n - 3);
    double sum = 0.0;
    for (int q = 0; q < 5; ++q) {
      int k = centre + q - 2;
      if (periodic) k = (k + n) % n;
      const std::size_t idx = along_x ? grid.index(k, j) : grid.index(i, k);
      double value = phi[idx];
      if (sides != nullptr && sides[idx] != sc) {
        if (jump_known == nullptr || jump_known[idx] == 0) return false;
        value += sc * jump[idx];
      }
      sum += kWeight[q] * value;
    }
    *out = sum;
    return true;
  };
  const bool x_ok = nx >= 5, y_ok = ny >= 5;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t idx = grid.index(i, j);
      const int sc = sides != nullptr ? sides[idx] : 0;
      double total = 0.0, d4 = 0.0;
      if (x_ok && fourth(i, j, sc, true, &d4)) total += d4;
      if (y_ok && fourth(i, j, sc, false, &d4)) total += d4;
      rhs[idx] += scale * total;
    }
  }
}

PoissonBoundaryData SampleBoundaryData(
    const Grid2D& grid, const PoissonBoundaries& bc,
    const std::function<double(double, double)>& value,
    const std::function<Eigen::Vector2d(double, double)>& gradient) {
  PoissonBoundaryData d;
  auto sample = [&](BoundaryKind kind, std::vector<double>& out, int count, auto point,
                    Eigen::Vector2d normal) {
    if (kind == BoundaryKind::kPeriodic) return;
    out.resize(count);
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector2d p = point(k);
      out[k] = (kind == BoundaryKind::kDirichlet) ? value(p.x(), p.y())
                                                  : gradient(p.x(), p.y()).dot(normal);
    }
  };
  sample(
      bc.x_min, d.x_min, grid.ny, [&](int j) { return Eigen::Vector2d(grid.x0, grid.y(j)); },
      Eigen::Vector2d(-1, 0));
  sample(
      bc.x_max, d.x_max, grid.ny, [&](int j) { return Eigen::Vector2d(grid.x_max(), grid.y(j)); },
      Eigen::Vector2d(1, 0));
  sample(
      bc.y_min, d.y_min, grid.nx, [&](int i) { return Eigen::Vector2d(grid.x(i), grid.y0); },
      Eigen::Vector2d(0, -1));
  sample(
      bc.y_max, d.y_max, grid.nx, [&](int i) { return Eigen::Vector2d(grid.x(i), grid.y_max()); },
      Eigen::Vector2d(0, 1));
  return d;
}

}  // namespace ehd
