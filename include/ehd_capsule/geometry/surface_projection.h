// Closest points on a triangulated surface (the foot points of grid nodes near the interface,
// where the 3D immersed interface corrections evaluate the jumps): the nearest point of the
// nearest triangle, its barycentric coordinates and the distance.
//
// Triangles are bucketed once into a uniform grid of cells of edge `bucket`; a query searches
// the buckets in growing shells until the nearest point found is closer than the shell, so the
// answer is the exact nearest point over all triangles (a test compares with brute force).
// Queries are meant for points within a few cells of the surface; far points cost more.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

struct SurfacePoint {
  int triangle = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // weights of the triangle's vertices
  double distance = 0;
};

// Nearest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5).
SurfacePoint ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c);

class SurfaceProjector {
 public:
  // bucket > 0 (about the grid spacing); the mesh is copied (positions of this instant).
  SurfaceProjector(const TriangleMesh& mesh, double bucket);
  SurfacePoint Closest(const Eigen::Vector3d& p) const;

 private:
  std::size_t Index(int i, int j, int k) const {
    return (static_cast<std::size_t>(i) * extent_[1] + j) * extent_[2] + k;
  }
  TriangleMesh mesh_;
  double bucket_;
  Eigen::Vector3d origin_;
  int extent_[3];
  Eigen::Matrix3Xd centroid_;   // of each triangle
  std::vector<double> radius_;  // of each triangle's bounding sphere about its centroid
  // Triangles touching each bucket (by bounding box), in triangle order: bucket b's are
  // bucket_triangles_[bucket_start_[b] .. bucket_start_[b + 1]).
  std::vector<int> bucket_start_, bucket_triangles_;
};

}  // namespace ehd
