#include "ehd_capsule/geometry/local_surface_fit.h"

#include <Eigen/Dense>
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

double Height(const std::array<double, 5>& c, double u, double w) {
  return c[0] * u + c[1] * w + c[2] * u * u + c[3] * u * w + c[4] * w * w;
}

}  // namespace

LocalSurfaceFit::LocalSurfaceFit(const TriangleMesh& mesh, double bucket, int rings)
    : mesh_(mesh), projector_(mesh, bucket) {
  if (rings < 1 || rings > 4) {
    throw std::invalid_argument("LocalSurfaceFit: rings = " + std::to_string(rings) +
                                " outside [1, 4]");
  }
  const Eigen::Matrix3Xd& x = mesh.vertices();
  const int nv = mesh.vertex_count();
  Eigen::Matrix3Xd normal = Eigen::Matrix3Xd::Zero(3, nv);
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3d a = x.col(t[0]), b = x.col(t[1]), c = x.col(t[2]);
    const Eigen::Vector3d n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normal.col(t[k]) += n;
  }
  patches_.resize(nv);
  std::vector<int> mark(nv, -1);
  for (int v = 0; v < nv; ++v) {
    SurfacePatch& p = patches_[v];
    p.support = Rings(mesh, v, rings, mark);
    const int m = static_cast<int>(p.support.size());
    if (m < 7) {
      throw std::runtime_error("LocalSurfaceFit: vertex " + std::to_string(v) + " has " +
                               std::to_string(m - 1) + " neighbours within " +
                               std::to_string(rings) + " rings (6 needed)");
    }
    p.origin = x.col(v);
    p.n = normal.col(v).normalized();
    p.t1 = p.n.unitOrthogonal();
    p.t2 = p.n.cross(p.t1);
    double mean_square = 0;
    for (int j = 1; j < m; ++j) mean_square += (x.col(p.support[j]) - p.origin).squaredNorm();
    mean_square /= (m - 1);
    // Height through the vertex: 5 unknowns over the neighbours.
    Eigen::MatrixXd a(m - 1, 5);
    Eigen::VectorXd b(m - 1);
    // Function: 6 unknowns over the vertex and its neighbours.
    Eigen::MatrixXd af(m, 6);
    Eigen::VectorXd weight_root(m);
    for (int j = 0; j < m; ++j) {
      const Eigen::Vector3d d = x.col(p.support[j]) - p.origin;
      const double u = d.dot(p.t1), w = d.dot(p.t2), h = d.dot(p.n);
      const double weight = 1.0 / (d.squaredNorm() + (j == 0 ? mean_square : 0.0));
      weight_root(j) = std::sqrt(weight);
      af.row(j) << 1, u, w, u * u, u * w, w * w;
      af.row(j) *= weight_root(j);
      if (j > 0) {
        a.row(j - 1) << u, w, u * u, u * w, w * w;
        a.row(j - 1) *= weight;
        b(j - 1) = h * weight;
      }
    }
    const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
    for (int k = 0; k < 5; ++k) p.height[k] = c(k);
    const double fu = c(0), fw = c(1);
    Eigen::Matrix2d first, hess;
    first << 1 + fu * fu, fu * fw, fu * fw, 1 + fw * fw;
    hess << 2 * c(2), c(3), c(3), 2 * c(4);
    p.curvature_sum = -(first.inverse() * hess).trace() / std::sqrt(1 + fu * fu + fw * fw);
    // function_fit = (W^1/2 A)^+ W^1/2: coefficients = function_fit * values(support).
    const Eigen::MatrixXd weights = weight_root.asDiagonal();
    p.function_fit = af.colPivHouseholderQr().solve(weights);
  }
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
    const double hu = c[0] + 2 * c[2] * u + c[3] * w, hw = c[1] + c[3] * u + 2 * c[4] * w;
    const double huu = 2 * c[2], huw = c[3], hww = 2 * c[4];
    r = x - (p.origin + u * p.t1 + w * p.t2 + Height(c, u, w) * p.n);
    xu = p.t1 + hu * p.n;
    xw = p.t2 + hw * p.n;
    const double rn = r.dot(p.n);
    Eigen::Matrix2d jac;
    jac << -xu.dot(xu) + rn * huu, -xu.dot(xw) + rn * huw, -xw.dot(xu) + rn * huw,
        -xw.dot(xw) + rn * hww;
    const Eigen::Vector2d residual(r.dot(xu), r.dot(xw));
    const Eigen::Vector2d step = jac.lu().solve(-residual);
    u += step(0);
    w += step(1);
    if (step.norm() < 1e-14 * (1 + std::abs(u) + std::abs(w))) break;
  }
  const double hu = c[0] + 2 * c[2] * u + c[3] * w, hw = c[1] + c[3] * u + 2 * c[4] * w;
  xu = p.t1 + hu * p.n;
  xw = p.t2 + hw * p.n;
  foot.u = u;
  foot.w = w;
  foot.point = p.origin + u * p.t1 + w * p.t2 + Height(c, u, w) * p.n;
  foot.normal = xu.cross(xw).normalized();
  foot.signed_distance = (x - foot.point).dot(foot.normal);
  Eigen::Matrix2d first, hess;
  first << 1 + hu * hu, hu * hw, hu * hw, 1 + hw * hw;
  hess << 2 * c[2], c[3], c[3], 2 * c[4];
  foot.curvature_sum = -(first.inverse() * hess).trace() / std::sqrt(1 + hu * hu + hw * hw);
  foot.gaussian_curvature = hess.determinant() / std::pow(1 + hu * hu + hw * hw, 2);
  return foot;
}

std::array<double, 6> LocalSurfaceFit::FitFunction(int v, const std::vector<double>& values) const {
  if (static_cast<int>(values.size()) != mesh_.vertex_count()) {
    throw std::invalid_argument("LocalSurfaceFit: " + std::to_string(values.size()) +
                                " values for " + std::to_string(mesh_.vertex_count()) +
                                " vertices");
  }
  const SurfacePatch& p = patches_[v];
  std::array<double, 6> a{};
  for (int i = 0; i < 6; ++i) {
    double s = 0;
    for (std::size_t j = 0; j < p.support.size(); ++j)
      s += p.function_fit(i, j) * values[p.support[j]];
    a[i] = s;
  }
  return a;
}

double LocalSurfaceFit::Value(const PatchFoot& foot, const std::vector<double>& values) const {
  const auto a = FitFunction(foot.vertex, values);
  const double u = foot.u, w = foot.w;
  return a[0] + a[1] * u + a[2] * w + a[3] * u * u + a[4] * u * w + a[5] * w * w;
}

double LocalSurfaceFit::SurfaceLaplacian(const PatchFoot& foot,
                                         const std::vector<double>& values) const {
  // At the vertex the frame is the tangent plane to O(h) and the Christoffel symbols of the graph
  // vanish to the same order, so Delta_s F = F_uu + F_ww + O(h).
  const auto a = FitFunction(foot.vertex, values);
  return 2 * a[3] + 2 * a[5];
}

std::vector<double> LocalSurfaceFit::ValueWeights(const PatchFoot& foot) const {
  const SurfacePatch& p = patches_[foot.vertex];
  const double u = foot.u, w = foot.w;
  const double basis[6] = {1, u, w, u * u, u * w, w * w};
  std::vector<double> out(p.support.size(), 0.0);
  for (std::size_t j = 0; j < out.size(); ++j) {
    for (int i = 0; i < 6; ++i) out[j] += basis[i] * p.function_fit(i, j);
  }
  return out;
}

std::vector<double> LocalSurfaceFit::SurfaceLaplacianWeights(int v) const {
  const SurfacePatch& p = patches_[v];
  std::vector<double> out(p.support.size());
  for (std::size_t j = 0; j < out.size(); ++j) {
    out[j] = 2 * p.function_fit(3, j) + 2 * p.function_fit(5, j);
  }
  return out;
}

}  // namespace ehd
