// Fast immersed interface method for div(sigma grad phi) = f with [phi] = w, [sigma phi_n] = v
// (song2019 sec. 2.4, Z. Li's augmented approach; relations corrected in docs/electric_solver.md).
//
// Augmented unknown G = [phi_n] at the M markers. For a given G:
//   L Phi = F + C(W, G)                                          eq. (45)-(47)
// L the 5-point Laplacian (FastPoissonSolver), F = f/sigma of each point's region, and at an
// irregular point x_ij the correction C_ij = (1/h^2) sum_k s_k J(x_k) over the stencil neighbours
// x_k across the curve (s_k = +1 if x_ij is inside and x_k outside, -1 the other way), with J the
// jump expansion of jump_relations.h about x_k's closest curve point (G enters through its
// periodic spline). phi_n^- at the markers comes from the weighted least-squares cubic fit
// (normal_derivative_fit.h; the reference fits a quadratic) and phi_n^+ = phi_n^- + G, eq. (87).
// The Schur system (57) is the scaled flux residual of Xu (eq. (49)-(50)), which equals ([sigma
// phi_n] - v) / [sigma]:
//   sigma^+ > sigma^-:  R = phi_n^- + (sigma^+/[sigma]) G - v/[sigma]
//   sigma^- > sigma^+:  R = phi_n^+ + (sigma^-/[sigma]) G - v/[sigma]
// R is affine in G; restarted GMRES solves R(G) = 0 with the mat-vec R(G) - R(0), one Poisson
// solve each (eq. (59)-(61)), in the Schur solver shared with the 3D solver
// (interface_schur_system.h; this file gives R and the unknowns). sigma^+ = sigma^-: G = v / sigma
// is known and no GMRES is run. [f/sigma] and [d_xi(f/sigma)] in J are estimated at the markers by
// one-sided weighted least-squares fits of each side's grid values of F
// (NormalDerivativeFit::SideExtrapolation, O(h^3) and O(h^2)). Dirichlet box sides use the
// second-order ghost (AddDirichletGhostCorrection), which the reference does not need (its boundary
// values sit on grid nodes).
//
// Departure from the text for sigma^- > sigma^+: the scaled residual is then
// phi_n^- - (sigma^+/(sigma^- - sigma^+)) G + ..., and a near-constant G changes phi_n^- very
// little (a constant single layer is constant inside a circle), so the constant mode has an
// eigenvalue ~ -sigma^+/sigma^- and the O(h^2) error of the fitted mean of phi_n^- is amplified
// by sigma^-/sigma^+ (order and GMRES iterations degrade at sigma^-/sigma^+ >= 10). We replace
// the mean of the fitted phi_n^- by its exact value from the divergence theorem,
//   sum_k phi_n^-(X_k) dl_k = integral over Omega^- of f^-/sigma^- dA,
// (the area integral by an O(h^3) cut-cell quadrature, see ComputeInteriorFlux), so the constant
// mode of G is fixed by the flux balance itself, as in the continuous problem. The same near-null
// behaviour hits modes of G that the grid cannot resolve (wavelength ~2 marker spacings < ~4h), so
// for sigma^- > sigma^+ GMRES therefore works on control markers spaced >= ~1.5 h (FastIimOptions),
// with G at the other markers from the periodic spline through the control values. For
// sigma^+ > sigma^- every marker is a control (no near-null modes there).
//
// Deferred correction (FastIimOptions::deferred_correction, default on): each potential solve
// adds the estimated 5-point truncation T = (h^2/12)(phi_xxxx + phi_yyyy) from a first solve
// (AddTruncationCorrection), which makes the max error third order (not in the reference).
//
// Guarantees (FastIimOptions; the options and the dimension-free checks are shared with the 3D
// solver: interface_solver_options.h, interface_guarantees.h): before solving, the inner-ratio
// cap, the grid-scale curvature, the marker spacing, the box faces and no grid segment crossed
// twice by the curve (a part thinner than h); after solving, the marker-scale oscillation of G,
// the cubic/quadratic fit agreement of phi_n^- and, for sigma^-/sigma^+ >= verify_min_ratio,
// the coarse-grid verification (2D only). docs/electric_solver.md, "Guarantees".
//
// Cost per Solve: classification and fit set-up O(M + band), then (iterations + 2) potential
// solves, two Poisson solves each with the deferred correction (warm or cold, see
// FastIimOptions::warm_start_refresh). Non-convergence throws SolverError.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <memory>
#include <vector>

#include "ehd_capsule/electric/fast_poisson_solver.h"
#include "ehd_capsule/electric/gmres.h"
#include "ehd_capsule/electric/interface_classification.h"
#include "ehd_capsule/electric/interface_problem.h"
#include "ehd_capsule/electric/interface_schur_system.h"
#include "ehd_capsule/electric/interface_solver_options.h"
#include "ehd_capsule/electric/normal_derivative_fit.h"
#include "ehd_capsule/geometry/closed_curve.h"

namespace ehd {

// How G is represented when there are fewer GMRES unknowns than markers (sigma^- > sigma^+ with
// markers denser than min_control_spacing_h): kFourier (default), a Fourier series in arc length
// with as many terms as there would be controls, residual projected on it with the arc weights
// (Galerkin): the discrete problem does not depend on the first marker nor on the marker
// direction; kSplineControls, the periodic spline through control markers chosen from marker
// 0 (the previous method, kept for comparison).
enum class ControlBasis { kFourier, kSplineControls };

// The shared settings (interface_solver_options.h: GMRES, the fit, the resolution checks, the
// inner-ratio cap, the Fourier basis for sigma^-/sigma^+ >= basis_min_ratio, the fit-agreement
// and oscillation checks, the warm start) and what only the curve solver has, because its
// algorithm differs there: the closest-point band, the control markers, the optional mean
// deflation (always on in 3D, where the basis needs it), the deferred correction (not carried to
// 3D) and the coarse-grid verification (3D relies on its flux-balance estimate instead).
//
// Basis (InterfaceSolverOptions::basis_wavelength_h, 5 h here): at sigma^-/sigma^+ >=
// basis_min_ratio (kFourier only) G is always sought in the Fourier basis, with the number of
// terms set by its shortest wavelength, P / k_max >= basis_wavelength_h h (at most (M - 1) / 2
// terms), as the 3D solver's harmonic basis. Below the ratio, or with basis_wavelength_h = 0, as
// many terms as there are controls (every marker a control: no basis). Measured
// (docs/electric_solver.md, "A much more conducting inside"): at 1000:1 the five-petal stars with
// troughs of curvature radius 2 h need 15-19 GMRES iterations at every N with 5 h, where the
// control count stalls GMRES (185 at N = 160, > 400 at N = 224) and 4 h already grows with N
// (39-108).
struct FastIimOptions : InterfaceSolverOptions<2> {
  double band_width_h = 3.5;  // closest points are found for |d| < band_width_h * h
  // sigma^- > sigma^+ only: GMRES unknowns live on control markers spaced >= this many h of
  // arc length (chosen walking along the curve, so bunched markers do not give close controls;
  // G at the others is the periodic spline through them). Markers denser than the grid
  // resolves would otherwise add modes of G that barely change phi_n^-, i.e. near-null modes of
  // the Schur system for sigma^- > sigma^+.
  double min_control_spacing_h = 1.5;
  ControlBasis control_basis = ControlBasis::kFourier;
  // sigma^- > sigma^+ only. The exact interior flux fixes the arc-weighted mean of the residual,
  // hence the mean of G (mu = (mean(v)/[sigma] - flux/P) / (sigma^+/[sigma])); the operator's
  // near-null mode (the equilibrium density of the curve, eigenvalue ~ -sigma^+/sigma^-, a
  // constant only on a circle) is lifted by adding -(mean(G) - mu) to every residual. Same
  // solution, fewer iterations (star at sigma^-/sigma^+ = 1000: 19/18/16/15 -> 15/13/11/11 at
  // N = 40..320). false: the plain Schur system.
  bool deflate_mean = true;
  // Deferred correction of the regular 5-point truncation (AddTruncationCorrection), default
  // on: every potential solve for a given G becomes phi^1 = L_h^-1 (F + C), then
  // phi = L_h^-1 (F + C + T), T = (delta^4_x + delta^4_y) phi^1 / (12 h^2) with the values across
  // the curve replaced by their same-side continuation phi^1 -/+ J (J at the band points within
  // 2.5 h of the curve). phi is still affine in G, so GMRES solves the Schur system of the
  // corrected potential (G consistent with it; a guess that is the solution needs 0 iterations).
  // Max error third order on the examples (docs/electric_solver.md sec. 5); cost: two Poisson
  // solves per potential solve.
  bool deferred_correction = true;
  // Guarantees (no wrong answer returned as a success; each failure is a SolverError naming the
  // marker, the quantity and the remedy), besides the shared ones (interface_guarantees.h):
  // - before solving, besides max_curvature_h (the Menger curvature through the markers 1 h away
  //   on each side), |kappa| l <= pi/2 over each marker segment l (markers too sparse);
  // - for sigma^-/sigma^+ >= verify_min_ratio, where the near-null mode of the Schur system
  //   (the curve's equilibrium density, eigenvalue -sigma^+/(sigma^- - sigma^+)) amplifies the
  //   discretisation error, a second solve on the grid coarsened twice (warm-started from G)
  //   gives the Richardson estimate |X_h - X_2h| / 3 of the error of G and phi_n^+ (second
  //   order); above verify_tolerance (relative to max(|G|, |phi_n^+-|)) Solve throws. The
  //   estimate is in InterfaceSolveReport::estimated_error. Costs ~1/4 of a solve. A grid that
  //   cannot be coarsened (odd or < 32 cells) cannot be verified: SolverError too.
  double verify_min_ratio = 10.0;  // infinity: never verify
  double verify_tolerance = 0.05;
};

class FastIimSolver {
 public:
  FastIimSolver(const Grid2D& grid, const PoissonBoundaries& bc,
                const FastIimOptions& options = FastIimOptions());

  // Solves the problem for the curve. g: on entry the initial guess for [phi_n] at the markers
  // (any size other than M means a zero guess), on exit the solution. phi: grid solution.
  // Throws std::invalid_argument for inconsistent sizes or sigma <= 0, SolverError if GMRES
  // does not reach the tolerance.
  InterfaceSolveReport Solve(const ClosedCurve& curve, const InterfaceProblem& problem,
                             std::vector<double>& g, std::vector<double>& phi);

  // Marker derivatives of the last solution: phi_n^-, phi_n^+ and the derivatives along the
  // counter-clockwise tangent phi_tau^-, phi_tau^+ = phi_tau^- + w'.
  const std::vector<double>& normal_derivative_minus() const { return dn_minus_; }
  const std::vector<double>& normal_derivative_plus() const { return dn_plus_; }
  const std::vector<double>& tangential_derivative_minus() const { return dt_minus_; }
  const std::vector<double>& tangential_derivative_plus() const { return dt_plus_; }
  // Jump J = phi^+_ext - phi^-_ext at the band points for the last solution (evaluated at the
  // points the method uses: neighbours across a stencil and outside fit points; 0 elsewhere).
  const std::vector<double>& band_jump() const { return band_jump_; }
  const InterfaceClassification& classification() const { return classes_; }
  const NormalDerivativeFit& fit() const { return fit_; }
  const Grid2D& grid() const { return poisson_.grid(); }
  const FastIimOptions& options() const { return options_; }
  void set_options(const FastIimOptions& options) {
    options_ = options;
    coarse_.reset();  // the verifying solver is rebuilt with the new options when next needed
    ResetWarmStart();
  }
  // Integral of f^-/sigma^- over Omega^- (cut-cell quadrature) of the last Solve().
  double interior_flux() const { return interior_flux_; }
  // Forget |b| of the last cold solve (call when the data change abruptly, e.g. a new applied
  // field); the next Solve() is cold.
  void ResetWarmStart() { schur_.ResetWarmStart(); }
  // Number of Poisson solves in the last Solve().
  int poisson_solves() const { return poisson_solves_; }
  // Of the last Solve(), relative to their scales (interface_guarantees.h): the largest
  // cubic/quadratic disagreement of phi_n^- (InterfaceSolverOptions::max_fit_disagreement) and
  // the largest marker-scale content of G (max_marker_oscillation; 0 for sigma^- = sigma^+).
  double fit_disagreement() const { return fit_disagreement_; }
  double marker_oscillation() const { return marker_oscillation_; }

 private:
  // The per-curve set-up of Solve: sides, band and crossing pairs, fit rows, F = f / sigma with
  // the side data, the jump data of J at the band points, the interior flux.
  void SetUpBand(const ClosedCurve& curve, const InterfaceProblem& problem);
  // The GMRES unknowns for sigma^- != sigma^+: control markers, or the Fourier basis (its
  // Galerkin test functions and Gram matrix); sets fourier_, every_marker_, unknowns_.
  void ChooseUnknowns(const ClosedCurve& curve);
  // GMRES on the Schur system in the unknowns of ChooseUnknowns (mean deflation, warm path);
  // g: guess in, solution at the markers out. Throws SolverError if GMRES does not converge.
  GmresResult SolveSchurSystem(const ClosedCurve& curve, std::vector<double>& g);
  // Residual R(g) (with_data) or its linear part R(g) - R(0) (without), into r.
  void Residual(const ClosedCurve& curve, const double* g, bool with_data, double* r);
  // sigma^- > sigma^+ only: shifts phi_n^- by a constant so that its integral over the curve
  // equals flux (see the file comment).
  void ImposeInteriorFlux(double flux);
  // Arc weights dl_k, perimeter and interior_flux_ (integral of f^-/sigma^- over Omega^-).
  void ComputeInteriorFlux(const ClosedCurve& curve, const PeriodicCubicSpline& fminus,
                           const PeriodicCubicSpline& fminus_xi, bool f_is_zero);
  // Resolution check before a solve (max_curvature_h, marker spacing); throws SolverError.
  void CheckResolution(const ClosedCurve& curve) const;
  // Marker-scale oscillation of g after a solve (max_marker_oscillation); throws SolverError.
  void CheckMarkerOscillation(const ClosedCurve& curve, const std::vector<double>& g);
  // Richardson estimate from a solve on the grid coarsened twice (verify_min_ratio); returns
  // the relative estimate (-1 if the grid cannot be coarsened), throws SolverError above
  // verify_tolerance.
  double Verify(const ClosedCurve& curve, const InterfaceProblem& problem,
                const std::vector<double>& g);
  // Deferred correction: target += T(phi), values across the curve continued with band_jump_.
  void AddTruncationTo(const std::vector<double>& phi, std::vector<double>& target);
  // Fills band_jump_ for g (plus the data part if with_data) and solves for phi.
  void SolveForPotential(const ClosedCurve& curve, const double* g, bool with_data,
                         std::vector<double>& phi);

  FastPoissonSolver poisson_;
  FastIimOptions options_;
  InterfaceClassification classes_;
  NormalDerivativeFit fit_;
  InterfaceSchurSolver schur_;
  double sigma_minus_ = 1.0, sigma_plus_ = 1.0;
  std::vector<double> v_;         // [sigma phi_n] at the markers
  std::vector<double> rhs_base_;  // F + side data
  std::vector<double> rhs_, phi_work_;
  std::vector<double> band_data_, band_gcoef_, band_gsscoef_, band_jump_;
  std::vector<double> dn_minus_, dn_plus_, dt_minus_, dt_plus_, w_s_;
  std::vector<double> grid_jump_;  // J at band points (deferred correction)
  std::vector<std::uint8_t> grid_jump_known_;
  std::vector<double> scratch_;
  struct BandSample {
    int slot, k;   // band slot, spline segment
    double t, hk;  // offset in the segment, segment length (spline parameter)
    double a, c;   // d^2/dl^2 = a S'' + c S'
  };
  std::vector<BandSample> band_samples_;
  std::vector<std::uint8_t> band_used_;
  std::vector<double> g_second_;
  std::vector<int> control_;   // marker indices of the GMRES unknowns
  bool fourier_ = false;       // the unknowns are Fourier coefficients
  bool every_marker_ = false;  // the unknowns are G at every marker
  int unknowns_ = 0;
  std::vector<double> control_knots_;
  Eigen::MatrixXd basis_;  // ControlBasis::kFourier: M x unknowns
  GalerkinUnknowns fourier_unknowns_;
  std::vector<double> arc_weight_;  // dl_k at the markers
  double perimeter_ = 0.0;
  double interior_flux_ = 0.0;  // integral of f^-/sigma^- over Omega^-
  int poisson_solves_ = 0;
  std::vector<double> dn_check_;  // phi_n^- of the lower-degree fit (fit-agreement check)
  double fit_disagreement_ = 0.0, marker_oscillation_ = 0.0;
  std::unique_ptr<FastIimSolver> coarse_;  // Verify(): the grid coarsened twice
  std::vector<double> coarse_g_, coarse_phi_;
};

}  // namespace ehd
