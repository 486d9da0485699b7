// Correction function method (CFM) for the elliptic interface problem with equal conductivities,
// song2019 sec. 2.3 (Marques, Nave & Petitpas, J. Comput. Phys. 230, 2011):
//
//   Laplace(phi) = f / sigma  in Omega^- and Omega^+,   [phi] = w,  [phi_n] = v / sigma  on Sigma
//
// (song2019 eqs. (7)-(10) with a = w, b = v; InterfaceProblem's [sigma phi_n] = v with
// sigma^+ = sigma^- = sigma). The correction function D = phi^+ - phi^- solves the local Cauchy
// problem Laplace(D) = [f]/sigma, D = w, D_n = v/sigma on Sigma (eqs. (11)-(13)), minimised in
// least squares on one patch per irregular stencil (CfmLocalCauchy, CfmStencilPatch). The
// 5-point stencil at x_ij then uses, for each neighbour x_k across Sigma, phi at x_k continued
// from x_ij's side: phi(x_k) = phi_ext(x_k) + s_k D(x_k), s_k = +1 if x_ij is in Omega^- and x_k
// in Omega^+, -1 the other way, so (song2019 eqs. (16)-(17))
//   L_h phi_ij = f_ij / sigma + C_ij,   C_ij = (1/h^2) sum_k s_k D(x_k),
// solved by one FastPoissonSolver call. (Eq. (17) prints C_ij for x_ij in Omega^+ only:
// C = -(D_{i+1,j} + D_{i,j+1})/h^2, which is s_k = -1.)
//
// [f] is needed at the patch quadrature points, but InterfaceProblem holds f only at grid points
// on their own side; each side's f is continued across Sigma by a least-squares linear fit to
// the grid values of that side in the 5 x 5 block around the stencil (an O(h^2) error in
// Laplace(D), i.e. O(h^4) in D: it does not limit the second-order scheme).
//
// Accuracy: bicubic D is O(h^4), so C_ij is O(h^2) and the solution is second order in the max
// norm (the 5-point stencil limits it; the fourth-order CFM needs a compact 9-point stencil).
// Not handled: an arm of a stencil crossing Sigma twice (under-resolved interface) - both ends
// are then on the same side and no correction is made, as in the text's 5-point method.
#pragma once

#include <cstdint>
#include <vector>

#include "ehd_capsule/electric/fast_poisson_solver.h"
#include "ehd_capsule/electric/interface_problem.h"
#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/reference/cfm_local_cauchy.h"

namespace ehd {

struct CorrectionFunctionOptions {
  CfmBasis basis = CfmBasis::kBicubic;
  double penalty = 10.0;  // c_p of song2019 eq. (18), > 0
  // Interface quadrature: sub-intervals of Sigma cap patch, 4 Gauss points each
  // (0 = default: 3 for the bicubic basis, 1 for the modified bilinear one as in the text).
  int interface_subintervals = 0;
  // Deferred correction of the regular 5-point truncation (AddTruncationCorrection in
  // fast_poisson_solver.h), default on: after the solve, T = (delta^4_x + delta^4_y) phi /
  // (12 h^2) wherever the 5-wide arm along an axis stays on the cell's side of Sigma (no term on
  // an axis that crosses it), then one more Poisson solve with rhs + T. Example cfm1, N =
  // 40..640: 1.9e-4 / 2.9e-5 / 3.3e-6 / 4.4e-7 / 5.8e-8 (plain 3.2e-4 ... 1.2e-6; song2019
  // Table 1: 2.3e-4 ... 1.4e-6), third order on the ellipse, star and biconcave curves too.
  // (Continuing the arms across Sigma with the patches' D, as the IIM does with its J, was
  // erratic: errors up to 1e-2 at some N on the non-circular curves.)
  bool deferred_correction = true;
  // Every marker at least this far (in h) inside the box's faces, else SolverError naming it
  // (electric/box_face_check.h: without it, a curve within 0.5 h of a face is solved O(1) wrong).
  double min_face_distance_h = 1.0;
};

class CorrectionFunctionSolver {
 public:
  // Makes the Poisson plans and all buffers once. Throws std::invalid_argument for bad options.
  CorrectionFunctionSolver(const Grid2D& grid, const PoissonBoundaries& bc,
                           const CorrectionFunctionOptions& options = {});

  // Solves for phi (resized to grid.size()). Requires problem.sigma_minus == problem.sigma_plus
  // (relative difference <= 1e-12, else std::invalid_argument naming both); f empty or
  // grid.size(), w and v empty or curve.size(). The report has iterations = 0 (direct method),
  // residual = 0, converged = false only if some irregular stencil had no usable patch.
  InterfaceSolveReport Solve(const ClosedCurve& curve, const InterfaceProblem& problem,
                             std::vector<double>& phi);

  // Diagnostics of the last Solve(): irregular stencils and those left uncorrected.
  int irregular_points() const { return irregular_points_; }
  int failed_patches() const { return failed_patches_; }
  const std::vector<double>& correction() const { return correction_; }  // C_ij of last solve

  const Grid2D& grid() const { return grid_; }
  const CorrectionFunctionOptions& options() const { return options_; }

 private:
  // inside_[idx] = 1 in Omega^-, and hint_[idx] a curve parameter near points close to Sigma.
  void ClassifyGrid(const ClosedCurve& curve);
  // Side fits of f around (i, j) evaluated at the 16 area points: f_jump = ([f] / sigma).
  void JumpOfSource(const std::vector<double>& f, int i, int j, double sigma,
                    const Eigen::Vector2d* points, double* f_jump) const;

  // Fits and solves the local Cauchy problem of the stencil at grid index `index` and stores
  // C_ij in correction_[index]; false if no patch could be built or solved.
  bool CorrectStencil(const ClosedCurve& curve, const std::vector<double>& f, double sigma,
                      int index, CfmLocalCauchy& cauchy);
  // Deferred correction (options_.deferred_correction): rhs_ += T from phi, solve again.
  void DeferredCorrection(std::vector<double>& phi);

  Grid2D grid_;
  PoissonBoundaries bc_;
  CorrectionFunctionOptions options_;
  FastPoissonSolver poisson_;
  std::vector<CfmLocalCauchy> cauchy_;  // one per OpenMP thread
  std::vector<int> irregular_;          // grid indices of the irregular stencils
  std::vector<char> inside_;
  std::vector<double> hint_;
  std::vector<char> near_;  // 1 if hint_ is set
  std::vector<double> rhs_;
  std::vector<double> correction_;
  std::vector<std::int8_t> sides_;
  std::vector<std::vector<double>> row_crossings_;
  PeriodicCubicSpline jump_value_, jump_normal_;
  std::vector<double> scratch_w_, scratch_v_;
  int irregular_points_ = 0;
  int failed_patches_ = 0;
};

}  // namespace ehd
