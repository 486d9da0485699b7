// Fast Poisson solver for the 5-point cell-centred Laplacian on a rectangle (Grid2D).
//
//   (phi_{i+1,j} - 2 phi_ij + phi_{i-1,j} + phi_{i,j+1} - 2 phi_ij + phi_{i,j-1}) / h^2 = rhs_ij
//
// Each side of the rectangle is independently Dirichlet (value at the face, ghost cell
// phi_{-1} = -phi_0), Neumann (zero outward flux, phi_{-1} = phi_0) or periodic (must pair with
// the opposite side). The 5-point operator with these ghost rules is diagonalised exactly by the
// FFTW real-to-real transforms below, so the solve is exact up to round-off (no iteration):
//   per axis   transform pair            eigenvalue * h^2, k = 0..n-1
//   D-D        RODFT10 / RODFT01         -4 sin^2(pi (k+1) / (2n))
//   N-N        REDFT10 / REDFT01         -4 sin^2(pi k / (2n))
//   D-N        RODFT11 / RODFT11         -4 sin^2(pi (k+1/2) / (2n))
//   N-D        REDFT11 / REDFT11         -4 sin^2(pi (k+1/2) / (2n))
//   periodic   R2HC / HC2R               -4 sin^2(pi m / n), m = min(k, n-k)
// (song2019 sec. 2.4 uses "a fast Poisson solver" for L Phi = F1 - B G, eq. (47) and (59).)
// The normalisation of each pair is 2n (n for periodic). Plans are made once in the constructor
// with FFTW_MEASURE; Solve() allocates nothing. Cost O(N^2 log N); FFTW is fastest when 2n
// (REDFT10/RODFT10 logical size) has only small prime factors.
//
// If no side is Dirichlet the operator is singular: the zero mode of the rhs is dropped (the
// rhs is projected onto the compatible subspace) and the zero-mean solution is returned.
//
// Inhomogeneous side data are folded into the rhs with AddBoundaryDataToRhs():
//   Dirichlet value g at the face:           rhs_adjacent -= 2 g / h^2
//   Neumann outward derivative q = dphi/dn:  rhs_adjacent -= q / h
// after which Solve() with the homogeneous operator gives the inhomogeneous solution.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "ehd_capsule/geometry/grid.h"

namespace ehd {
namespace poisson_detail {
class DiagonalisedLaplacian;
}

enum class BoundaryKind { kDirichlet, kNeumann, kPeriodic };

// Periodic sides must pair up (x_min with x_max, y_min with y_max).
struct PoissonBoundaries {
  BoundaryKind x_min = BoundaryKind::kDirichlet;
  BoundaryKind x_max = BoundaryKind::kDirichlet;
  BoundaryKind y_min = BoundaryKind::kDirichlet;
  BoundaryKind y_max = BoundaryKind::kDirichlet;
};

// Side data at the face midpoints: x_min/x_max hold ny values (at y_j), y_min/y_max hold nx
// values (at x_i). Dirichlet sides hold phi at the face, Neumann sides the outward normal
// derivative, periodic sides nothing. An empty vector means homogeneous data on that side.
struct PoissonBoundaryData {
  std::vector<double> x_min, x_max, y_min, y_max;
};

// Folds inhomogeneous side data into rhs (see the file comment). Throws std::invalid_argument
// if a non-empty side vector has the wrong length.
void AddBoundaryDataToRhs(const Grid2D& grid, const PoissonBoundaries& bc,
                          const PoissonBoundaryData& data, std::vector<double>& rhs);

// Second-order Dirichlet sides (call on rhs = F, the cell values of Laplace(phi), before
// AddBoundaryDataToRhs and before any other term is added). The ghost rule phi_{-1} = 2 g - phi_0
// misses (h^2/4) phi_nn at the face, an O(1) truncation error in the cells next to the side that
// makes an O(h^2) error with a large constant across the whole box (song2019 sec. 2.5 example 1:
// 40% of the L-inf error). With phi_nn = Laplace(phi) - g_tt at the face, the ghost is
// phi_{-1} = 2 g - phi_0 + (h^2/4) (F_0 - g_tt), i.e. rhs_adjacent -= (F_0 - g_tt) / 4, with F_0
// the adjacent cell's rhs and g_tt the second difference of the side data (that of the next
// point at the two ends). Dirichlet sides with at least 3 values only; a zero term is skipped, so
// constant side data with F = 0 there leave rhs bit-for-bit unchanged.
void AddDirichletGhostCorrection(const Grid2D& grid, const PoissonBoundaries& bc,
                                 const PoissonBoundaryData& data, std::vector<double>& rhs);

// Deferred (defect) correction of the 5-point truncation error. For smooth phi the 5-point
// operator gives L_h phi = Laplace(phi) + tau + O(h^4) with tau = (h^2/12)(phi_xxxx + phi_yyyy);
// after a second-order solve phi^1 of L_h phi = b, re-solving L_h phi^2 = b + T with
//   T_ij = (delta^4_x phi^1 + delta^4_y phi^1)_ij / (12 h^2),
//   delta^4_x u_i = u_{i+2} - 4 u_{i+1} + 6 u_i - 4 u_{i-1} + u_{i-2}  (= h^4 u_xxxx + O(h^6))
// cancels tau to O(h^4) where phi^1 is smooth. Adds T to rhs. Within 2 cells of a non-periodic
// side the 5-point fourth difference is taken at the nearest cell that has it (cell 2 or n-3: a
// constant extrapolation of phi_xxxx, O(h^3) there); periodic axes wrap. An axis with fewer than
// 5 cells gets no correction. Interface (optional, sides != nullptr): sides[idx] = -1 / +1 per
// cell; a stencil value on the other side from the cell the correction is for is replaced by its
// continuation from that cell's side, phi(x_k) + s_c jump[x_k] (jump = phi^+_ext - phi^-_ext at
// x_k, s_c the centre's side); if jump_known[x_k] == 0 (or jump and jump_known are null: no jump
// known anywhere) that axis's term is dropped at that cell.
// rhs, phi, sides, jump, jump_known: grid.size() entries. No allocation.
void AddTruncationCorrection(const Grid2D& grid, const PoissonBoundaries& bc,
                             const std::vector<double>& phi, const std::int8_t* sides,
                             const double* jump, const std::uint8_t* jump_known,
                             std::vector<double>& rhs);

// Side data sampled from a function: Dirichlet sides take value(x, y) at the face midpoints,
// Neumann sides take gradient(x, y) . outward normal there. Periodic sides are left empty.
PoissonBoundaryData SampleBoundaryData(
    const Grid2D& grid, const PoissonBoundaries& bc,
    const std::function<double(double, double)>& value,
    const std::function<Eigen::Vector2d(double, double)>& gradient);

// True if no side is Dirichlet (the operator has a constant null space).
bool IsSingular(const PoissonBoundaries& bc);

class FastPoissonSolver {
 public:
  // Makes the FFTW plans (FFTW_MEASURE; a few hundred ms for large grids). Throws
  // std::invalid_argument for an empty grid, h <= 0 or unpaired periodic sides.
  FastPoissonSolver(const Grid2D& grid, const PoissonBoundaries& bc);
  ~FastPoissonSolver();
  FastPoissonSolver(const FastPoissonSolver&) = delete;
  FastPoissonSolver& operator=(const FastPoissonSolver&) = delete;

  // 5-point cell-centred Laplacian(solution) = rhs with homogeneous side conditions. rhs and
  // solution have grid.size() entries (solution is resized if needed; may alias rhs).
  void Solve(const std::vector<double>& rhs, std::vector<double>& solution);

  const Grid2D& grid() const { return grid_; }
  const PoissonBoundaries& boundaries() const { return bc_; }

 private:
  Grid2D grid_;
  PoissonBoundaries bc_;
  std::unique_ptr<poisson_detail::DiagonalisedLaplacian> laplacian_;  // shared by 2D and 3D
};

}  // namespace ehd
