// Removal of mesh-scale modes from the deformation of a triangulated membrane, the 3D
// counterpart of the marker chain's sawtooth filter (ib/sawtooth_filter.h; not in song2019).
//
// Why (docs/validation_3d.md, "Long runs"): modes a few edges long are almost invisible to the
// immersed boundary's kernel, which spreads a force pattern of that scale with a small gain and
// interpolates the velocity back with the same gain, so the membrane's restoring force hardly
// moves them, while the interpolation error of a vertex that tank-treads past the grid feeds them.
// On sphere_shear (2562 vertices, edge 0.6 h) the mesh-scale part of the deformation grows by
// about 6e-4 h rms per time unit until triangles are compressed to 0.6 of their rest length and
// the shape goes (D_xy 0.12 -> 0.07 by t = 150).
//
// The high-pass. On a chain the zigzag is the Fourier mode theta = pi of the second difference;
// on a surface mesh there are no Fourier modes, so the filter is built on the graph Laplacian of
// the mesh (the umbrella operator of Taubin 1995, uniform weights, topology only):
//   (A X)_i = X_i - (1/n_i) sum_{j ~ i} X_j,     n_i = valence of vertex i.
// A = I - D^-1 W is self-adjoint in the valence-weighted inner product, so its eigenvalues are
// real, in [0, mu_max], mu_max <= 2 (the three-sublattice pattern of a triangulation: ~1.5). The
// high-pass H = (A / mu_max)^p has the gain (mu / mu_max)^p on the eigenmode of eigenvalue mu: 1 on
// the highest mode, (mu / mu_max)^p on smooth modes (p = 8: ~1e-18 for an l = 2 shape mode of a
// 2562-vertex sphere). mu_max is found once by power iteration (the topology does not change).
//
// Relative to the reference. X <- X - H X (the chain filter's form) would also remove the rest
// mesh's own mesh-scale content: the icosphere's vertices are not a smooth function of the graph
// (valence-5 vertices), and filtering them moves vertices by up to 0.1 edge, a prestress the
// capsule's membrane then resists. So the filter removes the mesh-scale part of the deformation
// only: with M_i the local linear map from the reference one-ring of vertex i to the current one
// (least squares over the ring's edges plus the normal, scaled by the ring's mean edge length),
//   X_i <- X_i - [(H X)_i - M_i (H X_0)_i].
// H is linear and acts per coordinate, so H(M X_0) = M H X_0 for any affine map M: a rigid
// motion or a uniform scaling of the reference is left exactly as it is, and a smooth
// deformation (M_i varying over many edges) nearly so, while a mesh-scale mode of the
// deformation is removed.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

class MeshScaleFilter {
 public:
  // reference: the rest mesh (its topology and vertex positions); order p >= 1.
  // Throws std::invalid_argument otherwise.
  explicit MeshScaleFilter(const TriangleMesh& reference, int order = 8);
  int order() const { return order_; }
  double mu_max() const { return mu_max_; }
  // Removes the mesh-scale part of the deformation from X (3 x V, the vertices of a mesh with
  // the reference's topology) in place.
  void Apply(Eigen::Matrix3Xd& X);
  // Gain of the high-pass H on an eigenmode of A with eigenvalue mu.
  double HighPassGain(double mu) const { return std::pow(mu / mu_max_, order_); }
  // H X, and A X (the umbrella operator), for tests and diagnostics.
  void HighPass(const Eigen::Matrix3Xd& X, Eigen::Matrix3Xd& out) const;
  void ApplyLaplacian(const Eigen::Matrix3Xd& X, Eigen::Matrix3Xd& out) const;

 private:
  // Area-weighted vertex normals (unit) and the mean edge length around each vertex.
  void NormalsAndScales(const Eigen::Matrix3Xd& X, Eigen::Matrix3Xd& normals,
                        std::vector<double>& scales) const;

  int order_;
  std::vector<TriangleMesh::Triangle> triangles_;
  std::vector<int> offsets_, neighbors_;  // CSR adjacency
  std::vector<double> inverse_valence_;
  double mu_max_ = 0.0;
  Eigen::Matrix3Xd reference_, reference_high_, reference_normals_;
  std::vector<double> reference_scales_;
  std::vector<Eigen::Matrix3d> reference_inverse_;  // (sum d0 d0^T + n0 n0^T)^-1 per vertex
  mutable Eigen::Matrix3Xd work_, high_;
  Eigen::Matrix3Xd normals_;
  std::vector<double> scales_;
};

}  // namespace ehd
