#include "ehd_capsule/electric/fast_iim_solver_3d.h"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "ehd_capsule/electric/box_face_check.h"
#include "ehd_capsule/electric/interface_guarantees.h"
#include "ehd_capsule/electric/interface_jumps_3d.h"
#include "ehd_capsule/geometry/radial_parametrisation.h"
#include "ehd_capsule/geometry/spherical_harmonics.h"

namespace ehd {
namespace {

constexpr const char* kSolverName = "3D immersed interface";

std::string VertexName(int v) { return "vertex " + std::to_string(v); }

constexpr double kPi = 3.14159265358979323846;

// Monomials of the fit in (xi, eta1, eta2) scaled by 1/h: quadratic first (10), then cubic (10).
void Monomials(double a, double b, double c, double* m) {
  const double v[20] = {1,         a,         b,         c,         a * a,     a * b,     a * c,
                        b * b,     b * c,     c * c,     a * a * a, a * a * b, a * a * c, a * b * b,
                        a * b * c, a * c * c, b * b * b, b * b * c, b * c * c, c * c * c};
  for (int i = 0; i < 20; ++i) m[i] = v[i];
}

// The rows gamma_k(q) = w_q m_q^T M^-1 e_k (k = 1, 2, 3: the c_xi, c_eta1, c_eta2 rows, times
// inv_h) of the weighted least-squares fit with the first kTerms monomials (M: its leading
// block of normal_matrix); rows[k] null: not wanted. False for fewer than 1.5 kTerms nodes or an
// ill-conditioned M (nothing written): M is symmetric positive definite, so it is factored by
// Cholesky, and its conditioning measured by the pivots d_i = L_ii^2, whose ratio min d / max d
// bounds the reciprocal condition number from above (every d_i lies in [lambda_min,
// lambda_max]) and falls to rounding level for a rank-deficient M; below 1e-12 it is refused.
template <int kTerms>
bool FitRows(const Eigen::Matrix<double, 20, 20>& normal_matrix,
             const Eigen::Map<const Eigen::Matrix<double, 20, Eigen::Dynamic>>& monomials,
             const std::vector<double>& weight, double inv_h, double* const rows[3]) {
  const int m = static_cast<int>(monomials.cols());
  if (m < kTerms + kTerms / 2) return false;
  const Eigen::LLT<Eigen::Matrix<double, kTerms, kTerms>> llt(
      normal_matrix.topLeftCorner<kTerms, kTerms>());
  if (llt.info() != Eigen::Success) return false;
  const auto pivots = llt.matrixLLT().diagonal().array().square();
  if (!(pivots.minCoeff() > 1e-12 * pivots.maxCoeff())) return false;
  const Eigen::Matrix<double, kTerms, 3> x =
      llt.solve(Eigen::Matrix<double, kTerms, kTerms>::Identity().template middleCols<3>(1));
  for (int k = 0; k < 3; ++k) {
    if (rows[k] == nullptr) continue;
    const Eigen::Matrix<double, kTerms, 1> xk = x.col(k) * inv_h;
    for (int q = 0; q < m; ++q) {
      rows[k][q] = weight[q] * monomials.col(q).template head<kTerms>().dot(xk);
    }
  }
  return true;
}
}  // namespace

FastIimSolver3D::FastIimSolver3D(const Grid3D& grid, const PoissonBoundaries3D& bc,
                                 const FastIim3DOptions& options)
    : poisson_(grid, bc), options_(options) {
  if (!(options.fit_radius_h >= 2.0 && options.fit_radius_h <= 6.0)) {
    throw std::invalid_argument("FastIimSolver3D: fit_radius_h = " +
                                std::to_string(options.fit_radius_h) + " outside [2, 6]");
  }
  if (options.fit_degree != 2 && options.fit_degree != 3) {
    throw std::invalid_argument(
        "FastIimSolver3D: fit_degree = " + std::to_string(options.fit_degree) + " (2 or 3)");
  }
}

FastIimSolver3D::~FastIimSolver3D() = default;

void FastIimSolver3D::CheckResolution(const TriangleMesh& surface) const {
  const double h = grid().h;
  for (int v = 0; v < surface.vertex_count(); ++v) {
    const double kappa = fit_->MaxCurvature(v);
    if (kappa * h > options_.max_curvature_h) {
      std::ostringstream os;
      os << "3D immersed interface: vertex " << v << " has curvature " << kappa
         << " (kappa h = " << kappa * h << " > max_curvature_h = " << options_.max_curvature_h
         << "): the surface is tighter there than the electric grid resolves; refine the grid";
      throw SolverError(os.str());
    }
  }
  const Eigen::Matrix3Xd& x = surface.vertices();
  CheckInsideBoxFaces(grid(), x, options_.min_face_distance_h, "3D immersed interface", "vertex");
  for (const auto& e : surface.edges()) {
    const double length = (x.col(e.a) - x.col(e.b)).norm();
    if (length > options_.max_edge_h * h) {
      std::ostringstream os;
      os << "3D immersed interface: mesh edge " << e.a << "-" << e.b << " is " << length / h
         << " h long (> max_edge_h = " << options_.max_edge_h
         << "): the jump data live on the vertices; refine the mesh";
      throw SolverError(os.str());
    }
  }
}

template <typename Visit>
void FastIimSolver3D::ForEachFitNode(const TriangleMesh& surface, int v, const Visit& visit) const {
  const Grid3D& g = grid();
  const double h = g.h, alpha = options_.fit_radius_h * h, alpha2 = alpha * alpha;
  const int reach = static_cast<int>(std::ceil(alpha / h)) + 1;
  const Eigen::Vector3d p = surface.vertices().col(v);
  const int ci = static_cast<int>(std::floor((p.x() - g.x0) / h));
  const int cj = static_cast<int>(std::floor((p.y() - g.y0) / h));
  const int ck = static_cast<int>(std::floor((p.z() - g.z0) / h));
  for (int k = std::max(0, ck - reach); k <= std::min(g.nz - 1, ck + reach); ++k) {
    const double dz = g.z(k) - p.z();
    for (int j = std::max(0, cj - reach); j <= std::min(g.ny - 1, cj + reach); ++j) {
      const double dy = g.y(j) - p.y(), dyz2 = dy * dy + dz * dz;
      if (dyz2 >= alpha2) continue;
      for (int i = std::max(0, ci - reach); i <= std::min(g.nx - 1, ci + reach); ++i) {
        const double dx = g.x(i) - p.x(), r2 = dx * dx + dyz2;
        if (r2 < alpha2) visit(g.index(i, j, k), Eigen::Vector3d(dx, dy, dz), r2);
      }
    }
  }
}

void FastIimSolver3D::SetUpBand(const TriangleMesh& surface) {
  const Grid3D& g = grid();
  slot_.assign(g.size(), -1);
  band_node_.clear();
  crossings_.clear();
  const auto add = [&](std::size_t node) {
    if (slot_[node] < 0) {
      slot_[node] = static_cast<int>(band_node_.size());
      band_node_.push_back(node);
    }
    return slot_[node];
  };
  const int n[3] = {g.nx, g.ny, g.nz};
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t c = g.index(i, j, k);
        if (!sides_.irregular[c]) continue;
        for (int axis = 0; axis < 3; ++axis) {
          for (int s = -1; s <= 1; s += 2) {
            int q[3] = {i, j, k};
            q[axis] += s;
            if (q[axis] < 0 || q[axis] >= n[axis]) continue;
            const std::size_t o = g.index(q[0], q[1], q[2]);
            if (sides_.side[o] == sides_.side[c]) continue;
            crossings_.push_back({c, add(o), sides_.side[o] > 0 ? 1.0 : -1.0});
          }
        }
      }
    }
  }
  // Outside nodes within the fit radius of a vertex (the nodes of SetUpFits).
  for (int v = 0; v < surface.vertex_count(); ++v) {
    ForEachFitNode(surface, v, [&](std::size_t c, const Eigen::Vector3d&, double) {
      if (sides_.side[c] >= 0) add(c);
    });
  }
  // Foot points and the rows of J (interface_jumps_3d.h).
  const std::size_t nb = band_node_.size();
  band_vertex_.resize(nb);
  band_offset_.assign(1, 0);
  band_support_.clear();
  band_w_row_.clear();
  band_g_row_.clear();
  band_f_coefficient_.resize(nb);
  band_f_dxi_coefficient_.resize(nb);
  // The stencils are independent (threaded); the rows are then laid out in band order, so the
  // result does not depend on the thread count.
  std::vector<JumpStencil3D> stencils(nb);
  const int threads = options_.threads > 0 ? options_.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads) if (threads != 1)
  for (long b = 0; b < static_cast<long>(nb); ++b) {
    const std::size_t node = band_node_[b];
    const int i = static_cast<int>(node % g.nx);
    const int j = static_cast<int>((node / g.nx) % g.ny);
    const int k = static_cast<int>(node / (static_cast<std::size_t>(g.nx) * g.ny));
    stencils[b] = MakeJumpStencil(*fit_, Eigen::Vector3d(g.x(i), g.y(j), g.z(k)));
  }
  for (std::size_t b = 0; b < nb; ++b) {
    const JumpStencil3D& stencil = stencils[b];
    band_vertex_[b] = stencil.vertex;
    band_f_coefficient_[b] = stencil.f_coefficient;
    band_f_dxi_coefficient_[b] = stencil.f_dxi_coefficient;
    const std::vector<int>& support = fit_->patch(stencil.vertex).support;
    for (std::size_t q = 0; q < support.size(); ++q) {
      band_support_.push_back(support[q]);
      band_w_row_.push_back(stencil.w_row[q]);
      band_g_row_.push_back(stencil.g_row[q]);
    }
    band_offset_.push_back(static_cast<int>(band_support_.size()));
  }
}

void FastIimSolver3D::SetUpFits(const TriangleMesh& surface) {
  const Grid3D& g = grid();
  const double h = g.h, alpha = options_.fit_radius_h * h;
  const int nv = surface.vertex_count();
  fit_normal_.resize(3, nv);
  fit_t1_.resize(3, nv);
  fit_t2_.resize(3, nv);
  // The rows are laid out in vertex order: count first, then each vertex fills its own range
  // (threaded, independent; the result does not depend on the thread count).
  fit_offset_.assign(nv + 1, 0);
  for (int v = 0; v < nv; ++v) {
    int m = 0;
    ForEachFitNode(surface, v, [&](std::size_t, const Eigen::Vector3d&, double) { ++m; });
    fit_offset_[v + 1] = fit_offset_[v] + m;
  }
  const std::size_t total = static_cast<std::size_t>(fit_offset_[nv]);
  fit_node_.resize(total);
  fit_slot_.resize(total);
  fit_gamma_.resize(total);
  fit_gamma_t1_.resize(total);
  fit_gamma_t2_.resize(total);
  fit_gamma_check_.resize(total);
  std::vector<int> failed(nv, 0);
  const int threads = options_.threads > 0 ? options_.threads : omp_get_max_threads();
#pragma omp parallel num_threads(threads) if (threads != 1)
  {
    // Per thread: the monomials (node-major, 20 a node) and weights of one vertex's nodes.
    std::vector<double> mono, weight;
#pragma omp for schedule(dynamic, 16)
    for (int v = 0; v < nv; ++v) {
      const SurfacePatch& patch = fit_->patch(v);
      const Eigen::Vector3d normal = (patch.t1 + patch.height[0] * patch.n)
                                         .cross(patch.t2 + patch.height[1] * patch.n)
                                         .normalized();
      const Eigen::Vector3d t1 = (patch.t1 - patch.t1.dot(normal) * normal).normalized();
      const Eigen::Vector3d t2 = normal.cross(t1);
      fit_normal_.col(v) = normal;
      fit_t1_.col(v) = t1;
      fit_t2_.col(v) = t2;
      const int offset = fit_offset_[v];
      const int m = fit_offset_[v + 1] - offset;
      mono.resize(20 * static_cast<std::size_t>(m));
      weight.resize(m);
      int q = 0;
      ForEachFitNode(surface, v, [&](std::size_t node, const Eigen::Vector3d& r, double r2) {
        fit_node_[offset + q] = node;
        fit_slot_[offset + q] = sides_.side[node] > 0 ? slot_[node] : -1;
        Monomials(r.dot(normal) / h, r.dot(t1) / h, r.dot(t2) / h, &mono[20 * q]);
        weight[q] = 0.5 * (1.0 + std::cos(kPi * std::sqrt(r2) / alpha));  // eq. (67)
        ++q;
      });
      // Weighted least squares by the normal equations M c = A^T W y, M = A^T W A (coordinates
      // in units of h; the quadratic's M is the cubic's leading 10 x 10 block): only the rows of
      // M^-1 A^T W for c_xi, c_eta1, c_eta2 are needed, gamma_k(q) = w_q m_q^T M^-1 e_k. A cubic
      // whose M is ill-conditioned (FitRows) drops to the quadratic.
      Eigen::Matrix<double, 20, 20> normal_matrix = Eigen::Matrix<double, 20, 20>::Zero();
      for (int n = 0; n < m; ++n) {
        const Eigen::Map<const Eigen::Matrix<double, 20, 1>> row(&mono[20 * n]);
        normal_matrix.noalias() += (weight[n] * row) * row.transpose();
      }
      const Eigen::Map<const Eigen::Matrix<double, 20, Eigen::Dynamic>> monomials(mono.data(), 20,
                                                                                  m);
      double* const rows[3] = {&fit_gamma_[offset], &fit_gamma_t1_[offset], &fit_gamma_t2_[offset]};
      double* check = &fit_gamma_check_[offset];
      const bool cubic =
          options_.fit_degree == 3 && FitRows<20>(normal_matrix, monomials, weight, 1.0 / h, rows);
      // The one-degree-lower fit, for the resolution check after the solve (the cubic and the
      // quadratic agree to O(h^2) where the field is resolved near the surface); without the
      // cubic, the quadratic is the fit and its own check.
      double* const check_only[3] = {check, nullptr, nullptr};
      const bool quadratic =
          FitRows<10>(normal_matrix, monomials, weight, 1.0 / h, cubic ? check_only : rows);
      if (!cubic && !quadratic) {
        failed[v] = 1;
      } else if (!cubic || !quadratic) {
        std::copy(rows[0], rows[0] + m, check);
      }
    }
  }
  for (int v = 0; v < nv; ++v) {
    if (failed[v]) {  // the lowest such vertex
      throw SolverError("3D immersed interface: the normal-derivative fit at vertex " +
                        std::to_string(v) + " has " +
                        std::to_string(fit_offset_[v + 1] - fit_offset_[v]) +
                        " nodes within fit_radius_h (a quadratic needs 15 in general position); "
                        "the surface is too close to the box or the grid too coarse");
    }
  }
}

void FastIimSolver3D::CheckFitAgreement(const std::vector<double>& phi,
                                        const std::vector<double>& g) {
  const int nv = static_cast<int>(fit_offset_.size()) - 1;
  dn_check_.resize(nv);
  for (int v = 0; v < nv; ++v) {
    double check = 0;
    for (int q = fit_offset_[v]; q < fit_offset_[v + 1]; ++q) {
      check += fit_gamma_check_[q] *
               (phi[fit_node_[q]] - (fit_slot_[q] >= 0 ? band_jump_[fit_slot_[q]] : 0.0));
    }
    dn_check_[v] = check;
  }
  fit_disagreement_ = ehd::CheckFitAgreement(kSolverName, dn_minus_, dn_check_, g,
                                             options_.max_fit_disagreement, VertexName);
}

void FastIimSolver3D::CheckPointOscillation(const TriangleMesh& surface,
                                            const std::vector<double>& g) {
  // The vertex-scale content of G: L(L G) / 4 with (L G)_v = mean over v's edge neighbours of G
  // minus G_v (the random-walk graph Laplacian, eigenvalues in [-2, 0]). On a chain of markers
  // it is the 2D check's fourth difference / 16 (L is half the second difference there); a
  // spike of size s gives 3 s / 8 there and 7 s / 24 at a vertex of valence 6. The threshold is
  // the 2D one: resolved cases measure <= 0.03 (docs/electric_solver_3d.md).
  const int nv = surface.vertex_count();
  laplacian_.assign(nv, 0.0);
  point_content_.assign(nv, 0.0);
  const auto apply = [&](const std::vector<double>& in, std::vector<double>& out) {
    for (int v = 0; v < nv; ++v) {
      const std::vector<int>& edges = surface.vertex_edges(v);
      double sum = 0;
      for (int e : edges) {
        const TriangleMesh::Edge& edge = surface.edges()[e];
        sum += in[edge.a == v ? edge.b : edge.a];
      }
      out[v] = sum / static_cast<double>(edges.size()) - in[v];
    }
  };
  apply(g, laplacian_);
  apply(laplacian_, point_content_);
  double scale = 0;
  for (int v = 0; v < nv; ++v) {
    point_content_[v] = std::abs(point_content_[v]) / 4.0;
    scale =
        std::max({scale, std::abs(g[v]), std::abs(dn_minus_[v]), std::abs(dn_minus_[v] + g[v])});
  }
  point_oscillation_ =
      ehd::CheckPointOscillation(kSolverName, "vertex", point_content_, scale,
                                 options_.max_marker_oscillation, VertexName, [&](int v) {
                                   std::ostringstream os;
                                   os << " (at (" << surface.vertices().col(v).transpose() << "))";
                                   return os.str();
                                 });
}

void FastIimSolver3D::BandJump(const double* g, bool with_data) {
  const std::size_t nb = band_node_.size();
  band_jump_.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    double j = with_data ? band_data_[b] : 0.0;
    for (int q = band_offset_[b]; q < band_offset_[b + 1]; ++q) {
      j += band_g_row_[q] * g[band_support_[q]];
    }
    band_jump_[b] = j;
  }
}

void FastIimSolver3D::EvaluateNormalDerivative(const std::vector<double>& phi,
                                               const std::vector<double>& g,
                                               std::vector<double>& dn_minus) {
  const int nv = static_cast<int>(fit_offset_.size()) - 1;
  if (nv <= 0 || phi.size() != grid().size() || static_cast<int>(g.size()) != nv) {
    throw std::invalid_argument(
        "EvaluateNormalDerivative: call after Solve() with phi of the "
        "grid's size and one g per vertex");
  }
  BandJump(g.data(), true);
  dn_minus.resize(nv);
  for (int v = 0; v < nv; ++v) {
    double s = 0;
    for (int q = fit_offset_[v]; q < fit_offset_[v + 1]; ++q) {
      s += fit_gamma_[q] *
           (phi[fit_node_[q]] - (fit_slot_[q] >= 0 ? band_jump_[fit_slot_[q]] : 0.0));
    }
    dn_minus[v] = s;
  }
}

void FastIimSolver3D::PotentialAndNormalDerivative(const double* g, bool with_data,
                                                   std::vector<double>& phi,
                                                   std::vector<double>& dn) {
  BandJump(g, with_data);
  if (with_data) {
    rhs_ = rhs_base_;
  } else {
    rhs_.assign(grid().size(), 0.0);
  }
  const double inv_h2 = 1.0 / (grid().h * grid().h);
  for (const Crossing& c : crossings_) rhs_[c.node] += c.sign * band_jump_[c.slot] * inv_h2;
  poisson_.Solve(rhs_, phi);
  ++poisson_solves_;
  const int nv = static_cast<int>(fit_offset_.size()) - 1;
  dn.resize(nv);
  for (int v = 0; v < nv; ++v) {
    double s = 0;
    for (int q = fit_offset_[v]; q < fit_offset_[v + 1]; ++q) {
      const double value = phi[fit_node_[q]] - (fit_slot_[q] >= 0 ? band_jump_[fit_slot_[q]] : 0.0);
      s += fit_gamma_[q] * value;
    }
    dn[v] = s;
  }
}

int FastIimSolver3D::CachedIcosphereLevel(const TriangleMesh& surface) {
  // The same mesh as last time (a capsule's connectivity never changes): no new icosphere.
  const int last = static_cast<int>(icosphere_triangles_.size()) - 1;
  if (last >= 0 && surface.vertex_count() == 10 * (1 << (2 * last)) + 2 &&
      surface.triangles() == icosphere_triangles_[last]) {
    return last;
  }
  const int level = IcosphereLevel(surface);
  icosphere_triangles_.clear();
  for (int j = 0; j <= level; ++j) icosphere_triangles_.push_back(IcosphereMesh(j).triangles());
  return level;
}

void FastIimSolver3D::SetUpHarmonicBasis(const TriangleMesh& surface, int level, int degree) {
  if (level >= 0) {
    // Icosphere connectivity: the unit icosphere's vertices and third areas (cached by level).
    if (level == basis_level_ && degree == basis_degree_) return;
    const TriangleMesh sphere = IcosphereMesh(level, 1.0);
    basis_ = RealSphericalHarmonics(sphere.vertices(), degree);
    const std::vector<double> area = VertexThirdAreas(sphere);
    basis_sphere_area_ = Eigen::Map<const Eigen::VectorXd>(area.data(), sphere.vertex_count());
    basis_level_ = level;
    basis_degree_ = degree;
    return;
  }
  // The radial parametrisation: the directions move with the surface, so the basis is rebuilt
  // unless nothing changed.
  if (basis_level_ < 0 && degree == basis_degree_ &&
      surface.vertices().cols() == basis_positions_.cols() &&
      surface.vertices() == basis_positions_) {
    return;
  }
  basis_ = RealSphericalHarmonics(radial_.direction, degree);
  basis_sphere_area_ = radial_.solid_angle;
  basis_positions_ = surface.vertices();
  basis_level_ = -1;
  basis_degree_ = degree;
}

namespace {

// Vertex weights for surface integrals on a mesh of icosphere connectivity: the third areas of
// its submeshes at `level` and below, Richardson-extrapolated `steps` times (the error of the
// third-area rule on these nested meshes is an even series in the edge length, measured: each
// step gains a factor 16, then 64, per level), on the first 10 * 4^level + 2 vertices of `mesh`.
// steps <= level.
// triangles[j]: IcosphereMesh(j)'s triangle list (the solver's cache).
Eigen::VectorXd ExtrapolatedVertexWeights(
    const Eigen::Matrix3Xd& x, const std::vector<std::vector<TriangleMesh::Triangle>>& triangles,
    int level, int steps) {
  if (steps == 0) {
    const int count = 10 * (1 << (2 * level)) + 2;
    const std::vector<double> a = VertexThirdAreas(x, triangles[level], count);
    return Eigen::Map<const Eigen::VectorXd>(a.data(), count);
  }
  // R_s(level) = (4^s R_{s-1}(level) - R_{s-1}(level - 1)) / (4^s - 1).
  Eigen::VectorXd q = ExtrapolatedVertexWeights(x, triangles, level, steps - 1);
  const Eigen::VectorXd below = ExtrapolatedVertexWeights(x, triangles, level - 1, steps - 1);
  const double factor = std::pow(4.0, steps);
  q *= factor;
  q.head(below.size()) -= below;
  return q / (factor - 1.0);
}

}  // namespace

GmresResult FastIimSolver3D::SolveInHarmonicBasis(const TriangleMesh& surface,
                                                  const InterfaceProblem3D& problem, int level,
                                                  std::vector<double>& g) {
  const int nv = surface.vertex_count();
  const double jump = sigma_plus_ - sigma_minus_;
  const double scale = sigma_plus_ / jump;
  const bool with_source = !problem.f.empty();
  if (with_source && !std::isfinite(problem.interior_source_integral)) {
    throw std::invalid_argument(
        "FastIimSolver3D: f is given at sigma^-/sigma^+ above basis_min_ratio without "
        "interior_source_integral (the integral of f^-/sigma^- over the inside, which the flux "
        "balance needs)");
  }
  // The flux balance: mu = (mean(v)/[sigma] - flux/area) / scale.
  const auto flux_mean = [&](const Eigen::VectorXd& q, double* area_out) {
    double area = 0, integral_v = 0;
    for (int i = 0; i < q.size(); ++i) {
      area += q(i);
      integral_v += q(i) * v_[i];
    }
    if (area_out) *area_out = area;
    const double flux = with_source ? problem.interior_source_integral : 0.0;
    return (integral_v / jump - flux) / area / scale;
  };
  const std::vector<double> third = VertexThirdAreas(surface);
  Eigen::VectorXd q;
  double area = 0, mu = 0, mu_error = 0;
  if (level >= 0) {
    // Icosphere connectivity: the vertex weights extrapolated twice (levels L, L - 1, L - 2); the
    // same from the level below estimates its error (divided by 63: the rule's error falls 64x
    // per level, measured on the sphere, ellipsoid and red cell).
    const Eigen::Matrix3Xd& position = surface.vertices();
    q = ExtrapolatedVertexWeights(position, icosphere_triangles_, level, 2);
    mu = flux_mean(q, &area);
    mu_error = level >= 3
                   ? std::abs(mu - flux_mean(ExtrapolatedVertexWeights(
                                                 position, icosphere_triangles_, level - 1, 2),
                                             nullptr)) /
                         63.0
                   : std::abs(mu - flux_mean(ExtrapolatedVertexWeights(
                                                 position, icosphere_triangles_, level, 1),
                                             nullptr));
  } else {
    // Any other mesh: without data (v = 0, no source: the leaky dielectric) mu = 0 for any
    // weights, and the vertex third areas serve. With data the weights are those of the radial
    // parametrisation, exact for the harmonics of degree <= kQuadratureDegree
    // (geometry/radial_parametrisation.h); the same at 4 degrees fewer estimates the error.
    const bool with_data =
        with_source || std::any_of(v_.begin(), v_.end(), [](double x) { return x != 0.0; });
    q = Eigen::Map<const Eigen::VectorXd>(third.data(), nv);
    if (with_data) {
      constexpr int kQuadratureDegree = 24;
      int quadrature_degree = kQuadratureDegree;
      while (quadrature_degree > 4 && SphericalHarmonicCount(quadrature_degree) * 4 > nv) {
        --quadrature_degree;
      }
      q = RadialSurfaceWeights(radial_, quadrature_degree);
      mu_error = std::abs(flux_mean(q, nullptr) -
                          flux_mean(RadialSurfaceWeights(radial_, quadrature_degree - 4), nullptr));
    }
    mu = flux_mean(q, &area);
  }
  const Eigen::VectorXd mean_weight = q / area;
  // Degree: shortest wavelength 2 pi R / L >= basis_wavelength_h h, R of the same area, and
  // at least four vertices per basis function.
  const double radius = std::sqrt(area / (4.0 * 3.14159265358979323846));
  int degree = static_cast<int>(
      std::floor(2.0 * 3.14159265358979323846 * radius / (options_.basis_wavelength_h * grid().h)));
  degree = std::min(degree, options_.max_harmonic_degree);
  while (degree > 1 && SphericalHarmonicCount(degree) * 4 > nv) --degree;
  if (degree < 2) {
    std::ostringstream os;
    os << "3D immersed interface: sigma^-/sigma^+ = " << sigma_minus_ / sigma_plus_
       << " needs [phi_n] in a harmonic basis of degree >= 2, but the surface (radius " << radius
       << " = " << radius / grid().h << " h, " << nv << " vertices) allows only degree " << degree
       << "; refine the grid or the mesh";
    throw SolverError(os.str());
  }
  SetUpHarmonicBasis(surface, level, degree);
  harmonic_degree_ = degree;
  Eigen::VectorXd test_weight(nv);
  for (int i = 0; i < nv; ++i) test_weight(i) = third[i] / area;
  GalerkinUnknowns harmonics;
  harmonics.Set(basis_, test_weight, basis_sphere_area_);
  // R(G) = dn^-(G) + scale G - v/[sigma], tested with Y, the mean deflated to mu.
  MeanDeflation deflation;
  deflation.active = true;
  deflation.target = mu;
  deflation.mean = [&](const double* gv) {
    return mean_weight.dot(Eigen::Map<const Eigen::VectorXd>(gv, mean_weight.size()));
  };
  const GmresResult result = schur_.Solve(harmonics, nv, SchurResidual(), deflation, options_.gmres,
                                          options_.warm_start_refresh, g);
  const Eigen::Map<const Eigen::VectorXd> gvec(g.data(), nv);
  const double gmax = std::max(gvec.cwiseAbs().maxCoeff(), 1e-300);
  flux_balance_error_ = mu_error / gmax;
  if (result.converged && flux_balance_error_ > options_.max_flux_balance_error) {
    std::ostringstream os;
    os << "3D immersed interface: at sigma^-/sigma^+ = " << sigma_minus_ / sigma_plus_
       << " the mean of [phi_n] from the flux balance is uncertain by " << flux_balance_error_
       << " of max |[phi_n]| (> max_flux_balance_error = " << options_.max_flux_balance_error
       << "): the surface quadrature of [sigma phi_n] (and of f) is amplified by the ratio; "
          "refine the mesh";
    throw SolverError(os.str());
  }
  return result;
}

void FastIimSolver3D::CheckThinParts(const TriangleMesh& surface) const {
  const MultipleCrossing thin = FindMultipleCrossing(grid(), surface);
  if (thin.found) ThrowThinPart(kSolverName, "surface", thin, grid().h);
}

void FastIimSolver3D::SetUpData(const TriangleMesh& surface, const InterfaceProblem3D& problem) {
  const Grid3D& grid3 = grid();
  const int nv = surface.vertex_count();
  w_ = problem.w.empty() ? std::vector<double>(nv, 0.0) : problem.w;
  v_ = problem.v.empty() ? std::vector<double>(nv, 0.0) : problem.v;
  // Data part of J: the w rows and the [f/sigma] terms.
  const std::size_t nb = band_node_.size();
  band_data_.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    double j = 0;
    for (int q = band_offset_[b]; q < band_offset_[b + 1]; ++q) {
      j += band_w_row_[q] * w_[band_support_[q]];
    }
    const int vertex = band_vertex_[b];
    if (!problem.f_over_sigma_jump.empty()) {
      j += band_f_coefficient_[b] * problem.f_over_sigma_jump[vertex];
    }
    if (!problem.f_over_sigma_dxi_jump.empty()) {
      j += band_f_dxi_coefficient_[b] * problem.f_over_sigma_dxi_jump[vertex];
    }
    band_data_[b] = j;
  }
  rhs_base_.assign(grid3.size(), 0.0);
  if (!problem.f.empty()) {
    for (std::size_t c = 0; c < grid3.size(); ++c) {
      rhs_base_[c] = problem.f[c] / (sides_.side[c] > 0 ? sigma_plus_ : sigma_minus_);
    }
  }
  AddBoundaryDataToRhs(grid3, poisson_.boundaries(), problem.boundary, rhs_base_);
}

InterfaceSchurSolver::PointResidual FastIimSolver3D::SchurResidual() {
  const double jump = sigma_plus_ - sigma_minus_;
  const double scale = sigma_plus_ / jump;
  return [this, jump, scale](const double* g, bool with_data, double* r) {
    PotentialAndNormalDerivative(g, with_data, phi_work_, dn_work_);
    const int nv = static_cast<int>(dn_work_.size());
    for (int v = 0; v < nv; ++v) r[v] = dn_work_[v] + scale * g[v];
    if (with_data) {
      for (int v = 0; v < nv; ++v) r[v] -= v_[v] / jump;
    }
  };
}

GmresResult FastIimSolver3D::SolveAtVertices(int nv, std::vector<double>& g) {
  return schur_.Solve(PointUnknowns(nv), nv, SchurResidual(), MeanDeflation(), options_.gmres,
                      options_.warm_start_refresh, g);
}

void FastIimSolver3D::TangentialGradients(const std::vector<double>& phi) {
  const int nv = static_cast<int>(fit_normal_.cols());
  // Tangential gradients: phi^- from the fit's eta rows, phi^+ = phi^- + grad_s w (the patch fit
  // of w, projected on the fit's tangent plane).
  tangent_minus_.resize(3, nv);
  tangent_plus_.resize(3, nv);
  for (int v = 0; v < nv; ++v) {
    double d1 = 0, d2 = 0;
    for (int q = fit_offset_[v]; q < fit_offset_[v + 1]; ++q) {
      const double value = phi[fit_node_[q]] - (fit_slot_[q] >= 0 ? band_jump_[fit_slot_[q]] : 0.0);
      d1 += fit_gamma_t1_[q] * value;
      d2 += fit_gamma_t2_[q] * value;
    }
    tangent_minus_.col(v) = d1 * fit_t1_.col(v) + d2 * fit_t2_.col(v);
    const auto a = fit_->FitFunction(v, w_);
    const SurfacePatch& patch = fit_->patch(v);
    Eigen::Vector3d grad_w = a[1] * patch.t1 + a[2] * patch.t2;
    grad_w -= grad_w.dot(fit_normal_.col(v)) * fit_normal_.col(v);
    tangent_plus_.col(v) = tangent_minus_.col(v) + grad_w;
  }
}

InterfaceSolveReport FastIimSolver3D::Solve(const TriangleMesh& surface,
                                            const InterfaceProblem3D& problem,
                                            std::vector<double>& g, std::vector<double>& phi) {
  const auto start = std::chrono::steady_clock::now();
  const Grid3D& grid3 = grid();
  const int nv = surface.vertex_count();
  if (!(problem.sigma_minus > 0) || !(problem.sigma_plus > 0)) {
    throw std::invalid_argument("FastIimSolver3D: sigma_minus and sigma_plus must be > 0");
  }
  const auto check = [&](const std::vector<double>& data, std::size_t n, const char* name) {
    if (!data.empty() && data.size() != n) {
      throw std::invalid_argument(std::string("FastIimSolver3D: ") + name + " has " +
                                  std::to_string(data.size()) + " values, " + std::to_string(n) +
                                  " expected");
    }
  };
  check(problem.f, grid3.size(), "f");
  check(problem.w, nv, "w");
  check(problem.v, nv, "v");
  check(problem.f_over_sigma_jump, nv, "f_over_sigma_jump");
  check(problem.f_over_sigma_dxi_jump, nv, "f_over_sigma_dxi_jump");
  if (!problem.f.empty() && problem.f_over_sigma_jump.empty()) {
    throw std::invalid_argument(
        "FastIimSolver3D: f is given without f_over_sigma_jump ([f/sigma] "
        "at the vertices)");
  }
  sigma_minus_ = problem.sigma_minus;
  sigma_plus_ = problem.sigma_plus;
  const double inner_ratio = sigma_minus_ / sigma_plus_;
  CheckInnerRatio(kSolverName, sigma_minus_, sigma_plus_, options_.max_inner_ratio);
  const bool harmonic = inner_ratio > options_.basis_min_ratio;
  // A mesh of icosphere connectivity (every surface of the package) keeps the icosphere
  // parametrisation; any other mesh takes the radial one, which needs a star-shaped surface.
  const int level = harmonic ? CachedIcosphereLevel(surface) : -1;
  if (harmonic && level >= 0 && level < 2) {
    std::ostringstream os;
    os << "3D immersed interface: sigma^-/sigma^+ = " << inner_ratio
       << " > basis_min_ratio = " << options_.basis_min_ratio
       << " needs a mesh of icosphere connectivity at subdivision level >= 2 (or another "
          "triangulation) for the harmonic basis of [phi_n]; this one is coarser";
    throw SolverError(os.str());
  }
  if (harmonic && level < 0) {
    radial_ = MakeRadialParametrisation(surface);
    if (!radial_.star_shaped()) {
      const auto& t = surface.triangles()[radial_.folded_triangle];
      std::ostringstream os;
      os << "3D immersed interface: sigma^-/sigma^+ = " << inner_ratio
         << " > basis_min_ratio = " << options_.basis_min_ratio
         << " needs a mesh of icosphere connectivity or a surface star-shaped about its "
            "centroid ("
         << radial_.center.transpose()
         << ") for the harmonic basis of [phi_n] in the directions from it, but triangle "
         << radial_.folded_triangle << " (vertices " << t[0] << ", " << t[1] << ", " << t[2]
         << ") is seen edge-on or from behind from there: the surface is not star-shaped";
      throw SolverError(os.str());
    }
  }
  harmonic_degree_ = 0;
  flux_balance_error_ = 0;
  poisson_solves_ = 0;
  fit_ = std::make_unique<LocalSurfaceFit>(surface, 2.0 * grid3.h, 2, 3, options_.threads);
  CheckResolution(surface);
  sides_ = ClassifyNodes(grid3, surface);
  CheckThinParts(surface);
  SetUpBand(surface);
  SetUpFits(surface);

  SetUpData(surface, problem);

  InterfaceSolveReport report;
  const double jump = sigma_plus_ - sigma_minus_;
  if (static_cast<int>(g.size()) != nv) g.assign(nv, 0.0);
  if (jump == 0.0) {
    for (int v = 0; v < nv; ++v) g[v] = v_[v] / sigma_plus_;
    report.converged = true;
  } else {
    GmresResult r;
    if (harmonic) {
      r = SolveInHarmonicBasis(surface, problem, level, g);
    } else {
      r = SolveAtVertices(nv, g);
    }
    report.iterations = r.iterations;
    report.residual = r.residual;
    report.converged = r.converged;
    if (!r.converged) {
      std::ostringstream os;
      os << "3D immersed interface: GMRES did not converge (" << r.iterations
         << " iterations, residual " << r.residual << " against " << r.reference
         << "); raise gmres.max_iterations or check the surface";
      throw SolverError(os.str());
    }
  }
  PotentialAndNormalDerivative(g.data(), true, phi, dn_minus_);
  point_oscillation_ = 0;
  if (jump != 0.0) CheckPointOscillation(surface, g);
  CheckFitAgreement(phi, g);
  dn_plus_.resize(nv);
  for (int v = 0; v < nv; ++v) dn_plus_[v] = dn_minus_[v] + g[v];
  TangentialGradients(phi);
  last_phi_side_jump_ = band_jump_;
  report.solve_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return report;
}

void FastIimSolver3D::GridField(const std::vector<double>& phi, std::vector<double>& ex,
                                std::vector<double>& ey, std::vector<double>& ez) const {
  const Grid3D& g = grid();
  if (phi.size() != g.size() || sides_.side.size() != g.size()) {
    throw std::invalid_argument("FastIimSolver3D::GridField: phi has " +
                                std::to_string(phi.size()) + " values for a grid of " +
                                std::to_string(g.size()) + " (call after Solve)");
  }
  std::vector<double>* out[3] = {&ex, &ey, &ez};
  for (auto* o : out) o->resize(g.size());
  const int n[3] = {g.nx, g.ny, g.nz};
  const double h = g.h;
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t c = g.index(i, j, k);
        const int sc = sides_.side[c];
        for (int axis = 0; axis < 3; ++axis) {
          // Neighbours at -2, -1, +1, +2 along the axis (-1: outside the box).
          long nb[4] = {-1, -1, -1, -1};
          const int offsets[4] = {-2, -1, 1, 2};
          for (int s = 0; s < 4; ++s) {
            int q[3] = {i, j, k};
            q[axis] += offsets[s];
            if (q[axis] >= 0 && q[axis] < n[axis]) {
              nb[s] = static_cast<long>(g.index(q[0], q[1], q[2]));
            }
          }
          // Value at a node seen from c's side: phi, or phi -/+ J across the surface (J is known
          // at every neighbour across of an irregular node; a +-2 node across, where it is not,
          // falls back to the one-sided first-order difference).
          bool known = true;
          const auto extended = [&](long o) {
            if (sides_.side[o] == sc) return phi[o];
            const int slot = slot_[o];
            if (slot < 0) {
              known = false;
              return 0.0;
            }
            return phi[o] - sides_.side[o] * last_phi_side_jump_[slot];
          };
          double derivative = 0;
          if (nb[1] >= 0 && nb[2] >= 0) {
            derivative = (extended(nb[2]) - extended(nb[1])) / (2 * h);
          } else if (nb[2] >= 0) {  // low face: second-order one-sided
            derivative = (-3 * phi[c] + 4 * extended(nb[2]) - extended(nb[3])) / (2 * h);
            if (!known) derivative = (extended(nb[2]) - phi[c]) / h;
          } else if (nb[1] >= 0) {
            derivative = (3 * phi[c] - 4 * extended(nb[1]) + extended(nb[0])) / (2 * h);
            if (!known) derivative = (phi[c] - extended(nb[1])) / h;
          }
          (*out[axis])[c] = -derivative;
        }
      }
    }
  }
}

Eigen::Matrix3Xd MaxwellTraction3D(const Eigen::Matrix3Xd& normal, double eps_minus,
                                   double eps_plus, const std::vector<double>& en_minus,
                                   const std::vector<double>& en_plus,
                                   const Eigen::Matrix3Xd& et_minus,
                                   const Eigen::Matrix3Xd& et_plus) {
  const long m = normal.cols();
  if (static_cast<long>(en_minus.size()) != m || static_cast<long>(en_plus.size()) != m ||
      et_minus.cols() != m || et_plus.cols() != m) {
    throw std::invalid_argument(
        "MaxwellTraction3D: field components must have one value per "
        "vertex (" +
        std::to_string(m) + ")");
  }
  Eigen::Matrix3Xd traction(3, m);
  for (long v = 0; v < m; ++v) {
    const double normal_part =
        0.5 * (eps_plus * (en_plus[v] * en_plus[v] - et_plus.col(v).squaredNorm()) -
               eps_minus * (en_minus[v] * en_minus[v] - et_minus.col(v).squaredNorm()));
    traction.col(v) = normal_part * normal.col(v) + eps_plus * en_plus[v] * et_plus.col(v) -
                      eps_minus * en_minus[v] * et_minus.col(v);
  }
  return traction;
}

}  // namespace ehd
