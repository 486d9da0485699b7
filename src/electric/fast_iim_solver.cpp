// Fast immersed interface method (song2019 sec. 2.4; see fast_iim_solver.h for the equations).
#include "ehd_capsule/electric/fast_iim_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "ehd_capsule/electric/box_face_check.h"
#include "ehd_capsule/electric/interface_guarantees.h"
#include "ehd_capsule/electric/jump_relations.h"
#include "ehd_capsule/geometry/gauss_legendre.h"

namespace ehd {
namespace {

constexpr const char* kSolverName = "FastIimSolver";

std::string Point(const ClosedCurve& curve, int k) {
  std::ostringstream o;
  o << "marker " << k << " (" << curve.markers()(0, k) << ", " << curve.markers()(1, k) << ")";
  return o.str();
}

// Primitive of clamp(t, 0, 1).
double ClampPrimitive(double t) { return t < 0.0 ? 0.0 : (t <= 1.0 ? 0.5 * t * t : t - 0.5); }

// Area fraction of the unit square [-1/2, 1/2]^2 where a x + b y < c, (a, b) a unit vector.
double HalfPlaneFraction(double a, double b, double c) {
  if (std::abs(b) < std::abs(a)) std::swap(a, b);  // |b| >= 1/sqrt(2)
  const double alpha = b > 0.0 ? c / b + 0.5 : 0.5 - c / b;
  const double beta = b > 0.0 ? -a / b : a / b;
  if (std::abs(beta) < 1e-12) return std::clamp(alpha, 0.0, 1.0);
  return (ClampPrimitive(alpha + 0.5 * beta) - ClampPrimitive(alpha - 0.5 * beta)) / beta;
}

// First moment, integral of u = (x - x_c).(a, b) over the part u < c of the unit square centred
// at x_c ((a, b) a unit vector): c A(c) - integral of A(u) du from u_min to c (midpoint rule).
double FirstMomentInside(double a, double b, double c) {
  const double u_min = -0.5 * (std::abs(a) + std::abs(b));
  const double u_max = -u_min;
  const double top = std::min(c, u_max);
  if (top <= u_min) return 0.0;
  constexpr int kSteps = 16;
  const double du = (top - u_min) / kSteps;
  double integral = 0.0;
  for (int q = 0; q < kSteps; ++q) integral += HalfPlaneFraction(a, b, u_min + (q + 0.5) * du);
  return top * HalfPlaneFraction(a, b, top) - integral * du;
}

// Area, in units of h^2, between the tangent line through the closest point X* = x_c - d n and
// the curve xi = -kappa eta^2 / 2 (local frame at X*), inside the cell of centre x_c and side h:
// integral of kappa eta^2 / 2 over the part of the tangent line inside the cell, i.e.
// kappa (eta_2^3 - eta_1^3) / 6 (subtract it from the half-plane fraction).
double CurvatureAreaCorrection(const Eigen::Vector2d& n, const Eigen::Vector2d& t, double d,
                               double kappa, double h) {
  double lo = -1e300, hi = 1e300;
  for (int a = 0; a < 2; ++a) {
    // |-d n_a + eta t_a| <= h / 2
    if (std::abs(t[a]) < 1e-14) {
      if (std::abs(d * n[a]) > 0.5 * h) return 0.0;
      continue;
    }
    double e1 = (d * n[a] - 0.5 * h) / t[a], e2 = (d * n[a] + 0.5 * h) / t[a];
    if (e1 > e2) std::swap(e1, e2);
    lo = std::max(lo, e1);
    hi = std::min(hi, e2);
  }
  if (!(hi > lo)) return 0.0;
  return kappa * (hi * hi * hi - lo * lo * lo) / (6.0 * h * h);
}

}  // namespace

FastIimSolver::FastIimSolver(const Grid2D& grid, const PoissonBoundaries& bc,
                             const FastIimOptions& options)
    : poisson_(grid, bc), options_(options) {
  rhs_base_.resize(grid.size());
  rhs_.resize(grid.size());
  phi_work_.resize(grid.size());
}

void FastIimSolver::SolveForPotential(const ClosedCurve& curve, const double* g, bool with_data,
                                      std::vector<double>& phi) {
  const int m = curve.size();
  scratch_.assign(g, g + m);
  const PeriodicCubicSpline gs = curve.FitScalar(scratch_);
  for (int k = 0; k < m; ++k) g_second_[k] = gs.SecondDerivativeAtKnot(k);
  // Cubic spline on the cached segment: S, S' and S'' in the spline parameter, then
  // d^2/dl^2 = a S'' + c S' (see the band sample set-up in Solve()).
  const double* __restrict y = g;
  const double* __restrict mk = g_second_.data();
  for (const BandSample& q : band_samples_) {
    const int k1 = q.k + 1 < m ? q.k + 1 : 0;
    const double u = q.hk - q.t;
    const double ak = y[q.k] / q.hk - mk[q.k] * q.hk / 6.0;
    const double bk = y[k1] / q.hk - mk[k1] * q.hk / 6.0;
    const double value =
        (mk[q.k] * u * u * u + mk[k1] * q.t * q.t * q.t) / (6.0 * q.hk) + ak * u + bk * q.t;
    const double first = (-mk[q.k] * u * u + mk[k1] * q.t * q.t) / (2.0 * q.hk) - ak + bk;
    const double second = (mk[q.k] * u + mk[k1] * q.t) / q.hk;
    const double g_ss = q.a * second + q.c * first;
    band_jump_[q.slot] = (with_data ? band_data_[q.slot] : 0.0) + value * band_gcoef_[q.slot] +
                         g_ss * band_gsscoef_[q.slot];
  }
  if (with_data) {
    rhs_ = rhs_base_;
  } else {
    std::fill(rhs_.begin(), rhs_.end(), 0.0);
  }
  const double inv_h2 = 1.0 / (grid().h * grid().h);
  for (const auto& p : classes_.crossing_pairs()) {
    rhs_[p.centre] += p.neighbour_side * band_jump_[p.neighbour_slot] * inv_h2;
  }
  poisson_.Solve(rhs_, phi);
  ++poisson_solves_;
  if (options_.deferred_correction) {
    // phi^2 = L_h^-1 (F + C + T(phi^1, J)): affine in G like phi^1, so the Schur system below is
    // solved for the corrected potential (warm starts and the GMRES tolerance keep their meaning).
    AddTruncationTo(phi, rhs_);
    poisson_.Solve(rhs_, phi);
    ++poisson_solves_;
  }
}

void FastIimSolver::AddTruncationTo(const std::vector<double>& phi, std::vector<double>& target) {
  // J of the last SolveForPotential at the band points it was evaluated at (all within 2.5 h of
  // the curve when deferred_correction is on).
  // (grid_jump_known_ is set once per Solve() for the band samples.)
  const Grid2D& grid = poisson_.grid();
  const std::vector<int>& points = classes_.band_points();
  for (const BandSample& q : band_samples_) grid_jump_[points[q.slot]] = band_jump_[q.slot];
  AddTruncationCorrection(grid, poisson_.boundaries(), phi, classes_.sides().data(),
                          grid_jump_.data(), grid_jump_known_.data(), target);
}

void FastIimSolver::ImposeInteriorFlux(double flux) {
  if (!(sigma_minus_ > sigma_plus_)) return;
  const int m = static_cast<int>(arc_weight_.size());
  double sum = 0.0;
  for (int k = 0; k < m; ++k) sum += dn_minus_[k] * arc_weight_[k];
  const double shift = (flux - sum) / perimeter_;
  for (int k = 0; k < m; ++k) dn_minus_[k] += shift;
}

void FastIimSolver::Residual(const ClosedCurve& curve, const double* g, bool with_data, double* r) {
  SolveForPotential(curve, g, with_data, phi_work_);
  const int m = curve.size();
  fit_.EvaluateNormal(phi_work_.data(), band_jump_.data(), dn_minus_.data());
  ImposeInteriorFlux(with_data ? interior_flux_ : 0.0);
  const double jump = sigma_plus_ - sigma_minus_;
  for (int k = 0; k < m; ++k) {
    const double data = with_data ? v_[k] / jump : 0.0;
    if (sigma_plus_ > sigma_minus_) {
      r[k] = dn_minus_[k] + (sigma_plus_ / jump) * g[k] - data;  // eq. (50)
    } else {
      r[k] = (dn_minus_[k] + g[k]) + (sigma_minus_ / jump) * g[k] - data;  // eq. (49)
    }
  }
}

void FastIimSolver::ComputeInteriorFlux(const ClosedCurve& curve, const PeriodicCubicSpline& fminus,
                                        const PeriodicCubicSpline& fminus_xi, bool f_is_zero) {
  const Grid2D& grid = poisson_.grid();
  const double h = grid.h;
  const int m = curve.size();
  // Interior flux: the integral of phi_n^- over the curve equals that of F^- = f^-/sigma^- over
  // Omega^- (divergence theorem). Quadrature, O(h^3) for smooth F^- and curve: cells farther
  // than 0.75 h from the curve by their side (midpoint rule); cells cut by the curve with their
  // inside area fraction (half-plane through the closest point minus the sliver between the
  // tangent and the osculating parabola), times F^- at the centre plus d_n F^- times the first
  // moment of the inside part about the centre; plus the (h^2/24) Laplace(F) midpoint term.
  // Arc weights: w_k = integral of L_k dl with L_k the periodic cubic cardinal spline of marker
  // k (5-point Gauss per segment), so that sum_k w_k f_k is the O(ds^4) integral of the spline
  // through f (PeriodicCubicSpline::IntegralWeights, O(M)). The trapezoid weights
  // (l_{k-1} + l_k) / 2 are only O(ds^2) on unevenly spaced markers, and for sigma^- >> sigma^+
  // the mean of G inherits the quadrature error of the flux balance multiplied by
  // (sigma^- - sigma^+) / sigma^+ (the ellipse at 1000:1, N = 80: G off by 10% with the
  // trapezoid weights).
  {
    const PeriodicCubicSpline& xs = curve.x_spline();
    const PeriodicCubicSpline& ys = curve.y_spline();
    std::vector<double> knots(m), speed(m * kGaussPoints);
    for (int j = 0; j < m; ++j) {
      knots[j] = curve.knot(j);
      const double len = (j + 1 < m ? curve.knot(j + 1) : curve.period()) - knots[j];
      for (int q = 0; q < kGaussPoints; ++q) {
        const double t = knots[j] + kGaussNode[q] * len;
        speed[j * kGaussPoints + q] = std::hypot(xs.Derivative(t), ys.Derivative(t));
      }
    }
    arc_weight_ = PeriodicCubicSpline::IntegralWeights(knots, curve.period(), speed);
  }
  perimeter_ = 0.0;
  for (int k = 0; k < m; ++k) perimeter_ += arc_weight_[k];
  interior_flux_ = 0.0;
  if (f_is_zero) return;
  double sum = 0.0;
  for (std::size_t idx = 0; idx < grid.size(); ++idx) {
    const int slot = classes_.band_slot(idx);
    if (slot < 0 || std::abs(classes_.band_distance()[slot]) > 0.75 * h) {
      if (classes_.side(idx) < 0) sum += rhs_base_[idx];
      continue;
    }
    const double s_star = classes_.band_parameter()[slot];
    const CurvePoint c = curve.At(s_star);
    const double d = classes_.band_distance()[slot];
    const double fraction = HalfPlaneFraction(c.normal.x(), c.normal.y(), -d / h) -
                            CurvatureAreaCorrection(c.normal, c.tangent, d, c.curvature, h);
    if (fraction <= 0.0) continue;
    const double dxi_f = fminus_xi.Value(s_star);
    // Inside centres: their own F; outside centres: F^- extrapolated along the normal.
    const double f_centre =
        classes_.side(idx) < 0 ? rhs_base_[idx] : fminus.Value(s_star) + d * dxi_f;
    sum += fraction * f_centre + FirstMomentInside(c.normal.x(), c.normal.y(), -d / h) * h * dxi_f;
  }
  // Midpoint rule per cell: integral = h^2 F_c + (h^4 / 24) Laplace(F)_c + O(h^6); summed over
  // Omega^- the second term is (h^2 / 24) times the integral of Laplace(F^-), i.e. (h^2 / 24)
  // times the curve integral of d_n F^- (divergence theorem), d_n F^- from the one-sided fits.
  double boundary = 0.0;
  for (int k = 0; k < m; ++k) boundary += fminus_xi.Value(curve.knot(k)) * arc_weight_[k];
  interior_flux_ = h * h * sum + h * h / 24.0 * boundary;
}

void FastIimSolver::SetUpBand(const ClosedCurve& curve, const InterfaceProblem& problem) {
  const Grid2D& grid = poisson_.grid();
  const int m = curve.size();
  // Geometry: sides, band, crossing pairs, fit rows.
  const double h = grid.h;
  classes_.Update(grid, curve, options_.band_width_h * h);
  fit_.Update(curve, classes_, options_.fit_radius_h * h, options_.fit_degree);
  const int nb = classes_.band_size();
  band_data_.resize(nb);
  band_gcoef_.resize(nb);
  band_gsscoef_.resize(nb);
  band_jump_.resize(nb);
  dn_minus_.resize(m);
  dn_plus_.resize(m);
  dt_minus_.resize(m);
  dt_plus_.resize(m);
  w_s_.resize(m);
  v_.assign(m, 0.0);
  if (!problem.v.empty()) v_ = problem.v;

  // F = f / sigma of each region, plus the side data.
  for (std::size_t idx = 0; idx < grid.size(); ++idx) {
    const double f = problem.f.empty() ? 0.0 : problem.f[idx];
    rhs_base_[idx] = f / (classes_.side(idx) < 0 ? sigma_minus_ : sigma_plus_);
  }
  // [f/sigma] and [d_xi(f/sigma)] at the markers, then the data part of J at band points.
  std::vector<double>& fm = dn_plus_;  // reuse marker buffers as scratch
  std::vector<double>& fp = dt_plus_;
  std::vector<double>& fm_xi = dn_minus_;
  std::vector<double>& fp_xi = dt_minus_;
  fit_.SideExtrapolation(rhs_base_.data(), fm.data(), fp.data(), fm_xi.data(), fp_xi.data());
  const PeriodicCubicSpline fminus = curve.FitScalar(fm);
  const PeriodicCubicSpline fminus_xi = curve.FitScalar(fm_xi);
  for (int k = 0; k < m; ++k) {
    fm[k] = fp[k] - fm[k];
    fm_xi[k] = fp_xi[k] - fm_xi[k];
  }
  const PeriodicCubicSpline fjump = curve.FitScalar(fm);
  const PeriodicCubicSpline fjump_xi = curve.FitScalar(fm_xi);
  ComputeInteriorFlux(curve, fminus, fminus_xi, problem.f.empty());
  const bool has_w = !problem.w.empty();
  PeriodicCubicSpline ws;
  if (has_w) ws = curve.FitScalar(problem.w);
  const std::vector<double>& bs = classes_.band_parameter();
  const std::vector<double>& bd = classes_.band_distance();
  const std::vector<double>& bk = classes_.band_curvature();
  scratch_.resize(m);
  for (int k = 0; k < m; ++k) scratch_[k] = curve.AtMarker(k).curvature;
  const PeriodicCubicSpline kappa_spline = curve.FitScalar(scratch_);
  for (int b = 0; b < nb; ++b) {
    double w = 0.0, w_s = 0.0, w_ss = 0.0, kappa_s = 0.0, kappa_ss = 0.0;
    if (has_w) {
      w = ws.Value(bs[b]);
      curve.ArcLengthDerivatives(ws, bs[b], &w_s, &w_ss);
    }
    curve.ArcLengthDerivatives(kappa_spline, bs[b], &kappa_s, &kappa_ss);
    band_data_[b] = JumpDataPart(w, w_s, w_ss, fjump.Value(bs[b]), fjump_xi.Value(bs[b]), bk[b],
                                 kappa_s, bd[b]);
    band_gcoef_[b] = JumpGCoefficient(bd[b], bk[b]);
    band_gsscoef_[b] = JumpGssCoefficient(bd[b]);
  }
  // Band points whose J is used (neighbours across a stencil, outside WLS fit points), with
  // their spline segment and the arc-length factors d^2/dl^2 = S''/|X'|^2 - S' X'.X''/|X'|^4.
  band_used_.assign(nb, 0);
  for (const auto& pair : classes_.crossing_pairs()) band_used_[pair.neighbour_slot] = 1;
  for (int idx : fit_.points()) {
    if (classes_.side(idx) > 0) band_used_[classes_.band_slot(idx)] = 1;
  }
  // The deferred correction continues values up to 2 cells across the curve: J at every band
  // point within 2 h (with margin) of it.
  if (options_.deferred_correction) {
    for (int b = 0; b < nb; ++b) {
      if (std::abs(bd[b]) < 2.5 * h) band_used_[b] = 1;
    }
  }
  band_samples_.clear();
  g_second_.resize(m);
  for (int b = 0; b < nb; ++b) {
    band_jump_[b] = 0.0;
    if (!band_used_[b]) continue;
    BandSample q;
    q.slot = b;
    q.k = curve.x_spline().Locate(bs[b], &q.t);
    q.hk = (q.k + 1 < m ? curve.knot(q.k + 1) : curve.period()) - curve.knot(q.k);
    const Eigen::Vector2d r1(curve.x_spline().Derivative(bs[b]),
                             curve.y_spline().Derivative(bs[b]));
    const Eigen::Vector2d r2(curve.x_spline().SecondDerivative(bs[b]),
                             curve.y_spline().SecondDerivative(bs[b]));
    const double speed2 = r1.squaredNorm();
    q.a = 1.0 / speed2;
    q.c = -r1.dot(r2) / (speed2 * speed2);
    band_samples_.push_back(q);
  }
  if (options_.deferred_correction) {
    grid_jump_.assign(grid.size(), 0.0);
    grid_jump_known_.assign(grid.size(), 0);
    const std::vector<int>& points = classes_.band_points();
    for (const BandSample& q : band_samples_) grid_jump_known_[points[q.slot]] = 1;
  }
  for (int k = 0; k < m; ++k) {
    double w_ss = 0.0;
    w_s_[k] = 0.0;
    if (has_w) curve.ArcLengthDerivatives(ws, curve.knot(k), &w_s_[k], &w_ss);
  }
  AddDirichletGhostCorrection(grid, poisson_.boundaries(), problem.boundary, rhs_base_);
  AddBoundaryDataToRhs(grid, poisson_.boundaries(), problem.boundary, rhs_base_);
}

void FastIimSolver::ChooseUnknowns(const ClosedCurve& curve) {
  const int m = curve.size();
  const double h = poisson_.grid().h;
  // Control markers: every stride-th marker, stride from the mean spacing so that controls are
  // >= min_control_spacing_h h apart on average; then, walking along the curve, a candidate
  // closer than 3/4 of that to the previous control (or the last one to the first) is
  // dropped. G at the other markers is the periodic spline through the control values. The
  // walk matters where markers bunch (a deforming drop's tips gather them 0.24 h apart):
  // controls closer than the grid resolves are near-null modes of the Schur system for
  // sigma^- > sigma^+, and a drop in shear and field blew up on them.
  // Only for sigma^- > sigma^+: for sigma^+ > sigma^- the Schur system has no near-null
  // modes, every marker is a control, and the result does not depend on the marker order
  // (thinning there cost up to 6x accuracy and made the answer depend on the direction of the
  // markers).
  const double min_spacing = sigma_minus_ > sigma_plus_ ? options_.min_control_spacing_h * h : 0.0;
  const int stride =
      std::max(1, static_cast<int>(std::ceil(min_spacing * m / curve.ArcLength() - 1e-9)));
  control_.clear();
  control_.push_back(0);
  double since_last = 0.0;
  for (int k = 1; k < m; ++k) {
    since_last += curve.SegmentArcLength(k - 1);
    if (k % stride == 0 && since_last >= 0.75 * min_spacing) {
      control_.push_back(k);
      since_last = 0.0;
    }
  }
  if (min_spacing > 0.0 && control_.size() > 1 &&
      since_last + curve.SegmentArcLength(m - 1) < 0.75 * min_spacing) {
    control_.pop_back();
  }
  // Fourier basis in arc length (FastIimOptions::control_basis): G(s) = c_0 + sum_j
  // (a_j cos(2 pi j s / P) + b_j sin(2 pi j s / P)), j <= K, with as many unknowns as the
  // controls above would have; the residual is projected on the same basis with the arc
  // weights (Galerkin). The span does not depend on which marker is first nor on the marker
  // direction (s -> s + c rotates each cos/sin pair, s -> P - s flips the sines).
  const bool by_wavelength =
      sigma_minus_ >= options_.basis_min_ratio * sigma_plus_ && options_.basis_wavelength_h > 0.0;
  fourier_ = options_.control_basis == ControlBasis::kFourier &&
             (static_cast<int>(control_.size()) < m || by_wavelength);
  unknowns_ = static_cast<int>(control_.size());
  if (fourier_) {
    const int k_max =
        by_wavelength
            ? std::max(2, std::min(static_cast<int>(perimeter_ / (options_.basis_wavelength_h * h)),
                                   (m - 1) / 2))
            : std::max(2, (unknowns_ - 1) / 2);
    unknowns_ = 2 * k_max + 1;
    basis_.resize(m, unknowns_);
    double arc = 0.0;
    const double period = perimeter_;
    for (int k = 0; k < m; ++k) {
      basis_(k, 0) = 1.0;
      for (int j = 1; j <= k_max; ++j) {
        const double angle = 2.0 * M_PI * j * arc / period;
        basis_(k, 2 * j - 1) = std::cos(angle);
        basis_(k, 2 * j) = std::sin(angle);
      }
      arc += curve.SegmentArcLength(k);
    }
    std::vector<double> test_weight(m);
    for (int k = 0; k < m; ++k) test_weight[k] = arc_weight_[k] / perimeter_;
    fourier_unknowns_.Set(basis_, test_weight);
  }
  every_marker_ = !fourier_ && unknowns_ == m;
  if (unknowns_ < 4) {
    throw std::invalid_argument("FastIimSolver: only " + std::to_string(unknowns_) +
                                " control markers (curve too small for the grid?)");
  }
  if (!fourier_) {
    control_knots_.resize(unknowns_);
    for (int c = 0; c < unknowns_; ++c) control_knots_[c] = curve.knot(control_[c]);
  }
}

namespace {

// ControlBasis::kSplineControls: G at the control markers, the periodic spline through them at
// the others; the residual is sampled at the controls.
class SplineControlUnknowns final : public InterfaceUnknowns {
 public:
  SplineControlUnknowns(const ClosedCurve& curve, const std::vector<int>& control,
                        const std::vector<double>& knots)
      : curve_(curve), control_(control), knots_(knots) {}
  int count() const override { return static_cast<int>(control_.size()); }
  void Expand(const double* x, double* g) const override {
    values_.assign(x, x + count());
    spline_.Fit(knots_, curve_.period(), values_);
    for (int k = 0; k < curve_.size(); ++k) g[k] = spline_.Value(curve_.knot(k));
  }
  void Restrict(const double* r, double* rx) const override {
    for (int c = 0; c < count(); ++c) rx[c] = r[control_[c]];
  }
  void Project(const double* g, double* x) const override { Restrict(g, x); }

 private:
  const ClosedCurve& curve_;
  const std::vector<int>& control_;
  const std::vector<double>& knots_;
  mutable PeriodicCubicSpline spline_;
  mutable std::vector<double> values_;
};

}  // namespace

GmresResult FastIimSolver::SolveSchurSystem(const ClosedCurve& curve, std::vector<double>& g) {
  const int m = curve.size();
  const PointUnknowns every_marker(m);
  const SplineControlUnknowns controls(curve, control_, control_knots_);
  const InterfaceUnknowns& unknowns =
      every_marker_ ? static_cast<const InterfaceUnknowns&>(every_marker)
                    : (fourier_ ? static_cast<const InterfaceUnknowns&>(fourier_unknowns_)
                                : static_cast<const InterfaceUnknowns&>(controls));
  // Mean deflation (FastIimOptions::deflate_mean): with R_k = phi_n^-_k + c G_k - v_k/[sigma],
  // c = sigma^+/[sigma], and sum_k phi_n^-_k dl_k = flux imposed exactly, R = 0 implies
  // mean(G) = mu (interface_schur_system.h).
  MeanDeflation deflation;
  deflation.active = sigma_minus_ > sigma_plus_ && options_.deflate_mean;
  if (deflation.active) {
    const double jump_sigma = sigma_plus_ - sigma_minus_;
    double mean_v = 0.0;
    for (int k = 0; k < m; ++k) mean_v += arc_weight_[k] * v_[k];
    mean_v /= perimeter_;
    deflation.target =
        (mean_v / jump_sigma - interior_flux_ / perimeter_) / (sigma_plus_ / jump_sigma);
    deflation.mean = [&](const double* gm) {
      double s = 0.0;
      for (int k = 0; k < m; ++k) s += arc_weight_[k] * gm[k];
      return s / perimeter_;
    };
  }
  const InterfaceSchurSolver::PointResidual residual =
      [&](const double* gm, bool with_data, double* r) { Residual(curve, gm, with_data, r); };
  const GmresResult r = schur_.Solve(unknowns, m, residual, deflation, options_.gmres,
                                     options_.warm_start_refresh, g);
  if (!r.converged) {
    std::ostringstream msg;
    msg << "FastIimSolver: GMRES did not converge: " << r.iterations << " iterations, residual "
        << r.residual << " > tolerance " << options_.gmres.tolerance
        << " x |b| = " << options_.gmres.tolerance * r.reference << " (sigma- = " << sigma_minus_
        << ", sigma+ = " << sigma_plus_ << ", " << m << " markers, " << unknowns.count()
        << " control)";
    throw SolverError(msg.str());
  }
  return r;
}

InterfaceSolveReport FastIimSolver::Solve(const ClosedCurve& curve, const InterfaceProblem& problem,
                                          std::vector<double>& g, std::vector<double>& phi) {
  const auto start = std::chrono::steady_clock::now();
  const Grid2D& grid = poisson_.grid();
  const int m = curve.size();
  if (!(problem.sigma_minus > 0.0) || !(problem.sigma_plus > 0.0)) {
    throw std::invalid_argument("FastIimSolver: sigma_minus and sigma_plus must be > 0, got " +
                                std::to_string(problem.sigma_minus) + " and " +
                                std::to_string(problem.sigma_plus));
  }
  if (!problem.f.empty() && problem.f.size() != grid.size()) {
    throw std::invalid_argument("FastIimSolver: problem.f has " + std::to_string(problem.f.size()) +
                                " values, grid has " + std::to_string(grid.size()));
  }
  auto check_marker_size = [m](const std::vector<double>& x, const char* name) {
    if (!x.empty() && static_cast<int>(x.size()) != m) {
      throw std::invalid_argument(std::string("FastIimSolver: problem.") + name + " has " +
                                  std::to_string(x.size()) + " values, curve has " +
                                  std::to_string(m) + " markers");
    }
  };
  check_marker_size(problem.w, "w");
  check_marker_size(problem.v, "v");
  poisson_solves_ = 0;
  sigma_minus_ = problem.sigma_minus;
  sigma_plus_ = problem.sigma_plus;
  CheckInnerRatio(kSolverName, sigma_minus_, sigma_plus_, options_.max_inner_ratio);
  CheckResolution(curve);
  const GridDoubleCrossing<2> thin = FindMultipleCrossing(grid, curve);
  if (thin.found) ThrowThinPart(kSolverName, "curve", thin, grid.h);

  SetUpBand(curve, problem);

  InterfaceSolveReport report;
  if (sigma_plus_ == sigma_minus_) {
    // [phi_n] = v / sigma is known: one solve.
    g.resize(m);
    for (int k = 0; k < m; ++k) g[k] = v_[k] / sigma_plus_;
    report.converged = true;
  } else {
    ChooseUnknowns(curve);
    const GmresResult r = SolveSchurSystem(curve, g);
    report.iterations = r.iterations;
    report.residual = r.residual;
    report.converged = r.converged;
  }
  SolveForPotential(curve, g.data(), true, phi);
  fit_.Evaluate(phi.data(), band_jump_.data(), dn_minus_.data(), dt_minus_.data());
  // The lower-degree fit's phi_n^-, kept as its difference from the fit's (ImposeInteriorFlux
  // shifts both alike).
  dn_check_.resize(m);
  fit_.EvaluateNormalCheck(phi.data(), band_jump_.data(), dn_check_.data());
  for (int k = 0; k < m; ++k) dn_check_[k] -= dn_minus_[k];
  ImposeInteriorFlux(interior_flux_);
  for (int k = 0; k < m; ++k) {
    dn_plus_[k] = dn_minus_[k] + g[k];
    dt_plus_[k] = dt_minus_[k] + w_s_[k];
    dn_check_[k] += dn_minus_[k];
  }
  marker_oscillation_ = 0.0;
  if (sigma_plus_ != sigma_minus_) CheckMarkerOscillation(curve, g);
  fit_disagreement_ =
      CheckFitAgreement(kSolverName, dn_minus_, dn_check_, g, options_.max_fit_disagreement,
                        [&](int k) { return Point(curve, k); });
  if (sigma_plus_ != sigma_minus_ && sigma_minus_ >= options_.verify_min_ratio * sigma_plus_) {
    report.estimated_error = Verify(curve, problem, g);
  }
  report.solve_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report;
}

// Four markers per full turn of the local curvature: the periodic spline through them still
// places the curve within ~1% of the curvature radius.
constexpr double kMaxTurnPerSegment = M_PI / 2;

void FastIimSolver::CheckResolution(const ClosedCurve& curve) const {
  // Curvature at the grid scale: the Menger curvature 4 area / (|ab| |bc| |ca|) of the marker
  // and the nearest markers at least h away along the chain on each side. It is the curvature
  // the grid can see; the spline's curvature at a marker also reacts to marker-scale jitter
  // (bunched drop markers, a sawtooth of 0.01 h between two filter passes), which the jump
  // expansion does not (it uses the closest points of band points, a cell or more away).
  const Grid2D& g = poisson_.grid();
  const double h = g.h;
  const Eigen::Matrix2Xd& x = curve.markers();
  const int m = curve.size();
  CheckInsideBoxFaces(g, x, options_.min_face_distance_h, "FastIimSolver", "marker");
  auto menger = [&](int a, int b, int c) {
    const Eigen::Vector2d u = x.col(b) - x.col(a), v = x.col(c) - x.col(b);
    const Eigen::Vector2d w = x.col(c) - x.col(a);
    const double denominator = u.norm() * v.norm() * w.norm();
    return denominator > 0.0 ? 2.0 * std::abs(u.x() * v.y() - u.y() * v.x()) / denominator : 0.0;
  };
  int worst = -1;
  double worst_kh = 0.0;
  for (int k = 0; k < m; ++k) {
    int back = k, ahead = k;
    for (int j = 1; j < m / 4; ++j) {
      back = (k - j + m) % m;
      if ((x.col(k) - x.col(back)).norm() >= h) break;
    }
    for (int j = 1; j < m / 4; ++j) {
      ahead = (k + j) % m;
      if ((x.col(ahead) - x.col(k)).norm() >= h) break;
    }
    const double kh = menger(back, k, ahead) * h;
    if (kh > worst_kh) {
      worst_kh = kh;
      worst = k;
    }
  }
  if (worst_kh > options_.max_curvature_h) {
    std::ostringstream msg;
    msg << "FastIimSolver: the curve is not resolved by the grid at " << Point(curve, worst)
        << ": curvature radius " << 1.0 / worst_kh << " h < " << 1.0 / options_.max_curvature_h
        << " h (|kappa| h = " << worst_kh << " > max_curvature_h = " << options_.max_curvature_h
        << ", curvature through the markers 1 h away on each side); refine the grid to h <= "
        << options_.max_curvature_h * h / worst_kh << " (now " << h << ")";
    throw SolverError(msg.str());
  }
  for (int k = 0; k < m; ++k) {
    const int k1 = k + 1 < m ? k + 1 : 0;
    // Turning of the curve over one segment, from the circle through it and its neighbours.
    const double kappa = std::max(menger((k + m - 1) % m, k, k1), menger(k, k1, (k1 + 1) % m));
    const double turn = kappa * curve.SegmentArcLength(k);
    if (turn > kMaxTurnPerSegment) {
      std::ostringstream msg;
      msg << "FastIimSolver: markers too sparse for the curve between " << Point(curve, k)
          << " and marker " << k1 << ": the tangent turns by " << turn
          << " rad over one segment (limit pi/2); add markers (segment "
          << curve.SegmentArcLength(k) << ", curvature radius " << 1.0 / kappa << ")";
      throw SolverError(msg.str());
    }
  }
}

void FastIimSolver::CheckMarkerOscillation(const ClosedCurve& curve, const std::vector<double>& g) {
  const int m = curve.size();
  double scale = 0.0;
  scratch_.resize(m);
  for (int k = 0; k < m; ++k) {
    scale = std::max({scale, std::abs(g[k]), std::abs(dn_plus_[k]), std::abs(dn_minus_[k])});
    // Fourth difference / 16 along the markers: the marker-scale part of G (a smooth G gives
    // (dl)^4 G'''' / 16; a spike of size s at one marker gives 3 s / 8).
    const double d4 = g[(k + m - 2) % m] - 4.0 * g[(k + m - 1) % m] + 6.0 * g[k] -
                      4.0 * g[(k + 1) % m] + g[(k + 2) % m];
    scratch_[k] = std::abs(d4) / 16.0;
  }
  marker_oscillation_ = CheckPointOscillation(
      kSolverName, "marker", scratch_, scale, options_.max_marker_oscillation,
      [&](int k) { return Point(curve, k); },
      [&](int k) {
        std::ostringstream o;
        o << " (curvature radius there " << 1.0 / std::abs(curve.AtMarker(k).curvature) / grid().h
          << " h)";
        return o.str();
      });
}

double FastIimSolver::Verify(const ClosedCurve& curve, const InterfaceProblem& problem,
                             const std::vector<double>& g) {
  const Grid2D& fine = poisson_.grid();
  if (fine.nx % 2 != 0 || fine.ny % 2 != 0 || fine.nx < 32 || fine.ny < 32) {
    std::ostringstream msg;
    msg << "FastIimSolver: cannot verify the solution for sigma-/sigma+ = "
        << sigma_minus_ / sigma_plus_ << " (>= verify_min_ratio = " << options_.verify_min_ratio
        << ", where the discretisation error is amplified) on a " << fine.nx << " x " << fine.ny
        << " grid: the check coarsens the grid twice and needs even sizes >= 32";
    throw SolverError(msg.str());
  }
  Grid2D coarse = fine;
  coarse.nx /= 2;
  coarse.ny /= 2;
  coarse.h *= 2.0;
  if (!coarse_) {
    FastIimOptions o = options_;
    o.verify_min_ratio = std::numeric_limits<double>::infinity();
    // The coarse grid resolves the curve half as well; its own resolution check is the fine
    // one's (a tip resolved only on the fine grid cannot be verified: reported below).
    coarse_ = std::make_unique<FastIimSolver>(coarse, poisson_.boundaries(), o);
  }
  // The problem on the coarse grid: f averaged over the fine cells of the coarse cell that lie
  // on the coarse centre's side, side data averaged in pairs, marker data unchanged.
  InterfaceProblem cp;
  cp.sigma_minus = problem.sigma_minus;
  cp.sigma_plus = problem.sigma_plus;
  cp.w = problem.w;
  cp.v = problem.v;
  if (!problem.f.empty()) {
    cp.f.assign(coarse.size(), 0.0);
    for (int J = 0; J < coarse.ny; ++J) {
      for (int I = 0; I < coarse.nx; ++I) {
        int side_sum = 0;
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di)
            side_sum += classes_.side(fine.index(2 * I + di, 2 * J + dj));
        int side = side_sum > 0 ? 1 : -1;
        if (side_sum == 0) side = curve.Contains({coarse.x(I), coarse.y(J)}) ? -1 : 1;
        double sum = 0.0;
        int count = 0;
        for (int dj = 0; dj < 2; ++dj) {
          for (int di = 0; di < 2; ++di) {
            const std::size_t idx = fine.index(2 * I + di, 2 * J + dj);
            if (classes_.side(idx) == side) {
              sum += problem.f[idx];
              ++count;
            }
          }
        }
        cp.f[coarse.index(I, J)] = count > 0 ? sum / count : 0.0;
      }
    }
  }
  auto pairs = [](const std::vector<double>& in, std::vector<double>& out) {
    out.resize(in.size() / 2);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = 0.5 * (in[2 * i] + in[2 * i + 1]);
  };
  if (!problem.boundary.x_min.empty()) pairs(problem.boundary.x_min, cp.boundary.x_min);
  if (!problem.boundary.x_max.empty()) pairs(problem.boundary.x_max, cp.boundary.x_max);
  if (!problem.boundary.y_min.empty()) pairs(problem.boundary.y_min, cp.boundary.y_min);
  if (!problem.boundary.y_max.empty()) pairs(problem.boundary.y_max, cp.boundary.y_max);
  coarse_g_.clear();  // cold: a warm start would keep the fine near-null component
  try {
    coarse_->Solve(curve, cp, coarse_g_, coarse_phi_);
  } catch (const SolverError& e) {
    std::ostringstream msg;
    msg << "FastIimSolver: cannot verify the solution for sigma-/sigma+ = "
        << sigma_minus_ / sigma_plus_ << " (>= verify_min_ratio = " << options_.verify_min_ratio
        << "): the grid coarsened twice fails (" << e.what()
        << "); at this conductivity ratio the curve needs twice this resolution: refine the grid "
           "(N)";
    throw SolverError(msg.str());
  }
  const int m = curve.size();
  double scale = 0.0, worst = 0.0;
  int worst_k = 0;
  for (int k = 0; k < m; ++k) {
    scale = std::max({scale, std::abs(g[k]), std::abs(dn_plus_[k]), std::abs(dn_minus_[k])});
    const double d = std::max(std::abs(g[k] - coarse_g_[k]),
                              std::abs(dn_plus_[k] - coarse_->normal_derivative_plus()[k]));
    if (d > worst) {
      worst = d;
      worst_k = k;
    }
  }
  // Second order: X_h - X = (X_2h - X_h) / 3.
  const double estimate = scale > 0.0 ? worst / 3.0 / scale : 0.0;
  if (!(estimate <= options_.verify_tolerance)) {
    std::ostringstream msg;
    msg << "FastIimSolver: estimated error " << estimate
        << " of [phi_n] / phi_n^+ (relative to their max " << scale << ") at "
        << Point(curve, worst_k) << " > verify_tolerance = " << options_.verify_tolerance
        << " (sigma-/sigma+ = " << sigma_minus_ / sigma_plus_
        << ": the near-null mode of the Schur system amplifies the "
        << "discretisation error; curvature radius there "
        << 1.0 / std::abs(curve.AtMarker(worst_k).curvature) / fine.h << " h); refine the grid (N)";
    throw SolverError(msg.str());
  }
  return estimate;
}

}  // namespace ehd
