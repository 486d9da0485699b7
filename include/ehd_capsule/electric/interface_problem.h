// The elliptic interface problem solved by the electric part (song2019 sec. 2.4, eq. (38)-(40)):
//
//   div(sigma grad phi) = f   in Omega^- (inside the curve) and Omega^+ (outside),
//   [phi] = w,  [sigma phi_n] = v   on the interface Sigma,  [q] = q^+ - q^-,
//
// sigma = sigma^- / sigma^+ constant in each region, n the unit normal out of Omega^-. In each
// region Laplace(phi) = f / sigma. Side conditions on the rectangle are those of the
// FastPoissonSolver (kinds fixed by the solver's PoissonBoundaries, values here).
#pragma once

#include <vector>

#include "ehd_capsule/electric/fast_poisson_solver.h"

namespace ehd {

struct InterfaceProblem {
  double sigma_minus = 1.0;
  double sigma_plus = 1.0;
  // Source f = div(sigma grad phi) at the grid points (size grid.size()); each point holds the
  // value of its own region's f. Empty means f = 0.
  std::vector<double> f;
  // [phi] and [sigma phi_n] at the markers (size = number of markers); empty means zero.
  std::vector<double> w, v;
  // Side data: Dirichlet values / Neumann outward derivatives of phi (see PoissonBoundaryData).
  PoissonBoundaryData boundary;
};

struct InterfaceSolveReport {
  int iterations = 0;      // GMRES iterations (mat-vecs = Poisson solves inside GMRES)
  double residual = 0.0;   // final 2-norm of the scaled flux residual over the markers
  bool converged = false;  // residual <= tolerance (always true when no GMRES was needed)
  double solve_ms = 0.0;   // wall time of the whole Solve() call
  // A-posteriori estimate of the relative error of [phi_n] and phi_n^+ at the markers (from a
  // solve on the grid coarsened twice, FastIimOptions::verify_min_ratio); -1 when not verified
  // (sigma^-/sigma^+ below that ratio).
  double estimated_error = -1.0;
};

}  // namespace ehd
