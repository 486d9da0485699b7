// Leaky dielectric drop in a DC field: fast IIM potential, grid field, Maxwell force
// (see leaky_dielectric_solver.h).
#include "ehd_capsule/electric/leaky_dielectric_solver.h"

#include <chrono>
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
  // A new field strength scales |b|: forget the warm-start reference (same value: keep it, the
  // coupled step calls this before every solve).
  if (e != applied_field_) iim_.ResetWarmStart();
  applied_field_ = e;
  const Grid2D& g = iim_.grid();
  problem_.boundary.y_min.assign(g.nx, e * g.y0);
  problem_.boundary.y_max.assign(g.nx, e * g.y_max());
}

const InterfaceSolveReport& LeakyDielectricSolver::Solve(const ClosedCurve& curve) {
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
