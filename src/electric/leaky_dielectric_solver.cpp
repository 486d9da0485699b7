// Leaky dielectric drop in a DC field: fast IIM potential, grid field, Maxwell force
// (see leaky_dielectric_solver.h).
#include "ehd_capsule/electric/leaky_dielectric_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "ehd_capsule/electric/electric_field.h"

namespace ehd {
namespace {

PoissonBoundaries DropBoundaries() {
  return PoissonBoundaries{BoundaryKind::kNeumann, BoundaryKind::kNeumann, BoundaryKind::kDirichlet,
                           BoundaryKind::kDirichlet};
}

FastIimOptions WithGmres(const GmresOptions& gmres) {
  FastIimOptions o;
  o.gmres = gmres;
  return o;
}

}  // namespace

LeakyDielectricSolver::LeakyDielectricSolver(const Grid2D& grid, double sigma_minus,
                                             double sigma_plus, double eps_minus, double eps_plus,
                                             const GmresOptions& gmres)
    : iim_(grid, DropBoundaries(), WithGmres(gmres)), eps_minus_(eps_minus), eps_plus_(eps_plus) {
  if (!(sigma_minus > 0) || !(sigma_plus > 0) || !(eps_minus > 0) || !(eps_plus > 0)) {
    throw std::invalid_argument(
        "LeakyDielectricSolver: sigma_minus, sigma_plus, eps_minus, eps_plus must be > 0, got " +
        std::to_string(sigma_minus) + ", " + std::to_string(sigma_plus) + ", " +
        std::to_string(eps_minus) + ", " + std::to_string(eps_plus));
  }
  problem_.sigma_minus = sigma_minus;
  problem_.sigma_plus = sigma_plus;
  SetAppliedField(0.0);
}

void LeakyDielectricSolver::SetAppliedField(double e) {
  // A new field strength scales |b|: forget the fast IIM's |b| reference (same value: keep it,
  // the coupled step calls this before every solve), and rescale the stored solutions.
  if (e != applied_field_) {
    iim_.ResetWarmStart();
    if (applied_field_ != 0.0 && e != 0.0) {
      const double scale = e / applied_field_;
      for (double& v : g_) v *= scale;
      for (double& v : history_.g_previous) v *= scale;
    }
  }
  applied_field_ = e;
  const Grid2D& g = iim_.grid();
  problem_.boundary.y_min.assign(g.nx, e * g.y0);
  problem_.boundary.y_max.assign(g.nx, e * g.y_max());
}

void LeakyDielectricSolver::set_jump_normal_derivative(const std::vector<double>& g) {
  g_ = g;
  history_ = WarmStartHistory();
}

const InterfaceSolveReport& LeakyDielectricSolver::Solve(const ClosedCurve& curve) {
  history_ = WarmStartHistory();
  return SolveFromGuess(curve);
}

const InterfaceSolveReport& LeakyDielectricSolver::Solve(const ClosedCurve& curve, double time) {
  const std::size_t m = static_cast<std::size_t>(curve.size());
  const double t0 = history_.time_previous, t1 = history_.time_last;
  std::vector<double>& g0 = history_.g_previous;
  const bool have_g1 = g_.size() == m && t1 < time;  // false for NaN t1
  if (have_g1 && g0.size() == m && t0 < t1) {
    // Linear extrapolation of the last two solutions; G0 <- G1, G1 <- guess.
    const double r = std::min((time - t1) / (t1 - t0), kMaxExtrapolationRatio);
    for (std::size_t k = 0; k < m; ++k) {
      const double g1 = g_[k];
      g_[k] += r * (g1 - g0[k]);
      g0[k] = g1;
    }
  } else if (have_g1) {
    g0 = g_;  // one timed solve so far: plain warm start from G1, which becomes G0
  } else {
    g0.clear();
  }
  history_.time_previous = have_g1 ? t1 : std::numeric_limits<double>::quiet_NaN();
  history_.time_last = time;
  return SolveFromGuess(curve);
}

const InterfaceSolveReport& LeakyDielectricSolver::SolveFromGuess(const ClosedCurve& curve) {
  const auto start = std::chrono::steady_clock::now();
  report_ = iim_.Solve(curve, problem_, g_, phi_);
  ComputeGridField(iim_.classification(), phi_, iim_.band_jump(), ex_, ey_);
  const int m = curve.size();
  en_minus_.resize(m);
  en_plus_.resize(m);
  et_.resize(m);
  et_plus_.resize(m);
  for (int k = 0; k < m; ++k) {
    en_minus_[k] = -iim_.normal_derivative_minus()[k];
    en_plus_[k] = -iim_.normal_derivative_plus()[k];
    et_[k] = -iim_.tangential_derivative_minus()[k];  // [phi] = 0: E_tau is continuous
    et_plus_[k] = -iim_.tangential_derivative_plus()[k];
  }
  force_ = MaxwellForce(curve, eps_minus_, eps_plus_, en_minus_, en_plus_, et_, et_plus_);
  report_.solve_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report_;
}

std::vector<double> LeakyDielectricSolver::SurfaceCharge() const {
  std::vector<double> q(en_minus_.size());
  for (std::size_t k = 0; k < q.size(); ++k) {
    q[k] = eps_plus_ * en_plus_[k] - eps_minus_ * en_minus_[k];
  }
  return q;
}

}  // namespace ehd
