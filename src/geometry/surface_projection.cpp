// Closest points on triangles and on a bucketed triangulated surface; see surface_projection.h.
#include "ehd_capsule/geometry/surface_projection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ehd {

SurfacePoint ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  SurfacePoint s;
  auto done = [&](double u, double v, double w) {
    s.barycentric = Eigen::Vector3d(u, v, w);
    s.point = u * a + v * b + w * c;
    s.distance = (p - s.point).norm();
    return s;
  };
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return done(1, 0, 0);  // vertex a
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return done(0, 1, 0);  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {  // edge ab
    const double v = d1 / (d1 - d3);
    return done(1 - v, v, 0);
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return done(0, 0, 1);  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {  // edge ac
    const double w = d2 / (d2 - d6);
    return done(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {  // edge bc
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return done(0, 1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);  // inside the face
  const double v = vb * denom, w = vc * denom;
  return done(1 - v - w, v, w);
}

SurfaceProjector::SurfaceProjector(const TriangleMesh& mesh, double bucket)
    : mesh_(mesh), bucket_(bucket) {
  if (!(bucket > 0.0)) throw std::invalid_argument("SurfaceProjector: bucket must be > 0");
  const Eigen::Matrix3Xd& x = mesh.vertices();
  origin_ = x.rowwise().minCoeff();
  const Eigen::Vector3d span = x.rowwise().maxCoeff() - origin_;
  // The buckets are a dense array over the mesh's box; a bucket far below the mesh's size
  // (more than 64 buckets a triangle) is widened until they fit (only the search's cost depends
  // on it).
  const double max_buckets = std::max(1 << 20, 64 * mesh.triangle_count());
  while ((span(0) / bucket_ + 1) * (span(1) / bucket_ + 1) * (span(2) / bucket_ + 1) >
         max_buckets) {
    bucket_ *= 2.0;
  }
  for (int a = 0; a < 3; ++a) extent_[a] = static_cast<int>(span(a) / bucket_) + 1;
  centroid_.resize(3, mesh.triangle_count());
  radius_.resize(mesh.triangle_count());
  // Each triangle's range of buckets (its bounding box), counted, then filled in triangle order.
  std::vector<std::array<int, 6>> range(mesh.triangle_count());
  bucket_start_.assign(static_cast<std::size_t>(extent_[0]) * extent_[1] * extent_[2] + 1, 0);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles()[t];
    // The bounding sphere about the centroid, its radius widened by a relative 1e-9 so that the
    // rejection in Closest never drops a triangle rounding could make the nearest.
    const Eigen::Vector3d centre = (x.col(tri[0]) + x.col(tri[1]) + x.col(tri[2])) / 3.0;
    double radius = 0.0;
    for (int c = 0; c < 3; ++c) radius = std::max(radius, (x.col(tri[c]) - centre).norm());
    centroid_.col(t) = centre;
    radius_[t] = radius * (1.0 + 1e-9) + 1e-12 * (centre.norm() + bucket_);
    Eigen::Vector3d lo = x.col(tri[0]), hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(Eigen::Vector3d(x.col(tri[c])));
      hi = hi.cwiseMax(Eigen::Vector3d(x.col(tri[c])));
    }
    for (int a = 0; a < 3; ++a) {
      range[t][a] = std::clamp(static_cast<int>(std::floor((lo(a) - origin_(a)) / bucket_)), 0,
                               extent_[a] - 1);
      range[t][3 + a] = std::clamp(static_cast<int>(std::floor((hi(a) - origin_(a)) / bucket_)), 0,
                                   extent_[a] - 1);
    }
    for (int i = range[t][0]; i <= range[t][3]; ++i)
      for (int j = range[t][1]; j <= range[t][4]; ++j)
        for (int k = range[t][2]; k <= range[t][5]; ++k) ++bucket_start_[Index(i, j, k) + 1];
  }
  for (std::size_t b = 1; b < bucket_start_.size(); ++b) bucket_start_[b] += bucket_start_[b - 1];
  bucket_triangles_.resize(bucket_start_.back());
  std::vector<int> fill(bucket_start_.begin(), bucket_start_.end() - 1);
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    for (int i = range[t][0]; i <= range[t][3]; ++i)
      for (int j = range[t][1]; j <= range[t][4]; ++j)
        for (int k = range[t][2]; k <= range[t][5]; ++k)
          bucket_triangles_[fill[Index(i, j, k)]++] = t;
  }
}

SurfacePoint SurfaceProjector::Closest(const Eigen::Vector3d& p) const {
  const Eigen::Matrix3Xd& x = mesh_.vertices();
  int c[3];
  for (int a = 0; a < 3; ++a) c[a] = static_cast<int>(std::floor((p(a) - origin_(a)) / bucket_));
  SurfacePoint best;
  best.distance = std::numeric_limits<double>::infinity();
  // Rings of buckets at Chebyshev distance r from the query's bucket. p lies in bucket c, so a
  // bucket of ring r + 1 or farther is at least r buckets plus p's clearance to the faces of its
  // own bucket from p: once the best point is that close, the search is complete. Beyond max_ring
  // every bucket of the mesh has been visited.
  const Eigen::Vector3d to_box =
      (p - origin_).cwiseMax(0.0) - (p - origin_).cwiseMin(0.0);  // |p - origin| per axis
  const int max_ring = std::max({extent_[0], extent_[1], extent_[2]}) +
                       static_cast<int>(to_box.maxCoeff() / bucket_) + 2;
  double clearance = std::numeric_limits<double>::infinity();  // p to its bucket's faces
  for (int a = 0; a < 3; ++a) {
    const double offset = p(a) - origin_(a) - c[a] * bucket_;  // in [0, bucket)
    clearance = std::min({clearance, offset, bucket_ - offset});
  }
  clearance = std::max(clearance, 0.0);
  for (int r = 0; r <= max_ring; ++r) {
    // The ring's buckets within the mesh's box (there are no others).
    for (int i = std::max(0, c[0] - r); i <= std::min(extent_[0] - 1, c[0] + r); ++i) {
      for (int j = std::max(0, c[1] - r); j <= std::min(extent_[1] - 1, c[1] + r); ++j) {
        const bool on_ring_ij = std::max(std::abs(i - c[0]), std::abs(j - c[1])) == r;
        for (int k = std::max(0, c[2] - r); k <= std::min(extent_[2] - 1, c[2] + r); ++k) {
          // Inside the ring only the two k faces, unless (i, j) is on it.
          if (!on_ring_ij && std::abs(k - c[2]) != r) continue;
          const std::size_t b = Index(i, j, k);
          for (int q = bucket_start_[b]; q < bucket_start_[b + 1]; ++q) {
            const int t = bucket_triangles_[q];
            // No point of the triangle is nearer than its bounding sphere.
            if ((p - centroid_.col(t)).norm() - radius_[t] >= best.distance) continue;
            const auto& tri = mesh_.triangles()[t];
            SurfacePoint s = ClosestPointOnTriangle(p, x.col(tri[0]), x.col(tri[1]), x.col(tri[2]));
            if (s.distance < best.distance) {
              s.triangle = t;
              best = s;
            }
          }
        }
      }
    }
    // Every bucket of ring r + 1 or farther lies outside the cube of rings 0..r about c, whose
    // faces are at least r buckets plus p's own clearance in its bucket from p.
    if (best.distance <= r * bucket_ + clearance) break;
  }
  return best;
}

}  // namespace ehd
