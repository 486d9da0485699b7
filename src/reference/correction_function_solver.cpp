// Correction function method, song2019 sec. 2.3 (eqs. (7)-(18)); see the header for the scheme,
// the sign of the correction C_ij and how [f] is continued across the interface.
#include "ehd_capsule/reference/correction_function_solver.h"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "ehd_capsule/electric/box_face_check.h"
#include "ehd_capsule/reference/cfm_stencil_patch.h"

namespace ehd {
namespace {

constexpr int kDi[4] = {1, -1, 0, 0};
constexpr int kDj[4] = {0, 0, 1, -1};
// Half width of the block of grid points used to continue f across Sigma (5 x 5 block).
constexpr int kSourceFitRadius = 2;

// Shortest round-trip text of a double (std::to_string prints fixed 6 decimals).
std::string Text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

CfmLocalCauchy MakeCauchy(const CorrectionFunctionOptions& options) {
  return CfmLocalCauchy(options.basis, options.penalty);
}

}  // namespace

CorrectionFunctionSolver::CorrectionFunctionSolver(const Grid2D& grid, const PoissonBoundaries& bc,
                                                   const CorrectionFunctionOptions& options)
    : grid_(grid),
      bc_(bc),
      options_(options),
      poisson_(grid, bc),
      cauchy_(static_cast<std::size_t>(std::max(1, omp_get_max_threads())), MakeCauchy(options)) {
  if (options_.interface_subintervals == 0) {
    options_.interface_subintervals = options_.basis == CfmBasis::kBicubic ? 3 : 1;
  }
  const int max_sub = CfmLocalCauchy::kMaxInterfaceSamples / 4;
  if (options_.interface_subintervals < 1 || options_.interface_subintervals > max_sub) {
    throw std::invalid_argument("CorrectionFunctionSolver: interface_subintervals = " +
                                std::to_string(options.interface_subintervals) +
                                " must be in [1, " + std::to_string(max_sub) +
                                "] (or 0 for the default)");
  }
  if (!(options_.min_face_distance_h >= 0.0)) {
    throw std::invalid_argument("CorrectionFunctionSolver: min_face_distance_h = " +
                                Text(options_.min_face_distance_h) + " must be >= 0");
  }
  inside_.assign(grid.size(), 0);
  hint_.assign(grid.size(), 0.0);
  near_.assign(grid.size(), 0);
  rhs_.assign(grid.size(), 0.0);
  correction_.assign(grid.size(), 0.0);
  irregular_.reserve(8 * static_cast<std::size_t>(grid.nx + grid.ny));
  row_crossings_.resize(grid.ny);
  for (auto& row : row_crossings_) row.reserve(16);
}

void CorrectionFunctionSolver::ClassifyGrid(const ClosedCurve& curve) {
  const Grid2D& g = grid_;
  const Eigen::Matrix2Xd& markers = curve.markers();
  const int m = curve.size();
  // 1. Even-odd rule on the marker polygon, one scan line per grid row (half-open in y).
  for (auto& row : row_crossings_) row.clear();
  for (int k = 0; k < m; ++k) {
    const Eigen::Vector2d a = markers.col(k), b = markers.col((k + 1) % m);
    if (a.y() == b.y()) continue;
    const double y_lo = std::min(a.y(), b.y()), y_hi = std::max(a.y(), b.y());
    const int j_begin = std::max(0, static_cast<int>(std::ceil((y_lo - g.y0) / g.h - 0.5)));
    for (int j = j_begin; j < g.ny && g.y(j) < y_hi; ++j) {
      if (g.y(j) < y_lo) continue;
      const double t = (g.y(j) - a.y()) / (b.y() - a.y());
      row_crossings_[j].push_back(a.x() + t * (b.x() - a.x()));
    }
  }
  std::fill(inside_.begin(), inside_.end(), 0);
  std::fill(near_.begin(), near_.end(), 0);
  for (int j = 0; j < g.ny; ++j) {
    auto& row = row_crossings_[j];
    std::sort(row.begin(), row.end());
    for (std::size_t c = 0; c + 1 < row.size(); c += 2) {
      const int i_begin = std::max(0, static_cast<int>(std::ceil((row[c] - g.x0) / g.h - 0.5)));
      for (int i = i_begin; i < g.nx && g.x(i) < row[c + 1]; ++i) {
        if (g.x(i) > row[c]) inside_[g.index(i, j)] = 1;
      }
    }
  }
  // 2. Near Sigma the spline, not the polygon, decides (as ClosedCurve::Contains does): every
  //    grid point within h (plus a quarter chord for the spline's bulge) of a marker segment
  //    gets the side of its closest spline point, and that point's parameter as a hint.
  for (int k = 0; k < m; ++k) {
    const Eigen::Vector2d a = markers.col(k), b = markers.col((k + 1) % m);
    const double margin = g.h + 0.25 * (b - a).norm();
    const int i_lo = std::max(
        0, static_cast<int>(std::floor((std::min(a.x(), b.x()) - margin - g.x0) / g.h - 0.5)));
    const int i_hi =
        std::min(g.nx - 1,
                 static_cast<int>(std::ceil((std::max(a.x(), b.x()) + margin - g.x0) / g.h - 0.5)));
    const int j_lo = std::max(
        0, static_cast<int>(std::floor((std::min(a.y(), b.y()) - margin - g.y0) / g.h - 0.5)));
    const int j_hi =
        std::min(g.ny - 1,
                 static_cast<int>(std::ceil((std::max(a.y(), b.y()) + margin - g.y0) / g.h - 0.5)));
    const double s_segment =
        0.5 * (curve.knot(k) + (k + 1 < m ? curve.knot(k + 1) : curve.period()));
    for (int j = j_lo; j <= j_hi; ++j) {
      for (int i = i_lo; i <= i_hi; ++i) {
        const std::size_t idx = g.index(i, j);
        if (near_[idx]) continue;
        const Eigen::Vector2d p(g.x(i), g.y(j));
        const double s = CfmLocalClosestParameter(curve, p, s_segment);
        const CurvePoint c = curve.At(s);
        inside_[idx] = (p - c.position).dot(c.normal) < 0.0 ? 1 : 0;
        hint_[idx] = s;
        near_[idx] = 1;
      }
    }
  }
}

void CorrectionFunctionSolver::JumpOfSource(const std::vector<double>& f, int i, int j,
                                            double sigma, const Eigen::Vector2d* points,
                                            double* f_jump) const {
  const Grid2D& g = grid_;
  const Eigen::Vector2d origin(g.x(i), g.y(j));
  // Linear least-squares fit c0 + c1 (x - x_i)/h + c2 (y - y_j)/h of each side's f.
  Eigen::Matrix3d normal[2];
  Eigen::Vector3d moment[2];
  int count[2] = {0, 0};
  double sum[2] = {0.0, 0.0};
  for (int side = 0; side < 2; ++side) {
    normal[side].setZero();
    moment[side].setZero();
  }
  for (int jj = std::max(0, j - kSourceFitRadius); jj <= std::min(g.ny - 1, j + kSourceFitRadius);
       ++jj) {
    for (int ii = std::max(0, i - kSourceFitRadius); ii <= std::min(g.nx - 1, i + kSourceFitRadius);
         ++ii) {
      const std::size_t idx = g.index(ii, jj);
      const int side = inside_[idx] ? 0 : 1;  // 0: Omega^-, 1: Omega^+
      const Eigen::Vector3d basis(1.0, ii - i, jj - j);
      normal[side] += basis * basis.transpose();
      moment[side] += f[idx] * basis;
      sum[side] += f[idx];
      ++count[side];
    }
  }
  Eigen::Vector3d coefficients[2];
  for (int side = 0; side < 2; ++side) {
    coefficients[side].setZero();
    if (count[side] == 0) continue;
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(normal[side]);
    if (count[side] >= 3 && lu.rank() == 3) {
      coefficients[side] = lu.solve(moment[side]);
    } else {
      coefficients[side](0) = sum[side] / count[side];  // too few points: constant continuation
    }
  }
  for (int q = 0; q < CfmLocalCauchy::kAreaPoints; ++q) {
    const Eigen::Vector3d basis(1.0, (points[q].x() - origin.x()) / g.h,
                                (points[q].y() - origin.y()) / g.h);
    f_jump[q] = (coefficients[1].dot(basis) - coefficients[0].dot(basis)) / sigma;
  }
}

bool CorrectionFunctionSolver::CorrectStencil(const ClosedCurve& curve,
                                              const std::vector<double>& f, double sigma, int index,
                                              CfmLocalCauchy& cauchy) {
  const Grid2D& g = grid_;
  const int i = index % g.nx, j = index / g.nx;
  const char side = inside_[index];
  Eigen::Vector2d far[4];
  int n_far = 0;
  for (int k = 0; k < 4; ++k) {
    const int ii = i + kDi[k], jj = j + kDj[k];
    if (ii < 0 || ii >= g.nx || jj < 0 || jj >= g.ny) continue;
    if (inside_[g.index(ii, jj)] != side) far[n_far++] = {g.x(ii), g.y(jj)};
  }
  const Eigen::Vector2d center(g.x(i), g.y(j));
  const double s_hint = near_[index] ? hint_[index] : curve.ClosestParameter(center);
  CfmStencilPatch stencil_patch;
  if (!BuildCfmStencilPatch(curve, center, g.h, far, n_far, s_hint, &stencil_patch)) {
    return false;
  }
  CfmInterfaceSample samples[CfmLocalCauchy::kMaxInterfaceSamples];
  double parameters[CfmLocalCauchy::kMaxInterfaceSamples];
  const int n_samples = CfmInterfaceQuadrature(
      curve, stencil_patch, options_.interface_subintervals, samples, parameters);
  for (int q = 0; q < n_samples; ++q) {
    samples[q].jump_value = jump_value_.Value(parameters[q]);
    samples[q].jump_normal = jump_normal_.Value(parameters[q]);
  }
  const auto area_points = CfmLocalCauchy::AreaPoints(stencil_patch.patch);
  double f_jump[CfmLocalCauchy::kAreaPoints] = {};
  if (!f.empty()) JumpOfSource(f, i, j, sigma, area_points.data(), f_jump);
  if (!cauchy.Solve(stencil_patch.patch, f_jump, samples, n_samples)) return false;
  // s_k = +1 if x_ij in Omega^- (then phi(x_k) = phi^+ = phi^-_ext + D), else -1.
  const double sign = side ? 1.0 : -1.0;
  double c = 0.0;
  for (int k = 0; k < n_far; ++k) c += sign * cauchy.Value(far[k]);
  correction_[index] = c / (g.h * g.h);
  return true;
}

void CorrectionFunctionSolver::DeferredCorrection(std::vector<double>& phi) {
  // T from one-sided stencils only: an axis whose 5-wide arm crosses Sigma gets no term at that
  // cell (no jump passed), so T is O(h^2) short in a band of ~2 cells, an O(h^3) global effect.
  const Grid2D& g = grid_;
  sides_.resize(g.size());
  for (std::size_t idx = 0; idx < g.size(); ++idx) sides_[idx] = inside_[idx] ? -1 : 1;
  AddTruncationCorrection(g, bc_, phi, sides_.data(), nullptr, nullptr, rhs_);
  poisson_.Solve(rhs_, phi);
}

InterfaceSolveReport CorrectionFunctionSolver::Solve(const ClosedCurve& curve,
                                                     const InterfaceProblem& problem,
                                                     std::vector<double>& phi) {
  const auto start = std::chrono::steady_clock::now();
  const double sm = problem.sigma_minus, sp = problem.sigma_plus;
  if (!(sm > 0.0) || !(sp > 0.0) || std::abs(sm - sp) > 1e-12 * std::max(sm, sp)) {
    throw std::invalid_argument(
        "CorrectionFunctionSolver: needs equal conductivities > 0, got sigma_minus = " + Text(sm) +
        ", sigma_plus = " + Text(sp) +
        " (use the fast immersed interface method for sigma^- != sigma^+)");
  }
  const Grid2D& g = grid_;
  const int m = curve.size();
  CheckInsideBoxFaces(g, curve.markers(), options_.min_face_distance_h, "CorrectionFunctionSolver",
                      "marker");
  if (!problem.f.empty() && problem.f.size() != g.size()) {
    throw std::invalid_argument("CorrectionFunctionSolver: f has " +
                                std::to_string(problem.f.size()) + " values, grid has " +
                                std::to_string(g.size()) + " (or give none)");
  }
  for (const auto* jump : {&problem.w, &problem.v}) {
    if (!jump->empty() && static_cast<int>(jump->size()) != m) {
      throw std::invalid_argument(std::string("CorrectionFunctionSolver: ") +
                                  (jump == &problem.w ? "w" : "v") + " has " +
                                  std::to_string(jump->size()) + " values, curve has " +
                                  std::to_string(m) + " markers (or give none)");
    }
  }
  const double sigma = sm;

  ClassifyGrid(curve);
  scratch_w_.assign(m, 0.0);
  scratch_v_.assign(m, 0.0);
  if (!problem.w.empty()) std::copy(problem.w.begin(), problem.w.end(), scratch_w_.begin());
  for (int k = 0; k < m && !problem.v.empty(); ++k) scratch_v_[k] = problem.v[k] / sigma;
  jump_value_.Fit(curve.knots(), curve.period(), scratch_w_);
  jump_normal_.Fit(curve.knots(), curve.period(), scratch_v_);

  if (problem.f.empty()) {
    std::fill(rhs_.begin(), rhs_.end(), 0.0);
  } else {
    for (std::size_t idx = 0; idx < g.size(); ++idx) rhs_[idx] = problem.f[idx] / sigma;
  }
  AddDirichletGhostCorrection(g, bc_, problem.boundary, rhs_);
  AddBoundaryDataToRhs(g, bc_, problem.boundary, rhs_);
  std::fill(correction_.begin(), correction_.end(), 0.0);

  // Irregular stencils (some arm crosses Sigma), then one local Cauchy problem each.
  irregular_.clear();
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const char side = inside_[g.index(i, j)];
      for (int k = 0; k < 4; ++k) {
        const int ii = i + kDi[k], jj = j + kDj[k];
        if (ii < 0 || ii >= g.nx || jj < 0 || jj >= g.ny) continue;
        if (inside_[g.index(ii, jj)] != side) {
          irregular_.push_back(static_cast<int>(g.index(i, j)));
          break;
        }
      }
    }
  }
  irregular_points_ = static_cast<int>(irregular_.size());
  int failed = 0;
#pragma omp parallel num_threads(static_cast <int>(cauchy_.size())) reduction(+ : failed)
  {
    CfmLocalCauchy& cauchy = cauchy_[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 8)
    for (int t = 0; t < irregular_points_; ++t) {
      if (!CorrectStencil(curve, problem.f, sigma, irregular_[t], cauchy)) ++failed;
    }
  }
  failed_patches_ = failed;
  for (const int idx : irregular_) rhs_[idx] += correction_[idx];
  poisson_.Solve(rhs_, phi);
  if (options_.deferred_correction) DeferredCorrection(phi);

  InterfaceSolveReport report;
  report.iterations = 0;
  report.residual = 0.0;
  report.converged = failed_patches_ == 0;
  report.solve_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace ehd
