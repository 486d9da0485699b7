#include "ehd_capsule/geometry/mesh_relaxation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/local_surface_fit.h"

namespace ehd {

namespace {

// Unit outward vertex normals: area-weighted face normals.
Eigen::Matrix3Xd VertexNormals(const TriangleMesh& mesh) {
  const Eigen::Matrix3Xd& x = mesh.vertices();
  Eigen::Matrix3Xd normal = Eigen::Matrix3Xd::Zero(3, mesh.vertex_count());
  for (const auto& t : mesh.triangles()) {
    const Eigen::Vector3d n = (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0]));
    for (int v : t) normal.col(v) += n;
  }
  normal.colwise().normalize();
  return normal;
}

}  // namespace

MeshRelaxationReport RelaxMeshTangentially(TriangleMesh& mesh, int iterations, double weight,
                                           double bucket) {
  if (iterations < 1) {
    throw std::invalid_argument(
        "RelaxMeshTangentially: iterations = " + std::to_string(iterations) + " (need >= 1)");
  }
  if (!(weight > 0.0 && weight <= 1.0)) {
    throw std::invalid_argument("RelaxMeshTangentially: weight = " + std::to_string(weight) +
                                " (need 0 < weight <= 1)");
  }
  if (!(bucket > 0.0)) {
    throw std::invalid_argument("RelaxMeshTangentially: bucket = " + std::to_string(bucket) +
                                " (need > 0)");
  }
  // The surface before the call (only its cubic height fits are used).
  const LocalSurfaceFit fit(mesh, bucket, 2, 3, 1);
  const Eigen::Matrix3Xd start = mesh.vertices();
  MeshRelaxationReport report;
  Eigen::Matrix3Xd next(3, mesh.vertex_count());
  for (int it = 0; it < iterations; ++it) {
    const Eigen::Matrix3Xd& x = mesh.vertices();
    const Eigen::Matrix3Xd normal = VertexNormals(mesh);
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      const auto& around = mesh.vertex_edges(v);
      for (int e : around) {
        const auto& edge = mesh.edges()[e];
        mean += x.col(edge.a == v ? edge.b : edge.a);
      }
      mean /= static_cast<double>(around.size());
      Eigen::Vector3d d = mean - x.col(v);
      d -= d.dot(normal.col(v)) * normal.col(v);
      const PatchFoot foot = fit.Project(x.col(v) + weight * d);
      report.max_normal_offset = std::max(report.max_normal_offset, std::abs(foot.signed_distance));
      next.col(v) = foot.point;
    }
    mesh.SetVertices(next);
  }
  report.max_tangential_move = (mesh.vertices() - start).colwise().norm().maxCoeff();
  return report;
}

Eigen::Matrix3Xd DropVertexVelocity(const TriangleMesh& mesh, const Eigen::Matrix3Xd& velocity) {
  const int n = mesh.vertex_count();
  if (velocity.cols() != n) {
    throw std::invalid_argument("DropVertexVelocity: " + std::to_string(velocity.cols()) +
                                " velocities for " + std::to_string(n) + " vertices");
  }
  const Eigen::Matrix3Xd normal = VertexNormals(mesh);
  const Eigen::Vector3d mean = AreaWeightedMean(mesh, VertexThirdAreas(mesh), velocity);
  Eigen::Matrix3Xd out(3, n);
  for (int v = 0; v < n; ++v) {
    out.col(v) = mean + (velocity.col(v) - mean).dot(normal.col(v)) * normal.col(v);
  }
  return out;
}

}  // namespace ehd
