// 3D fast Poisson solver: one rank-3 FFTW r2r transform with the per-axis kinds and eigenvalues of
// the 2D solver (poisson_axis.h); see fast_poisson_solver_3d.h.
#include "ehd_capsule/electric/fast_poisson_solver_3d.h"

#include <fftw3.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "diagonalised_laplacian.h"
#include "poisson_axis.h"

namespace ehd {

using poisson_detail::AxisTransform;
using poisson_detail::MakeAxis;

bool IsSingular(const PoissonBoundaries3D& bc) {
  for (BoundaryKind k : {bc.x_min, bc.x_max, bc.y_min, bc.y_max, bc.z_min, bc.z_max}) {
    if (k == BoundaryKind::kDirichlet) return false;
  }
  return true;
}

FastPoissonSolver3D::FastPoissonSolver3D(const Grid3D& grid, const PoissonBoundaries3D& bc)
    : grid_(grid), bc_(bc) {
  if (grid.nx < 1 || grid.ny < 1 || grid.nz < 1) {
    throw std::invalid_argument("FastPoissonSolver3D: grid must have nx, ny, nz >= 1");
  }
  if (!(grid.h > 0.0)) throw std::invalid_argument("FastPoissonSolver3D: grid.h must be > 0");
  const AxisTransform ax = MakeAxis(bc.x_min, bc.x_max, grid.nx, "x");
  const AxisTransform ay = MakeAxis(bc.y_min, bc.y_max, grid.ny, "y");
  const AxisTransform az = MakeAxis(bc.z_min, bc.z_max, grid.nz, "z");
  // Row-major [nz][ny][nx]: the first FFTW dimension is z (index = (k ny + j) nx + i).
  laplacian_ = std::make_unique<poisson_detail::DiagonalisedLaplacian>(
      std::vector<const AxisTransform*>{&az, &ay, &ax}, std::vector<int>{grid.nz, grid.ny, grid.nx},
      grid.h, "FastPoissonSolver3D");
}

FastPoissonSolver3D::~FastPoissonSolver3D() = default;

void FastPoissonSolver3D::Solve(const std::vector<double>& rhs, std::vector<double>& solution) {
  const std::size_t n = grid_.size();
  if (rhs.size() != n) {
    throw std::invalid_argument("FastPoissonSolver3D::Solve: rhs has " +
                                std::to_string(rhs.size()) + " entries, grid has " +
                                std::to_string(n));
  }
  laplacian_->Solve(rhs, solution);
}

namespace {

// The faces: kind, data, the two tangential extents, and the adjacent cell of face point (a, b).
template <typename F>
void ForEachFace(const Grid3D& g, const PoissonBoundaries3D& bc, F&& f) {
  f(
      bc.x_min, "x_min", g.ny, g.nz, [&g](int a, int b) { return g.index(0, a, b); }, 0, -1);
  f(
      bc.x_max, "x_max", g.ny, g.nz, [&g](int a, int b) { return g.index(g.nx - 1, a, b); }, 0, 1);
  f(
      bc.y_min, "y_min", g.nx, g.nz, [&g](int a, int b) { return g.index(a, 0, b); }, 1, -1);
  f(
      bc.y_max, "y_max", g.nx, g.nz, [&g](int a, int b) { return g.index(a, g.ny - 1, b); }, 1, 1);
  f(
      bc.z_min, "z_min", g.nx, g.ny, [&g](int a, int b) { return g.index(a, b, 0); }, 2, -1);
  f(
      bc.z_max, "z_max", g.nx, g.ny, [&g](int a, int b) { return g.index(a, b, g.nz - 1); }, 2, 1);
}

template <typename Data>  // PoissonBoundaryData3D, const or not
auto& FaceData(Data& d, const char* name) {
  const std::string n = name;
  return n == "x_min"   ? d.x_min
         : n == "x_max" ? d.x_max
         : n == "y_min" ? d.y_min
         : n == "y_max" ? d.y_max
         : n == "z_min" ? d.z_min
                        : d.z_max;
}

}  // namespace

void AddBoundaryDataToRhs(const Grid3D& grid, const PoissonBoundaries3D& bc,
                          const PoissonBoundaryData3D& data, std::vector<double>& rhs) {
  const double h = grid.h;
  ForEachFace(grid, bc,
              [&](BoundaryKind kind, const char* name, int na, int nb, auto index_of, int, int) {
                const std::vector<double>& face = FaceData(data, name);
                if (face.empty() || kind == BoundaryKind::kPeriodic) return;
                if (static_cast<int>(face.size()) != na * nb) {
                  throw std::invalid_argument(std::string("PoissonBoundaryData3D.") + name +
                                              " has " + std::to_string(face.size()) +
                                              " values, expected " + std::to_string(na * nb));
                }
                const double factor = (kind == BoundaryKind::kDirichlet) ? 2.0 / (h * h) : 1.0 / h;
                for (int b = 0; b < nb; ++b) {
                  for (int a = 0; a < na; ++a) rhs[index_of(a, b)] -= factor * face[a + na * b];
                }
              });
}

PoissonBoundaryData3D SampleBoundaryData(
    const Grid3D& grid, const PoissonBoundaries3D& bc,
    const std::function<double(double, double, double)>& value,
    const std::function<Eigen::Vector3d(double, double, double)>& gradient) {
  PoissonBoundaryData3D data;
  ForEachFace(grid, bc,
              [&](BoundaryKind kind, const char* name, int na, int nb, auto, int axis, int side) {
                if (kind == BoundaryKind::kPeriodic) return;
                std::vector<double>& face = FaceData(data, name);
                face.resize(static_cast<std::size_t>(na) * nb);
                const double wall =
                    side < 0 ? grid.origin(axis) : grid.origin(axis) + grid.extent(axis) * grid.h;
                for (int b = 0; b < nb; ++b) {
                  for (int a = 0; a < na; ++a) {
                    double p[3];
                    const int t1 = axis == 0 ? 1 : 0, t2 = axis == 2 ? 1 : 2;
                    p[axis] = wall;
                    p[t1] = grid.coordinate(t1, a);
                    p[t2] = grid.coordinate(t2, b);
                    face[a + na * b] = kind == BoundaryKind::kDirichlet
                                           ? value(p[0], p[1], p[2])
                                           : side * gradient(p[0], p[1], p[2])(axis);
                  }
                }
              });
  return data;
}

}  // namespace ehd
