// The radial parametrisation of a closed surface that is star-shaped about its centroid, built from
// the mesh alone (any triangulation: no particular mesh generator or vertex order):
//
//   x(u) = c + S r(u) u,   u on the unit sphere,   c the centroid of the enclosed volume,
//
// S = M^(1/2), M the second moment of the enclosed volume about c divided by the volume (an
// ellipsoid's u is then exactly the unit sphere it is the linear image of, and a flat red cell's
// directions spread over the sphere instead of crowding into its rim),
// so functions on the surface are functions of the direction u, and the real spherical harmonics
// Y_lm(u) (spherical_harmonics.h) are a smooth basis on it (the 3D fast IIM's basis of [phi_n] at a
// much more conducting inside, electric/fast_iim_solver_3d.h). The parametrisation is one-to-one
// exactly when every triangle is seen from its front from c (S maps rays from c to rays from c),
// i.e. det[x_a - c, x_b - c, x_c - c]
// has the sign of the enclosed volume for every triangle (a, b, c): the radial projection on the
// unit sphere is then an orientation-preserving covering of degree 1, a bijection. A triangle seen
// edge-on or from behind means the surface is not star-shaped about c (a fold of the projection):
// folded_triangle names the first one.
//
// Surface integrals to high order on any such mesh (RadialSurfaceWeights): with
// dA = J dOmega, J = |det S| |S^-1 r (r u - grad r)| (grad on the unit sphere),
//   int_S f dA = int_{S^2} f J dOmega ~ sum_i w_i J_i f_i,
// where w are the solid angles of the vertices (the third areas of the mesh projected on the unit
// sphere), corrected by the least change (in the metric of the solid angles) that makes them
// exact for every Y_lm, l <= L (sum_i w_i Y_lm(u_i) = sqrt(4 pi) delta_l0), and grad r is that of
// r's least-squares expansion in the same Y_lm (central differences of the expansion along two
// tangents, 1e-5 rad). For a smooth r and f the error falls spectrally with L, against h^2 for the
// third-area rule (measured in docs/electric_solver_3d.md; it does not converge on the red cell).
// Not in a reference. The solver uses it only on meshes not of icosphere connectivity; an
// icosphere mesh keeps the Richardson extrapolation over its nested submeshes.
#pragma once

#include <Eigen/Core>

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

struct RadialParametrisation {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();     // centroid of the enclosed volume
  Eigen::Matrix3d shape = Eigen::Matrix3d::Identity();  // S = M^(1/2)
  Eigen::Matrix3Xd direction;   // u of each vertex: S^-1 (x - center), normalised
  Eigen::VectorXd radius;       // r of each vertex: |S^-1 (x - center)|
  Eigen::VectorXd solid_angle;  // vertex third areas of the mesh projected on the unit sphere
  // The first triangle seen edge-on or from behind from center (not star-shaped); -1: none.
  int folded_triangle = -1;
  bool star_shaped() const { return folded_triangle < 0; }
};

// Throws std::invalid_argument for a mesh without triangles or with zero enclosed volume.
RadialParametrisation MakeRadialParametrisation(const TriangleMesh& mesh);

// Vertex weights for surface integrals, exact on the unit sphere for the harmonics of degree
// <= degree (the file comment). Throws std::invalid_argument for a parametrisation that is not
// star-shaped, degree < 0, or fewer vertices than (degree + 1)^2.
Eigen::VectorXd RadialSurfaceWeights(const RadialParametrisation& p, int degree);

}  // namespace ehd
