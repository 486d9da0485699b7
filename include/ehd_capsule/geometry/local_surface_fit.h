// Local polynomial reconstruction of a triangulated surface and of functions on it, for the 3D
// immersed interface corrections (issue #13), which need the interface position and the jump
// data at the foot point of a grid node to O(h^3) or better: the flat triangles and barycentric
// interpolation are only O(h^2), which would leave an O(1) local error at the irregular nodes and
// a first-order potential.
//
// At each vertex v, in the frame (t1, t2, n) of its area-weighted normal, the surface is the graph
// z = c1 u + c2 w + c3 u^2 + c4 u w + c5 w^2 [+ c6 u^3 + c7 u^2 w + c8 u w^2 + c9 w^3] fitted
// through v by weighted least squares (weights 1/|x_j - x_v|^2) over the vertices within `rings`
// edge rings (as FitCurvatures), and a vertex function F by F(u, w) = a0 + a1 u + a2 w + a3 u^2 +
// a4 u w + a5 w^2 [+ a6 u^3 + a7 u^2 w + a8 u w^2 + a9 w^3] over the same vertices plus v itself
// (degree 3, the default: value O(h^4), gradient O(h^3), Hessian O(h^2), which the d^3 term of the
// jump expansion needs on meshes coarser than the grid; degree 2: one order less each).
// Project(x) takes the patch of the nearest vertex of the nearest triangle and finds the foot
// point on its graph by Newton's method on (x - X(u, w)) . X_u = (x - X) . X_w = 0.
// The surface Laplacian of a fitted F at a foot point is that of the graph,
//   Delta_s F = g^ij F_ij - (g^ij h_ij) (grad h . grad F) / (1 + |grad h|^2)
// (g^ij the inverse metric, the second term the Christoffel symbols of a graph): at the foot
// point itself, not at the patch vertex, whose value would be O(h) off (an O(h d^2) error of the
// jump expansion, which the normal-derivative fit sees at d = 3 h).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "ehd_capsule/geometry/surface_projection.h"
#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

struct SurfacePatch {
  Eigen::Vector3d origin, t1, t2, n;  // the vertex and its frame
  std::array<double, 9> height{};     // c1..c9 (c6..c9 zero for degree 2)
  double curvature_sum = 0;           // kappa1 + kappa2 at the vertex (> 0 on a sphere)
  double gaussian_curvature = 0;      // kappa1 kappa2 at the vertex
  std::vector<int> support;           // the vertex first, then its neighbours
  Eigen::MatrixXd function_fit;       // 10 x |support|: coefficients a = function_fit * values
};

struct PatchFoot {
  int vertex = -1;                // the patch used
  double u = 0, w = 0;            // tangent coordinates of the foot point in that patch
  Eigen::Vector3d point;          // the foot point on the fitted surface
  Eigen::Vector3d normal;         // unit outward normal there
  double signed_distance = 0;     // (x - point) . normal: > 0 outside
  double curvature_sum = 0;       // kappa1 + kappa2 of the fitted graph at the foot point
  double gaussian_curvature = 0;  // kappa1 kappa2 there
};

class LocalSurfaceFit {
 public:
  // rings in [1, 4]; 2 is the default (the cubic function fit has 10 unknowns; two rings hold
  // about 18 vertices). degree 2 or 3. bucket: the cell size of the closest-triangle search
  // (about the grid spacing). Throws std::invalid_argument for a bad ring count or degree and
  // std::runtime_error for a vertex with too few neighbours.
  // threads: OpenMP threads for the per-vertex fits (<= 0: the OpenMP default; the result does
  // not depend on it).
  LocalSurfaceFit(const TriangleMesh& mesh, double bucket, int rings = 2, int degree = 3,
                  int threads = 0);
  // The larger principal curvature magnitude at vertex v.
  double MaxCurvature(int v) const;

  PatchFoot Project(const Eigen::Vector3d& x) const;

  // Coefficients a0..a9 of F in the patch of vertex v (values: one per mesh vertex).
  std::array<double, 10> FitFunction(int v, const std::vector<double>& values) const;
  // F, and its surface Laplacian, at a foot point.
  double Value(const PatchFoot& foot, const std::vector<double>& values) const;
  double SurfaceLaplacian(const PatchFoot& foot, const std::vector<double>& values) const;

  // The same as weights over patch(foot.vertex).support (F = sum_j weight_j values[support_j]):
  // for operators that are applied many times to changing values (the Schur unknown of the 3D
  // immersed interface method).
  std::vector<double> ValueWeights(const PatchFoot& foot) const;
  std::vector<double> SurfaceLaplacianWeights(const PatchFoot& foot) const;

  const SurfacePatch& patch(int v) const { return patches_[v]; }
  int vertex_count() const { return static_cast<int>(patches_.size()); }

 private:
  static constexpr int kSmallSupport = 32;
  static void FitPatch(const TriangleMesh& mesh, const Eigen::Matrix3Xd& normal, int v, int rings,
                       int height_terms, int function_terms, std::vector<int>& mark,
                       SurfacePatch& p);
  TriangleMesh mesh_;
  SurfaceProjector projector_;
  std::vector<SurfacePatch> patches_;
};

}  // namespace ehd
