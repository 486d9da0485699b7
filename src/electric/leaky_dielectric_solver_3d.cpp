// 3D leaky dielectric in a DC field: fast IIM potential and Maxwell force per vertex (see
// leaky_dielectric_solver_3d.h).
#include "ehd_capsule/electric/leaky_dielectric_solver_3d.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

namespace ehd {
namespace {

PoissonBoundaries3D FieldBoundaries() {
  PoissonBoundaries3D bc;
  bc.x_min = bc.x_max = bc.y_min = bc.y_max = BoundaryKind::kNeumann;
  bc.z_min = bc.z_max = BoundaryKind::kDirichlet;
  return bc;
}

}  // namespace

LeakyDielectricSolver3D::LeakyDielectricSolver3D(const Grid3D& grid, double sigma_minus,
                                                 double sigma_plus, double eps_minus,
                                                 double eps_plus, const FastIim3DOptions& options)
    : iim_(grid, FieldBoundaries(), options), eps_minus_(eps_minus), eps_plus_(eps_plus) {
  if (!(sigma_minus > 0) || !(sigma_plus > 0) || !(eps_minus > 0) || !(eps_plus > 0)) {
    throw std::invalid_argument(
        "LeakyDielectricSolver3D: sigma_minus, sigma_plus, eps_minus, eps_plus must be > 0, got " +
        std::to_string(sigma_minus) + ", " + std::to_string(sigma_plus) + ", " +
        std::to_string(eps_minus) + ", " + std::to_string(eps_plus));
  }
  problem_.sigma_minus = sigma_minus;
  problem_.sigma_plus = sigma_plus;
  SetAppliedField(0.0);
}

void LeakyDielectricSolver3D::SetAppliedField(double e) {
  if (e != applied_field_ && applied_field_ != 0.0 && e != 0.0) {
    // G is linear in E (f = w = v = 0, the face data scale with E).
    const double scale = e / applied_field_;
    for (double& v : warm_.g) v *= scale;
    for (double& v : warm_.g_previous) v *= scale;
  }
  applied_field_ = e;
  const Grid3D& g = iim_.grid();
  const std::size_t face = static_cast<std::size_t>(g.nx) * g.ny;
  problem_.boundary.z_min.assign(face, e * g.z0);
  problem_.boundary.z_max.assign(face, e * g.z_max());
  problem_.boundary.x_min.assign(static_cast<std::size_t>(g.ny) * g.nz, 0.0);
  problem_.boundary.x_max.assign(static_cast<std::size_t>(g.ny) * g.nz, 0.0);
  problem_.boundary.y_min.assign(static_cast<std::size_t>(g.nx) * g.nz, 0.0);
  problem_.boundary.y_max.assign(static_cast<std::size_t>(g.nx) * g.nz, 0.0);
}

const InterfaceSolveReport& LeakyDielectricSolver3D::Solve(const TriangleMesh& surface,
                                                           double time) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t m = static_cast<std::size_t>(surface.vertex_count());
  const double t0 = warm_.time_previous, t1 = warm_.time_last;
  const bool have_g1 = warm_.g.size() == m && t1 < time;  // false for NaN t1
  std::vector<double> guess;
  if (have_g1 && warm_.g_previous.size() == m && t0 < t1) {
    const double r = std::min((time - t1) / (t1 - t0), kMaxExtrapolationRatio);
    guess.resize(m);
    for (std::size_t k = 0; k < m; ++k)
      guess[k] = warm_.g[k] + r * (warm_.g[k] - warm_.g_previous[k]);
  } else if (have_g1) {
    guess = warm_.g;
  }
  std::vector<double> g = guess;
  report_ = iim_.Solve(surface, problem_, g, phi_);
  // The solution becomes G1, the previous G1 becomes G0 (only a timed, same-size history).
  warm_.g_previous = have_g1 ? warm_.g : std::vector<double>();
  warm_.time_previous = have_g1 ? t1 : std::numeric_limits<double>::quiet_NaN();
  warm_.g = g;
  warm_.time_last = time;

  const int nv = surface.vertex_count();
  en_minus_.resize(nv);
  en_plus_.resize(nv);
  for (int v = 0; v < nv; ++v) {
    en_minus_[v] = -iim_.normal_derivative_minus()[v];
    en_plus_[v] = -iim_.normal_derivative_plus()[v];
  }
  traction_ =
      MaxwellTraction3D(iim_.normals(), eps_minus_, eps_plus_, en_minus_, en_plus_,
                        -iim_.tangential_gradient_minus(), -iim_.tangential_gradient_plus());
  const SurfaceGeometry geometry = MeasureSurface(surface);
  force_.resize(3, nv);
  for (int v = 0; v < nv; ++v) force_.col(v) = traction_.col(v) * geometry.vertex_area[v];
  report_.solve_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report_;
}

std::vector<double> LeakyDielectricSolver3D::SurfaceCharge() const {
  std::vector<double> q(en_minus_.size());
  for (std::size_t k = 0; k < q.size(); ++k) {
    q[k] = eps_plus_ * en_plus_[k] - eps_minus_ * en_minus_[k];
  }
  return q;
}

}  // namespace ehd
