// Closed triangle meshes, their shapes and discrete differential geometry; see triangle_mesh.h.
#include "ehd_capsule/geometry/triangle_mesh.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace ehd {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d Column(const Eigen::Matrix3Xd& x, int k) { return x.col(k); }

double Cotangent(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return u.dot(v) / u.cross(v).norm();
}

}  // namespace

TriangleMesh::TriangleMesh(Eigen::Matrix3Xd vertices, std::vector<Triangle> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  const int v = vertex_count();
  if (v < 3 || triangles_.size() < 2) {
    throw std::invalid_argument(
        "TriangleMesh: a closed surface needs >= 3 vertices and >= 2 "
        "triangles (got " +
        std::to_string(v) + ", " + std::to_string(triangles_.size()) + ")");
  }
  vertex_triangles_.assign(v, {});
  vertex_edges_.assign(v, {});
  // Directed edge a -> b to (triangle, opposite vertex); each must appear once.
  std::map<std::pair<int, int>, std::pair<int, int>> directed;
  for (int t = 0; t < triangle_count(); ++t) {
    const Triangle& tri = triangles_[t];
    for (int c = 0; c < 3; ++c) {
      if (tri[c] < 0 || tri[c] >= v) {
        throw std::invalid_argument("TriangleMesh: triangle " + std::to_string(t) +
                                    " has vertex index " + std::to_string(tri[c]) +
                                    " outside [0, " + std::to_string(v) + ")");
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
      throw std::invalid_argument("TriangleMesh: triangle " + std::to_string(t) +
                                  " repeats a vertex");
    }
    for (int c = 0; c < 3; ++c) {
      vertex_triangles_[tri[c]].push_back(t);
      const auto key = std::make_pair(tri[c], tri[(c + 1) % 3]);
      if (!directed.emplace(key, std::make_pair(t, tri[(c + 2) % 3])).second) {
        throw std::invalid_argument("TriangleMesh: edge " + std::to_string(key.first) + " -> " +
                                    std::to_string(key.second) +
                                    " appears twice in the same direction (inconsistent "
                                    "orientation or a non-manifold edge)");
      }
    }
  }
  for (const auto& [key, value] : directed) {
    const auto [a, b] = key;
    if (a > b) continue;
    const auto other = directed.find(std::make_pair(b, a));
    if (other == directed.end()) {
      throw std::invalid_argument("TriangleMesh: edge " + std::to_string(a) + " - " +
                                  std::to_string(b) +
                                  " has one triangle only (the surface is not closed)");
    }
    Edge e{a, b, value.first, other->second.first, value.second, other->second.second};
    vertex_edges_[a].push_back(static_cast<int>(edges_.size()));
    vertex_edges_[b].push_back(static_cast<int>(edges_.size()));
    edges_.push_back(e);
  }
  for (int k = 0; k < v; ++k) {
    if (vertex_triangles_[k].empty()) {
      throw std::invalid_argument("TriangleMesh: vertex " + std::to_string(k) +
                                  " is in no triangle");
    }
  }
}

void TriangleMesh::SetVertices(const Eigen::Matrix3Xd& vertices) {
  if (vertices.cols() != vertices_.cols()) {
    throw std::invalid_argument("TriangleMesh::SetVertices: " + std::to_string(vertices.cols()) +
                                " positions for " + std::to_string(vertices_.cols()) + " vertices");
  }
  vertices_ = vertices;
}

TriangleMesh IcosphereMesh(int subdivisions, double radius) {
  if (subdivisions < 0 || subdivisions > 7) {
    throw std::invalid_argument("IcosphereMesh: subdivisions = " + std::to_string(subdivisions) +
                                " outside [0, 7]");
  }
  if (!(radius > 0.0)) throw std::invalid_argument("IcosphereMesh: radius must be > 0");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                    {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                    {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& q : p) q.normalize();
  std::vector<TriangleMesh::Triangle> f = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& tri : f) {  // outward orientation (the icosahedron is star-shaped about 0)
    const Eigen::Vector3d n = (p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]);
    if (n.dot(p[tri[0]]) < 0) std::swap(tri[1], tri[2]);
  }
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoint.find(key);
      if (found != midpoint.end()) return found->second;
      p.push_back((p[a] + p[b]).normalized());
      const int index = static_cast<int>(p.size()) - 1;
      midpoint.emplace(key, index);
      return index;
    };
    std::vector<TriangleMesh::Triangle> next;
    next.reserve(4 * f.size());
    for (const auto& tri : f) {
      const int ab = middle(tri[0], tri[1]), bc = middle(tri[1], tri[2]),
                ca = middle(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  Eigen::Matrix3Xd x(3, static_cast<Eigen::Index>(p.size()));
  for (std::size_t k = 0; k < p.size(); ++k) x.col(static_cast<Eigen::Index>(k)) = radius * p[k];
  return TriangleMesh(std::move(x), std::move(f));
}

TriangleMesh EllipsoidMesh(int subdivisions, double a, double b, double c) {
  if (!(a > 0.0 && b > 0.0 && c > 0.0)) {
    throw std::invalid_argument("EllipsoidMesh: semi-axes must be > 0");
  }
  TriangleMesh sphere = IcosphereMesh(subdivisions);
  Eigen::Matrix3Xd x = sphere.vertices();
  x.row(0) *= a;
  x.row(1) *= b;
  x.row(2) *= c;
  return TriangleMesh(std::move(x), sphere.triangles());
}

TriangleMesh BiconcaveMesh(int subdivisions, const BiconcaveParameters& p) {
  if (!(p.radius > 0.0) || !(p.alpha > 0.0)) {
    throw std::invalid_argument("BiconcaveMesh: radius and alpha must be > 0");
  }
  TriangleMesh sphere = IcosphereMesh(subdivisions);
  const double big_r = p.radius * p.alpha;
  Eigen::Matrix3Xd x = sphere.vertices();
  for (int k = 0; k < x.cols(); ++k) {
    const double cos_chi = x(1, k);                           // the symmetry axis is y
    const double s2 = x(0, k) * x(0, k) + x(2, k) * x(2, k);  // sin^2 chi
    x(0, k) *= big_r;
    x(2, k) *= big_r;
    x(1, k) = 0.5 * big_r * (p.c0 + p.c1 * s2 + p.c2 * s2 * s2) * cos_chi;
  }
  return TriangleMesh(std::move(x), sphere.triangles());
}

double BiconcaveVolume(const BiconcaveParameters& p) {
  const double big_r = p.radius * p.alpha;
  return 2.0 * kPi * big_r * big_r * big_r * (p.c0 / 3.0 + 2.0 * p.c1 / 15.0 + 8.0 * p.c2 / 105.0);
}

std::vector<double> VertexThirdAreas(const TriangleMesh& mesh) {
  return VertexThirdAreas(mesh.vertices(), mesh.triangles(), mesh.vertex_count());
}

std::vector<double> VertexThirdAreas(const Eigen::Matrix3Xd& x,
                                     const std::vector<TriangleMesh::Triangle>& triangles,
                                     int vertex_count) {
  std::vector<double> area(vertex_count, 0.0);
  for (const auto& t : triangles) {
    const double third = (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0])).norm() / 6.0;
    for (int v : t) area[v] += third;
  }
  return area;
}

Eigen::Vector3d AreaWeightedMean(const TriangleMesh& mesh, const std::vector<double>& area,
                                 const Eigen::Matrix3Xd& field) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    mean += area[v] * field.col(v);
    total += area[v];
  }
  return mean / total;
}

double SurfaceArea(const TriangleMesh& mesh) {
  const Eigen::Matrix3Xd& x = mesh.vertices();
  double area = 0.0;
  for (const auto& t : mesh.triangles()) {
    area +=
        0.5 * (Column(x, t[1]) - Column(x, t[0])).cross(Column(x, t[2]) - Column(x, t[0])).norm();
  }
  return area;
}

double EnclosedVolume(const TriangleMesh& mesh) {
  return EnclosedVolume(mesh.vertices(), mesh.triangles());
}

double EnclosedVolume(const Eigen::Matrix3Xd& x,
                      const std::vector<TriangleMesh::Triangle>& triangles) {
  double volume = 0.0;
  for (const auto& t : triangles)
    volume += Column(x, t[0]).dot(Column(x, t[1]).cross(Column(x, t[2])));
  return volume / 6.0;
}

namespace {

// dV/dx_a = (x_b x x_c) / 6 summed over a's triangles (a, b, c).
Eigen::Matrix3Xd VolumeGradient(const Eigen::Matrix3Xd& x,
                                const std::vector<TriangleMesh::Triangle>& triangles) {
  Eigen::Matrix3Xd gradient = Eigen::Matrix3Xd::Zero(3, x.cols());
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      gradient.col(t[k]) += Column(x, t[(k + 1) % 3]).cross(Column(x, t[(k + 2) % 3])) / 6.0;
    }
  }
  return gradient;
}

}  // namespace

double RestoreEnclosedVolume(const std::vector<TriangleMesh::Triangle>& triangles, double volume,
                             Eigen::Matrix3Xd& x) {
  if (!(volume > 0.0)) {
    throw std::invalid_argument("RestoreEnclosedVolume: target volume must be > 0");
  }
  // The unit directions of dV/dx_i at the starting positions.
  Eigen::Matrix3Xd direction = VolumeGradient(x, triangles);
  for (long i = 0; i < x.cols(); ++i) {
    const double norm = direction.col(i).norm();
    if (!(norm > 0.0)) {
      throw std::invalid_argument("RestoreEnclosedVolume: vertex " + std::to_string(i) +
                                  " has no volume gradient (degenerate surface)");
    }
    direction.col(i) /= norm;
  }
  const Eigen::Matrix3Xd start = x;
  double delta = 0.0;
  for (int it = 0; it < 8; ++it) {
    x = start + delta * direction;
    const double residual = EnclosedVolume(x, triangles) - volume;
    if (std::abs(residual) <= 1e-14 * volume) break;
    // dV/d delta = sum_i dV/dx_i . direction_i at the current positions.
    const double slope = VolumeGradient(x, triangles).cwiseProduct(direction).sum();
    if (!(slope > 0.0)) {
      throw std::invalid_argument(
          "RestoreEnclosedVolume: the volume does not grow along the vertex normals (a surface "
          "turned inside out)");
    }
    delta -= residual / slope;
  }
  x = start + delta * direction;
  return delta;
}

Eigen::Vector3d Centroid(const TriangleMesh& mesh) {
  // Sum over the tetrahedra (0, a, b, c): volume-weighted centroids (a + b + c) / 4.
  const Eigen::Matrix3Xd& x = mesh.vertices();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double volume = 0.0;
  for (const auto& t : mesh.triangles()) {
    const double v = Column(x, t[0]).dot(Column(x, t[1]).cross(Column(x, t[2]))) / 6.0;
    volume += v;
    moment += v * (Column(x, t[0]) + Column(x, t[1]) + Column(x, t[2])) / 4.0;
  }
  return moment / volume;
}

Eigen::Matrix3Xd AreaWeightedVertexNormals(const TriangleMesh& mesh) {
  const Eigen::Matrix3Xd& x = mesh.vertices();
  Eigen::Matrix3Xd normal = Eigen::Matrix3Xd::Zero(3, mesh.vertex_count());
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3d n =
        (Column(x, t[1]) - Column(x, t[0])).cross(Column(x, t[2]) - Column(x, t[0]));
    for (int c = 0; c < 3; ++c) normal.col(t[c]) += n;  // area weighted (|n| = 2 area)
  }
  normal.colwise().normalize();
  return normal;
}

SurfaceGeometry MeasureSurface(const TriangleMesh& mesh) {
  const Eigen::Matrix3Xd& x = mesh.vertices();
  const int nv = mesh.vertex_count();
  SurfaceGeometry g;
  g.vertex_area.assign(nv, 0.0);
  g.normal.setZero(3, nv);
  g.laplace_position.setZero(3, nv);
  std::vector<double> angle_sum(nv, 0.0);
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3d p[3] = {x.col(t[0]), x.col(t[1]), x.col(t[2])};
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    const double area = 0.5 * n.norm();
    double angle[3], cot[3];
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d u = p[(c + 1) % 3] - p[c], v = p[(c + 2) % 3] - p[c];
      angle[c] = std::atan2(u.cross(v).norm(), u.dot(v));
      cot[c] = Cotangent(u, v);
      angle_sum[t[c]] += angle[c];
      g.normal.col(t[c]) += n;  // area weighted (|n| = 2 area)
    }
    const bool obtuse = angle[0] > 0.5 * kPi || angle[1] > 0.5 * kPi || angle[2] > 0.5 * kPi;
    for (int c = 0; c < 3; ++c) {
      const int a = (c + 1) % 3, b = (c + 2) % 3;
      if (!obtuse) {
        // Voronoi: (|x_c x_a|^2 cot(angle b) + |x_c x_b|^2 cot(angle a)) / 8.
        g.vertex_area[t[c]] +=
            ((p[a] - p[c]).squaredNorm() * cot[b] + (p[b] - p[c]).squaredNorm() * cot[a]) / 8.0;
      } else {
        g.vertex_area[t[c]] += angle[c] > 0.5 * kPi ? area / 2.0 : area / 4.0;
      }
    }
  }
  for (const auto& e : mesh.edges()) {
    const Eigen::Vector3d xa = x.col(e.a), xb = x.col(e.b);
    const Eigen::Vector3d l = x.col(e.opposite_left), r = x.col(e.opposite_right);
    const double w = Cotangent(xa - l, xb - l) + Cotangent(xa - r, xb - r);
    g.laplace_position.col(e.a) += w * (xb - xa);
    g.laplace_position.col(e.b) += w * (xa - xb);
  }
  g.mean_curvature.resize(nv);
  g.gaussian_curvature.resize(nv);
  for (int k = 0; k < nv; ++k) {
    g.normal.col(k).normalize();
    g.laplace_position.col(k) /= 2.0 * g.vertex_area[k];
    g.mean_curvature[k] = -0.5 * g.laplace_position.col(k).dot(g.normal.col(k));
    g.gaussian_curvature[k] = (2.0 * kPi - angle_sum[k]) / g.vertex_area[k];
  }
  return g;
}

std::vector<double> LaplaceBeltrami(const TriangleMesh& mesh, const std::vector<double>& area,
                                    const std::vector<double>& f) {
  const int nv = mesh.vertex_count();
  if (static_cast<int>(f.size()) != nv || static_cast<int>(area.size()) != nv) {
    throw std::invalid_argument("LaplaceBeltrami: f and area need one value per vertex");
  }
  const Eigen::Matrix3Xd& x = mesh.vertices();
  std::vector<double> out(nv, 0.0);
  for (const auto& e : mesh.edges()) {
    const Eigen::Vector3d xa = x.col(e.a), xb = x.col(e.b);
    const Eigen::Vector3d l = x.col(e.opposite_left), r = x.col(e.opposite_right);
    const double w = Cotangent(xa - l, xb - l) + Cotangent(xa - r, xb - r);
    out[e.a] += w * (f[e.b] - f[e.a]);
    out[e.b] += w * (f[e.a] - f[e.b]);
  }
  for (int k = 0; k < nv; ++k) out[k] /= 2.0 * area[k];
  return out;
}

std::vector<double> FittedCurvatures::mean_curvature() const {
  std::vector<double> h(kappa1.size());
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = 0.5 * (kappa1[i] + kappa2[i]);
  return h;
}

std::vector<double> FittedCurvatures::gaussian_curvature() const {
  std::vector<double> k(kappa1.size());
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = kappa1[i] * kappa2[i];
  return k;
}

FittedCurvatures FitCurvatures(const TriangleMesh& mesh, int rings) {
  if (rings < 1 || rings > 4) {
    throw std::invalid_argument("FitCurvatures: rings = " + std::to_string(rings) +
                                " outside [1, 4]");
  }
  const Eigen::Matrix3Xd& x = mesh.vertices();
  const int nv = mesh.vertex_count();
  // Area-weighted normals as the first frame.
  Eigen::Matrix3Xd normal = Eigen::Matrix3Xd::Zero(3, nv);
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3d n =
        (Column(x, t[1]) - Column(x, t[0])).cross(Column(x, t[2]) - Column(x, t[0]));
    for (int c = 0; c < 3; ++c) normal.col(t[c]) += n;
  }
  FittedCurvatures out;
  out.normal.resize(3, nv);
  out.direction1.resize(3, nv);
  out.direction2.resize(3, nv);
  out.kappa1.resize(nv);
  out.kappa2.resize(nv);
  std::vector<int> mark(nv, -1), neighbours;
  for (int v = 0; v < nv; ++v) {
    // The vertices within `rings` edge rings (breadth first).
    neighbours.clear();
    mark[v] = v;
    std::size_t begin = 0;
    neighbours.push_back(v);
    for (int r = 0; r < rings; ++r) {
      const std::size_t end = neighbours.size();
      for (std::size_t q = begin; q < end; ++q) {
        for (int e : mesh.vertex_edges(neighbours[q])) {
          const TriangleMesh::Edge& edge = mesh.edges()[e];
          const int w = edge.a == neighbours[q] ? edge.b : edge.a;
          if (mark[w] != v) {
            mark[w] = v;
            neighbours.push_back(w);
          }
        }
      }
      begin = end;
    }
    const Eigen::Vector3d n = normal.col(v).normalized();
    Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    const Eigen::Vector3d p = x.col(v);
    const int m = static_cast<int>(neighbours.size()) - 1;
    if (m < 5) {
      throw std::runtime_error("FitCurvatures: vertex " + std::to_string(v) + " has " +
                               std::to_string(m) + " neighbours within " + std::to_string(rings) +
                               " rings (5 needed)");
    }
    Eigen::MatrixXd a(m, 5);
    Eigen::VectorXd b(m);
    for (int j = 0; j < m; ++j) {
      const Eigen::Vector3d d = x.col(neighbours[j + 1]) - p;
      const double u = d.dot(t1), w = d.dot(t2), h = d.dot(n);
      const double weight = 1.0 / d.squaredNorm();
      a.row(j) << u, w, u * u, u * w, w * w;
      a.row(j) *= weight;
      b(j) = h * weight;
    }
    const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
    // Graph z = f(u, w): I = [[1 + fu^2, fu fw], [fu fw, 1 + fw^2]], II = Hess / sqrt(1 + |g|^2)
    // with the normal (-fu, -fw, 1)/sqrt(...) along +n. The outward normal sees a sphere as
    // z = -(u^2 + w^2)/(2R): the principal curvatures (positive there) are those of -II.
    const double fu = c(0), fw = c(1);
    Eigen::Matrix2d first, second;
    first << 1 + fu * fu, fu * fw, fu * fw, 1 + fw * fw;
    const double root = std::sqrt(1 + fu * fu + fw * fw);
    second << 2 * c(2), c(3), c(3), 2 * c(4);
    second /= root;
    // S = -I^-1 II is self-adjoint in the metric I: the generalized symmetric eigenproblem
    // (-II) v = kappa I v gives its eigenvalues and eigenvectors.
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> eig(-second, first);
    const Eigen::Vector2d kappa = eig.eigenvalues();  // ascending
    const Eigen::Vector3d corrected = ((-fu) * t1 + (-fw) * t2 + n).normalized();
    out.normal.col(v) = corrected;
    out.kappa1[v] = kappa(1);
    out.kappa2[v] = kappa(0);
    // Principal directions: tangent vectors (du, dw) -> du (t1 + fu n) + dw (t2 + fw n).
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d dv = eig.eigenvectors().col(1 - k);
      const Eigen::Vector3d dir = (dv(0) * (t1 + fu * n) + dv(1) * (t2 + fw * n)).normalized();
      (k == 0 ? out.direction1 : out.direction2).col(v) = dir;
    }
  }
  return out;
}

std::vector<Eigen::Vector2d> CrossSectionZ(const TriangleMesh& mesh, double z0) {
  const Eigen::Matrix3Xd& x = mesh.vertices();
  const auto above = [&](int v) { return x(2, v) >= z0; };
  const int ne = mesh.edge_count();
  // Crossing point of each cut edge; per cut edge, the cut edges it is joined to through its
  // two triangles (each triangle the plane cuts has exactly two cut edges).
  std::vector<Eigen::Vector2d> point(ne);
  std::vector<char> cut(ne, 0);
  for (int e = 0; e < ne; ++e) {
    const TriangleMesh::Edge& edge = mesh.edges()[e];
    if (above(edge.a) == above(edge.b)) continue;
    const double t = (z0 - x(2, edge.a)) / (x(2, edge.b) - x(2, edge.a));
    point[e] = (x.col(edge.a) + t * (x.col(edge.b) - x.col(edge.a))).head<2>();
    cut[e] = 1;
  }
  // Edge index of each triangle side, from the vertex pairs.
  std::vector<std::array<int, 2>> links(ne, {-1, -1});
  std::vector<std::vector<int>> vertex_edges(mesh.vertex_count());
  for (int e = 0; e < ne; ++e) {
    vertex_edges[mesh.edges()[e].a].push_back(e);
    vertex_edges[mesh.edges()[e].b].push_back(e);
  }
  const auto edge_of = [&](int u, int v) {
    for (int e : vertex_edges[u]) {
      const TriangleMesh::Edge& edge = mesh.edges()[e];
      if ((edge.a == u && edge.b == v) || (edge.a == v && edge.b == u)) return e;
    }
    return -1;
  };
  for (const auto& t : mesh.triangles()) {
    int ends[2], n = 0;
    for (int c = 0; c < 3; ++c) {
      const int e = edge_of(t[c], t[(c + 1) % 3]);
      if (e >= 0 && cut[e] && n < 2) ends[n++] = e;
    }
    if (n != 2) continue;
    for (int k = 0; k < 2; ++k) {
      auto& l = links[ends[k]];
      (l[0] < 0 ? l[0] : l[1]) = ends[1 - k];
    }
  }
  std::vector<Eigen::Vector2d> best;
  std::vector<char> used(ne, 0);
  for (int start = 0; start < ne; ++start) {
    if (!cut[start] || used[start]) continue;
    std::vector<Eigen::Vector2d> loop;
    int previous = -1, current = start;
    while (current >= 0 && !used[current]) {
      used[current] = 1;
      loop.push_back(point[current]);
      const auto& l = links[current];
      const int next = l[0] != previous ? l[0] : l[1];
      previous = current;
      current = next;
    }
    if (loop.size() > best.size()) best = std::move(loop);
  }
  double area2 = 0;
  for (std::size_t k = 0; k < best.size(); ++k) {
    const Eigen::Vector2d& p = best[k];
    const Eigen::Vector2d& q = best[(k + 1) % best.size()];
    area2 += p.x() * q.y() - q.x() * p.y();
  }
  if (area2 < 0) std::reverse(best.begin(), best.end());
  return best;
}

MeshQuality MeasureQuality(const TriangleMesh& mesh) {
  const Eigen::Matrix3Xd& x = mesh.vertices();
  MeshQuality q;
  q.min_edge = 1e300;
  q.min_angle_deg = 180.0;
  double sum = 0.0;
  for (const auto& e : mesh.edges()) {
    const double l = (x.col(e.a) - x.col(e.b)).norm();
    q.min_edge = std::min(q.min_edge, l);
    q.max_edge = std::max(q.max_edge, l);
    sum += l;
  }
  q.mean_edge = sum / mesh.edge_count();
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3d p[3] = {x.col(t[0]), x.col(t[1]), x.col(t[2])};
    double len[3];
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d u = p[(c + 1) % 3] - p[c], v = p[(c + 2) % 3] - p[c];
      const double angle = std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / kPi;
      q.min_angle_deg = std::min(q.min_angle_deg, angle);
      q.max_angle_deg = std::max(q.max_angle_deg, angle);
      len[c] = (p[(c + 1) % 3] - p[c]).norm();
    }
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    const double s = 0.5 * (len[0] + len[1] + len[2]);
    q.max_aspect_ratio =
        std::max(q.max_aspect_ratio, len[0] * len[1] * len[2] * s / (8.0 * area * area));
  }
  q.min_valence = 1 << 30;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const int valence = static_cast<int>(mesh.vertex_edges(v).size());
    q.min_valence = std::min(q.min_valence, valence);
    q.max_valence = std::max(q.max_valence, valence);
  }
  return q;
}

std::string MeshQuality::Describe() const {
  std::ostringstream o;
  o << "edges " << min_edge << " .. " << max_edge << " (mean " << mean_edge << "), angles "
    << min_angle_deg << " .. " << max_angle_deg << " deg, aspect ratio <= " << max_aspect_ratio
    << ", valence " << min_valence << " .. " << max_valence;
  return o.str();
}

}  // namespace ehd
