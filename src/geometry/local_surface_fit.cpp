#include "ehd_capsule/geometry/local_surface_fit.h"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {
namespace {

// The vertices within `rings` edge rings of v, v first (breadth first).
std::vector<int> Rings(const TriangleMesh& mesh, int v, int rings, std::vector<int>& mark) {
  std::vector<int> out{v};
  mark[v] = v;
  std::size_t begin = 0;
  for (int r = 0; r < rings; ++r) {
    const std::size_t end = out.size();
    for (std::size_t q = begin; q < end; ++q) {
      for (int e : mesh.vertex_edges(out[q])) {
        const TriangleMesh::Edge& edge = mesh.edges()[e];
        const int other = edge.a == out[q] ? edge.b : edge.a;
        if (mark[other] != v) {
          mark[other] = v;
          out.push_back(other);
        }
      }
    }
    begin = end;
  }
  return out;
}

// Height and its derivatives (h, h_u, h_w, h_uu, h_uw, h_ww) of the patch graph at (u, w).
struct HeightJet {
  double h, hu, hw, huu, huw, hww;
};
HeightJet Height(const std::array<double, 9>& c, double u, double w) {
  HeightJet j;
  j.h = c[0] * u + c[1] * w + c[2] * u * u + c[3] * u * w + c[4] * w * w + c[5] * u * u * u +
        c[6] * u * u * w + c[7] * u * w * w + c[8] * w * w * w;
  j.hu = c[0] + 2 * c[2] * u + c[3] * w + 3 * c[5] * u * u + 2 * c[6] * u * w + c[7] * w * w;
  j.hw = c[1] + c[3] * u + 2 * c[4] * w + c[6] * u * u + 2 * c[7] * u * w + 3 * c[8] * w * w;
  j.huu = 2 * c[2] + 6 * c[5] * u + 2 * c[6] * w;
  j.huw = c[3] + 2 * c[6] * u + 2 * c[7] * w;
  j.hww = 2 * c[4] + 2 * c[7] * u + 6 * c[8] * w;
  return j;
}

// Monomials 1, u, w, u^2, u w, w^2, u^3, u^2 w, u w^2, w^3.
void Basis(double u, double w, double* b) {
  b[0] = 1;
  b[1] = u;
  b[2] = w;
  b[3] = u * u;
  b[4] = u * w;
  b[5] = w * w;
  b[6] = u * u * u;
  b[7] = u * u * w;
  b[8] = u * w * w;
  b[9] = w * w * w;
}

// The least squares of FitPatch in matrices of type Matrix (fixed maximum size or dynamic).
template <typename Matrix>
void FitPatchLeastSquares(const Eigen::Matrix3Xd& x, int height_terms, int function_terms,
                          SurfacePatch& p) {
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, Matrix::MaxRowsAtCompileTime, 1>;
  const int m = static_cast<int>(p.support.size());
  double mean_square = 0;
  for (int j = 1; j < m; ++j) mean_square += (x.col(p.support[j]) - p.origin).squaredNorm();
  mean_square /= (m - 1);
  // Height through the vertex over the neighbours; the function over the vertex and them.
  Matrix a(m - 1, height_terms);
  Vector b(m - 1);
  Matrix af(m, function_terms);
  Vector weight_root(m);
  for (int j = 0; j < m; ++j) {
    const Eigen::Vector3d d = x.col(p.support[j]) - p.origin;
    const double u = d.dot(p.t1), w = d.dot(p.t2), h = d.dot(p.n);
    const double weight = 1.0 / (d.squaredNorm() + (j == 0 ? mean_square : 0.0));
    weight_root(j) = std::sqrt(weight);
    double basis[10];
    Basis(u, w, basis);
    for (int t = 0; t < function_terms; ++t) af(j, t) = basis[t] * weight_root(j);
    if (j > 0) {
      for (int t = 0; t < height_terms; ++t) a(j - 1, t) = basis[t + 1] * weight;
      b(j - 1) = h * weight;
    }
  }
  const Vector c = a.colPivHouseholderQr().solve(b);
  p.height.fill(0.0);
  for (int k = 0; k < height_terms; ++k) p.height[k] = c(k);
  const double fu = c(0), fw = c(1);
  Eigen::Matrix2d first, hess;
  first << 1 + fu * fu, fu * fw, fu * fw, 1 + fw * fw;
  hess << 2 * c(2), c(3), c(3), 2 * c(4);
  p.curvature_sum = -(first.inverse() * hess).trace() / std::sqrt(1 + fu * fu + fw * fw);
  p.gaussian_curvature = hess.determinant() / std::pow(1 + fu * fu + fw * fw, 2);
  // function_fit = (W^1/2 A)^+ W^1/2: coefficients = function_fit * values(support).
  const Matrix weights = weight_root.asDiagonal();
  p.function_fit = Eigen::MatrixXd::Zero(10, m);
  p.function_fit.topRows(function_terms) = af.colPivHouseholderQr().solve(weights);
}
}  // namespace

LocalSurfaceFit::LocalSurfaceFit(const TriangleMesh& mesh, double bucket, int rings, int degree,
                                 int threads)
    : mesh_(mesh), projector_(mesh, bucket) {
  if (rings < 1 || rings > 4) {
    throw std::invalid_argument("LocalSurfaceFit: rings = " + std::to_string(rings) +
                                " outside [1, 4]");
  }
  if (degree != 2 && degree != 3) {
    throw std::invalid_argument("LocalSurfaceFit: degree = " + std::to_string(degree) +
                                " (2 or 3)");
  }
  const int height_terms = degree == 3 ? 9 : 5, function_terms = degree == 3 ? 10 : 6;
  const Eigen::Matrix3Xd& x = mesh.vertices();
  const int nv = mesh.vertex_count();
  Eigen::Matrix3Xd normal = Eigen::Matrix3Xd::Zero(3, nv);
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3d a = x.col(t[0]), b = x.col(t[1]), c = x.col(t[2]);
    const Eigen::Vector3d n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normal.col(t[k]) += n;
  }
  patches_.resize(nv);
  // The patches are independent: threaded (OpenMP, threads <= 0: the default), each vertex's
  // result the same whatever the thread count.
  std::string error;
#pragma omp parallel num_threads(threads > 0 ? threads : omp_get_max_threads()) if (threads != 1)
  {
    std::vector<int> mark(nv, -1);
#pragma omp for schedule(dynamic, 64)
    for (int v = 0; v < nv; ++v) {
      try {
        FitPatch(mesh, normal, v, rings, height_terms, function_terms, mark, patches_[v]);
      } catch (const std::exception& e) {
#pragma omp critical(local_surface_fit_error)
        if (error.empty()) error = e.what();
      }
    }
  }
  if (!error.empty()) throw std::runtime_error(error);
}

void LocalSurfaceFit::FitPatch(const TriangleMesh& mesh, const Eigen::Matrix3Xd& normal, int v,
                               int rings, int height_terms, int function_terms,
                               std::vector<int>& mark, SurfacePatch& p) {
  const Eigen::Matrix3Xd& x = mesh.vertices();
  p.support = Rings(mesh, v, rings, mark);
  const int m = static_cast<int>(p.support.size());
  if (m < function_terms + 1) {
    throw std::runtime_error("LocalSurfaceFit: vertex " + std::to_string(v) + " has " +
                             std::to_string(m - 1) + " neighbours within " + std::to_string(rings) +
                             " rings (" + std::to_string(function_terms) + " needed)");
  }
  p.origin = x.col(v);
  p.n = normal.col(v).normalized();
  p.t1 = p.n.unitOrthogonal();
  p.t2 = p.n.cross(p.t1);
  // Two rings hold at most kSmallSupport vertices on the meshes of this package (valence <= 8):
  // their least squares run in matrices on the stack (the fits are redone at every electric
  // solve); larger supports on the heap, with the same arithmetic.
  if (m <= kSmallSupport) {
    FitPatchLeastSquares<
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kSmallSupport, kSmallSupport>>(
        x, height_terms, function_terms, p);
  } else {
    FitPatchLeastSquares<Eigen::MatrixXd>(x, height_terms, function_terms, p);
  }
}

double LocalSurfaceFit::MaxCurvature(int v) const {
  const double half = 0.5 * patches_[v].curvature_sum;
  return std::abs(half) + std::sqrt(std::max(0.0, half * half - patches_[v].gaussian_curvature));
}

PatchFoot LocalSurfaceFit::Project(const Eigen::Vector3d& x) const {
  const SurfacePoint nearest = projector_.Closest(x);
  const auto& tri = mesh_.triangles()[nearest.triangle];
  int k = 0;
  nearest.barycentric.maxCoeff(&k);
  PatchFoot foot;
  foot.vertex = tri[k];
  const SurfacePatch& p = patches_[foot.vertex];
  const auto& c = p.height;
  const Eigen::Vector3d d0 = x - p.origin;
  double u = d0.dot(p.t1), w = d0.dot(p.t2);
  Eigen::Vector3d xu, xw, r;
  for (int it = 0; it < 30; ++it) {
    const HeightJet j = Height(c, u, w);
    r = x - (p.origin + u * p.t1 + w * p.t2 + j.h * p.n);
    xu = p.t1 + j.hu * p.n;
    xw = p.t2 + j.hw * p.n;
    const double rn = r.dot(p.n);
    Eigen::Matrix2d jac;
    jac << -xu.dot(xu) + rn * j.huu, -xu.dot(xw) + rn * j.huw, -xw.dot(xu) + rn * j.huw,
        -xw.dot(xw) + rn * j.hww;
    const Eigen::Vector2d residual(r.dot(xu), r.dot(xw));
    const Eigen::Vector2d step = jac.lu().solve(-residual);
    u += step(0);
    w += step(1);
    if (step.norm() < 1e-14 * (1 + std::abs(u) + std::abs(w))) break;
  }
  const HeightJet j = Height(c, u, w);
  xu = p.t1 + j.hu * p.n;
  xw = p.t2 + j.hw * p.n;
  foot.u = u;
  foot.w = w;
  foot.point = p.origin + u * p.t1 + w * p.t2 + j.h * p.n;
  foot.normal = xu.cross(xw).normalized();
  foot.signed_distance = (x - foot.point).dot(foot.normal);
  Eigen::Matrix2d first, hess;
  first << 1 + j.hu * j.hu, j.hu * j.hw, j.hu * j.hw, 1 + j.hw * j.hw;
  hess << j.huu, j.huw, j.huw, j.hww;
  const double root = std::sqrt(1 + j.hu * j.hu + j.hw * j.hw);
  foot.curvature_sum = -(first.inverse() * hess).trace() / root;
  foot.gaussian_curvature = hess.determinant() / std::pow(root, 4);
  return foot;
}

std::array<double, 10> LocalSurfaceFit::FitFunction(int v,
                                                    const std::vector<double>& values) const {
  if (static_cast<int>(values.size()) != mesh_.vertex_count()) {
    throw std::invalid_argument("LocalSurfaceFit: " + std::to_string(values.size()) +
                                " values for " + std::to_string(mesh_.vertex_count()) +
                                " vertices");
  }
  const SurfacePatch& p = patches_[v];
  std::array<double, 10> a{};
  for (int i = 0; i < 10; ++i) {
    double s = 0;
    for (std::size_t j = 0; j < p.support.size(); ++j)
      s += p.function_fit(i, j) * values[p.support[j]];
    a[i] = s;
  }
  return a;
}

double LocalSurfaceFit::Value(const PatchFoot& foot, const std::vector<double>& values) const {
  const auto a = FitFunction(foot.vertex, values);
  double basis[10];
  Basis(foot.u, foot.w, basis);
  double value = 0;
  for (int i = 0; i < 10; ++i) value += a[i] * basis[i];
  return value;
}

double LocalSurfaceFit::SurfaceLaplacian(const PatchFoot& foot,
                                         const std::vector<double>& values) const {
  const std::vector<double> weights = SurfaceLaplacianWeights(foot);
  const std::vector<int>& support = patches_[foot.vertex].support;
  double out = 0;
  for (std::size_t q = 0; q < support.size(); ++q) out += weights[q] * values[support[q]];
  return out;
}

std::vector<double> LocalSurfaceFit::ValueWeights(const PatchFoot& foot) const {
  const SurfacePatch& p = patches_[foot.vertex];
  double basis[10];
  Basis(foot.u, foot.w, basis);
  std::vector<double> out(p.support.size(), 0.0);
  for (std::size_t j = 0; j < out.size(); ++j) {
    for (int i = 0; i < 10; ++i) out[j] += basis[i] * p.function_fit(i, j);
  }
  return out;
}

std::vector<double> LocalSurfaceFit::SurfaceLaplacianWeights(const PatchFoot& foot) const {
  const SurfacePatch& p = patches_[foot.vertex];
  const double u = foot.u, w = foot.w;
  const HeightJet j = Height(p.height, u, w);
  const double q = 1 + j.hu * j.hu + j.hw * j.hw;
  // Inverse metric of the graph: I - grad h grad h^T / q.
  const double g11 = 1 - j.hu * j.hu / q, g12 = -j.hu * j.hw / q, g22 = 1 - j.hw * j.hw / q;
  const double trace_h = g11 * j.huu + 2 * g12 * j.huw + g22 * j.hww;
  std::vector<double> out(p.support.size());
  for (std::size_t k = 0; k < out.size(); ++k) {
    const auto a = [&](int i) { return p.function_fit(i, k); };
    const double fu =
        a(1) + 2 * a(3) * u + a(4) * w + 3 * a(6) * u * u + 2 * a(7) * u * w + a(8) * w * w;
    const double fw =
        a(2) + a(4) * u + 2 * a(5) * w + a(7) * u * u + 2 * a(8) * u * w + 3 * a(9) * w * w;
    const double fuu = 2 * a(3) + 6 * a(6) * u + 2 * a(7) * w;
    const double fuw = a(4) + 2 * a(7) * u + 2 * a(8) * w;
    const double fww = 2 * a(5) + 2 * a(8) * u + 6 * a(9) * w;
    out[k] = g11 * fuu + 2 * g12 * fuw + g22 * fww - trace_h * (j.hu * fu + j.hw * fw) / q;
  }
  return out;
}

}  // namespace ehd
