// Closest points on triangles and on a bucketed triangulated surface; see surface_projection.h.
#include "ehd_capsule/geometry/surface_projection.h"

#include <algorithm>
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
  for (int a = 0; a < 3; ++a) extent_[a] = static_cast<int>(span(a) / bucket) + 1;
  centroid_.resize(3, mesh.triangle_count());
  radius_.resize(mesh.triangle_count());
  for (int t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles()[t];
    // The bounding sphere about the centroid, its radius widened by a relative 1e-9 so that the
    // rejection in Closest never drops a triangle rounding could make the nearest.
    const Eigen::Vector3d centre = (x.col(tri[0]) + x.col(tri[1]) + x.col(tri[2])) / 3.0;
    double radius = 0.0;
    for (int c = 0; c < 3; ++c) radius = std::max(radius, (x.col(tri[c]) - centre).norm());
    centroid_.col(t) = centre;
    radius_[t] = radius * (1.0 + 1e-9) + 1e-12 * (centre.norm() + bucket);
    Eigen::Vector3d lo = x.col(tri[0]), hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(Eigen::Vector3d(x.col(tri[c])));
      hi = hi.cwiseMax(Eigen::Vector3d(x.col(tri[c])));
    }
    int l[3], h[3];
    for (int a = 0; a < 3; ++a) {
      l[a] = static_cast<int>(std::floor((lo(a) - origin_(a)) / bucket));
      h[a] = static_cast<int>(std::floor((hi(a) - origin_(a)) / bucket));
    }
    for (int i = l[0]; i <= h[0]; ++i)
      for (int j = l[1]; j <= h[1]; ++j)
        for (int k = l[2]; k <= h[2]; ++k) buckets_[Key(i, j, k)].push_back(t);
  }
}

long SurfaceProjector::Key(int i, int j, int k) const {
  // Buckets beyond the mesh's box exist only in queries: shift into a non-negative range.
  const long s = 1 << 20;
  return ((static_cast<long>(i) + s) * (2 * s) + (j + s)) * (2 * s) + (k + s);
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
    for (int i = c[0] - r; i <= c[0] + r; ++i) {
      for (int j = c[1] - r; j <= c[1] + r; ++j) {
        for (int k = c[2] - r; k <= c[2] + r; ++k) {
          if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != r) continue;
          const auto it = buckets_.find(Key(i, j, k));
          if (it == buckets_.end()) continue;
          for (int t : it->second) {
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
