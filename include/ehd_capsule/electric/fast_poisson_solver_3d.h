// Fast Poisson solver for the 7-point cell-centred Laplacian on a box (Grid3D): the 3D version of
// fast_poisson_solver.h, for the 3D electric potential (song2019 ch. 6: Dirichlet on z = 0, 10,
// Neumann on the x and y sides).
//
//   sum over the three axes (phi_{+1} - 2 phi + phi_{-1}) / h^2 = rhs
//
// Each of the six faces is Dirichlet (value at the face), Neumann (outward derivative) or
// periodic (paired with the opposite face), with the same ghost rules and the same per-axis FFTW
// real-to-real transforms as in 2D, applied as one rank-3 r2r transform; the solve is exact up to
// round-off. Plans are made once (FFTW_MEASURE). Without a Dirichlet face the zero mode is dropped
// and the zero-mean solution returned. Transform cost depends strongly on the sizes: the
// REDFT10/RODFT10 logical size is 2n, and a size with a large prime factor is several times slower
// (poisson_bench --dim 3 prints the table; docs/electric_solver_3d.md).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "ehd_capsule/electric/fast_poisson_solver.h"
#include "ehd_capsule/geometry/grid.h"

namespace ehd {

struct PoissonBoundaries3D {
  BoundaryKind x_min = BoundaryKind::kDirichlet, x_max = BoundaryKind::kDirichlet;
  BoundaryKind y_min = BoundaryKind::kDirichlet, y_max = BoundaryKind::kDirichlet;
  BoundaryKind z_min = BoundaryKind::kDirichlet, z_max = BoundaryKind::kDirichlet;
};

// Face data at the face centres: x faces hold ny * nz values (index j + ny k), y faces nx * nz
// (i + nx k), z faces nx * ny (i + nx j). Dirichlet: phi at the face; Neumann: the outward
// normal derivative; periodic or empty: nothing (homogeneous).
struct PoissonBoundaryData3D {
  std::vector<double> x_min, x_max, y_min, y_max, z_min, z_max;
};

// Folds inhomogeneous face data into rhs (Dirichlet g: rhs_adjacent -= 2 g / h^2; Neumann q:
// rhs_adjacent -= q / h). Throws std::invalid_argument naming the face for a wrong length.
void AddBoundaryDataToRhs(const Grid3D& grid, const PoissonBoundaries3D& bc,
                          const PoissonBoundaryData3D& data, std::vector<double>& rhs);

// Face data sampled from a function (Dirichlet: value; Neumann: gradient . outward normal).
PoissonBoundaryData3D SampleBoundaryData(
    const Grid3D& grid, const PoissonBoundaries3D& bc,
    const std::function<double(double, double, double)>& value,
    const std::function<Eigen::Vector3d(double, double, double)>& gradient);

bool IsSingular(const PoissonBoundaries3D& bc);

class FastPoissonSolver3D {
 public:
  // Throws std::invalid_argument for an empty grid, h <= 0 or unpaired periodic faces.
  FastPoissonSolver3D(const Grid3D& grid, const PoissonBoundaries3D& bc);
  ~FastPoissonSolver3D();
  FastPoissonSolver3D(const FastPoissonSolver3D&) = delete;
  FastPoissonSolver3D& operator=(const FastPoissonSolver3D&) = delete;

  // 7-point Laplacian(solution) = rhs with homogeneous face conditions (solution may alias rhs).
  void Solve(const std::vector<double>& rhs, std::vector<double>& solution);

  const Grid3D& grid() const { return grid_; }
  const PoissonBoundaries3D& boundaries() const { return bc_; }

 private:
  Grid3D grid_;
  PoissonBoundaries3D bc_;
  std::unique_ptr<poisson_detail::DiagonalisedLaplacian> laplacian_;  // shared by 2D and 3D
};

}  // namespace ehd
