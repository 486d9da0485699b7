// The leaky-dielectric layer over the fast IIM of each dimension (leaky_dielectric_solver.h):
// the warm start, the field strength and the charge are one code; the box data and the Maxwell
// force are each dimension's (FieldGeometry<D>).
#include "ehd_capsule/electric/leaky_dielectric_solver.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <utility>

#include "ehd_capsule/electric/electric_field.h"

namespace ehd {
namespace {

template <int D>
struct FieldGeometry;

template <>
struct FieldGeometry<2> {
  static constexpr const char* kName = "LeakyDielectricSolver<2>";
  // phi = E y on the y sides, dphi/dx = 0 on the x sides.
  static PoissonBoundaries Boundaries() {
    return PoissonBoundaries{BoundaryKind::kNeumann, BoundaryKind::kNeumann,
                             BoundaryKind::kDirichlet, BoundaryKind::kDirichlet};
  }
  static void SetFieldData(const Grid2D& g, double e, InterfaceProblem& problem) {
    problem.boundary.y_min.assign(g.nx, e * g.y0);
    problem.boundary.y_max.assign(g.nx, e * g.y_max());
  }
  // A new field scales |b|: the solver's warm-start reference is forgotten.
  static void FieldChanged(FastIimSolver& iim) { iim.ResetWarmStart(); }
  // F_E = [M_E] . n per unit length (eq. (148)), with each side's E_tau (continuous for
  // [phi] = 0; with a jump w, E_tau^+ = E_tau^- - w').
  static void Force(const FastIimSolver& iim, const ClosedCurve& curve, double eps_minus,
                    double eps_plus, const std::vector<double>& en_minus,
                    const std::vector<double>& en_plus, Eigen::Matrix2Xd& traction,
                    Eigen::Matrix2Xd& force) {
    const int m = curve.size();
    std::vector<double> et_minus(m), et_plus(m);
    for (int k = 0; k < m; ++k) {
      et_minus[k] = -iim.tangential_derivative_minus()[k];
      et_plus[k] = -iim.tangential_derivative_plus()[k];
    }
    force = MaxwellForce(curve, eps_minus, eps_plus, en_minus, en_plus, et_minus, et_plus);
    traction = force;
  }
  static std::vector<std::vector<double>> GridField(const FastIimSolver& iim,
                                                    const std::vector<double>& phi) {
    std::vector<std::vector<double>> e(2);
    ComputeGridField(iim.classification(), phi, iim.band_jump(), e[0], e[1]);
    return e;
  }
};

template <>
struct FieldGeometry<3> {
  static constexpr const char* kName = "LeakyDielectricSolver<3>";
  // phi = E z on the z faces, zero normal derivative on the x and y faces (song2019 ch. 6).
  static PoissonBoundaries3D Boundaries() {
    PoissonBoundaries3D bc;
    bc.x_min = bc.x_max = bc.y_min = bc.y_max = BoundaryKind::kNeumann;
    bc.z_min = bc.z_max = BoundaryKind::kDirichlet;
    return bc;
  }
  static void SetFieldData(const Grid3D& g, double e, InterfaceProblem3D& problem) {
    const std::size_t face = static_cast<std::size_t>(g.nx) * g.ny;
    problem.boundary.z_min.assign(face, e * g.z0);
    problem.boundary.z_max.assign(face, e * g.z_max());
    problem.boundary.x_min.assign(static_cast<std::size_t>(g.ny) * g.nz, 0.0);
    problem.boundary.x_max.assign(static_cast<std::size_t>(g.ny) * g.nz, 0.0);
    problem.boundary.y_min.assign(static_cast<std::size_t>(g.nx) * g.nz, 0.0);
    problem.boundary.y_max.assign(static_cast<std::size_t>(g.nx) * g.nz, 0.0);
  }
  // As in 2D (the warm-start reference of InterfaceSolverOptions::warm_start_refresh).
  static void FieldChanged(FastIimSolver3D& iim) { iim.ResetWarmStart(); }
  // [M_E] . n per unit area, times the vertex area for the force per vertex.
  static void Force(const FastIimSolver3D& iim, const TriangleMesh& surface, double eps_minus,
                    double eps_plus, const std::vector<double>& en_minus,
                    const std::vector<double>& en_plus, Eigen::Matrix3Xd& traction,
                    Eigen::Matrix3Xd& force) {
    traction = MaxwellTraction3D(iim.normals(), eps_minus, eps_plus, en_minus, en_plus,
                                 -iim.tangential_gradient_minus(), -iim.tangential_gradient_plus());
    const SurfaceGeometry geometry = MeasureSurface(surface);
    const int nv = surface.vertex_count();
    force.resize(3, nv);
    for (int v = 0; v < nv; ++v) force.col(v) = traction.col(v) * geometry.vertex_area[v];
  }
  static std::vector<std::vector<double>> GridField(const FastIimSolver3D& iim,
                                                    const std::vector<double>& phi) {
    std::vector<std::vector<double>> e(3);
    iim.GridField(phi, e[0], e[1], e[2]);
    return e;
  }
};

int PointCount(const ClosedCurve& curve) { return curve.size(); }
int PointCount(const TriangleMesh& surface) { return surface.vertex_count(); }

}  // namespace

template <int D>
LeakyDielectricSolver<D>::LeakyDielectricSolver(const Grid<D>& grid, double sigma_minus,
                                                double sigma_plus, double eps_minus,
                                                double eps_plus, const Options& options)
    : iim_(grid, FieldGeometry<D>::Boundaries(), options),
      eps_minus_(eps_minus),
      eps_plus_(eps_plus) {
  if (!(sigma_minus > 0) || !(sigma_plus > 0) || !(eps_minus > 0) || !(eps_plus > 0)) {
    throw std::invalid_argument(std::string(FieldGeometry<D>::kName) +
                                ": sigma_minus, sigma_plus, eps_minus, eps_plus must be > 0, got " +
                                std::to_string(sigma_minus) + ", " + std::to_string(sigma_plus) +
                                ", " + std::to_string(eps_minus) + ", " + std::to_string(eps_plus));
  }
  problem_.sigma_minus = sigma_minus;
  problem_.sigma_plus = sigma_plus;
  SetAppliedField(0.0);
}

template <int D>
void LeakyDielectricSolver<D>::SetAppliedField(double e) {
  // The same value: nothing changes (the coupled step calls this before every solve).
  if (e != applied_field_) {
    FieldGeometry<D>::FieldChanged(iim_);
    const auto nonzero = [](double x) { return x != 0.0; };
    const bool jumps = std::any_of(problem_.w.begin(), problem_.w.end(), nonzero) ||
                       std::any_of(problem_.v.begin(), problem_.v.end(), nonzero);
    if (applied_field_ != 0.0 && e != 0.0 && !jumps) {
      const double scale = e / applied_field_;
      for (double& v : warm_.g) v *= scale;
      for (double& v : warm_.g_previous) v *= scale;
    }
  }
  applied_field_ = e;
  FieldGeometry<D>::SetFieldData(iim_.grid(), e, problem_);
}

template <int D>
void LeakyDielectricSolver<D>::SetInterfaceJumps(std::vector<double> w, std::vector<double> v) {
  problem_.w = std::move(w);
  problem_.v = std::move(v);
  FieldGeometry<D>::FieldChanged(iim_);  // new data: the 2D solver's |b| reference is stale
}

template <int D>
const InterfaceSolveReport& LeakyDielectricSolver<D>::Solve(const Shape& shape) {
  warm_.g_previous.clear();
  warm_.time_previous = warm_.time_last = std::numeric_limits<double>::quiet_NaN();
  return SolveFromGuess(shape);
}

template <int D>
const InterfaceSolveReport& LeakyDielectricSolver<D>::Solve(const Shape& shape, double time) {
  const std::size_t m = static_cast<std::size_t>(PointCount(shape));
  const double t0 = warm_.time_previous, t1 = warm_.time_last;
  std::vector<double>& g1 = warm_.g;
  std::vector<double>& g0 = warm_.g_previous;
  const bool have_g1 = g1.size() == m && t1 < time;  // false for NaN t1
  if (have_g1 && g0.size() == m && t0 < t1) {
    // Linear extrapolation of the last two solutions; G0 <- G1, G1 <- the guess.
    const double r = std::min((time - t1) / (t1 - t0), kMaxExtrapolationRatio);
    for (std::size_t k = 0; k < m; ++k) {
      const double last = g1[k];
      g1[k] = last + r * (last - g0[k]);
      g0[k] = last;
    }
  } else if (have_g1) {
    g0 = g1;  // one timed solve so far: plain warm start from G1, which becomes G0
  } else {
    g0.clear();
  }
  warm_.time_previous = have_g1 ? t1 : std::numeric_limits<double>::quiet_NaN();
  warm_.time_last = time;
  return SolveFromGuess(shape);
}

template <int D>
const InterfaceSolveReport& LeakyDielectricSolver<D>::SolveFromGuess(const Shape& shape) {
  const auto start = std::chrono::steady_clock::now();
  report_ = iim_.Solve(shape, problem_, warm_.g, phi_);  // G1: guess in, solution out
  const int n = PointCount(shape);
  en_minus_.resize(n);
  en_plus_.resize(n);
  for (int k = 0; k < n; ++k) {
    en_minus_[k] = -iim_.normal_derivative_minus()[k];
    en_plus_[k] = -iim_.normal_derivative_plus()[k];
  }
  FieldGeometry<D>::Force(iim_, shape, eps_minus_, eps_plus_, en_minus_, en_plus_, traction_,
                          force_);
  report_.solve_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report_;
}

template <int D>
std::vector<double> LeakyDielectricSolver<D>::SurfaceCharge() const {
  std::vector<double> q(en_minus_.size());
  for (std::size_t k = 0; k < q.size(); ++k) {
    q[k] = eps_plus_ * en_plus_[k] - eps_minus_ * en_minus_[k];
  }
  return q;
}

template <int D>
std::vector<std::vector<double>> LeakyDielectricSolver<D>::GridField() const {
  return FieldGeometry<D>::GridField(iim_, phi_);
}

template class LeakyDielectricSolver<2>;
template class LeakyDielectricSolver<3>;

}  // namespace ehd
