// Real spherical harmonics and the icosphere parametrisation of a triangulated surface: a smooth
// basis for functions on a closed genus-0 surface whose mesh was built by subdividing the
// icosahedron (IcosphereMesh and the shapes mapped from it: every 3D surface of this package).
//
// The 3D fast IIM (electric/fast_iim_solver_3d.h) represents [phi_n] in this basis for a much more
// conducting inside, where the vertex values have near-null modes on the grid scale: on the
// icosphere parametrisation for a mesh of icosphere connectivity, else at the directions of the
// radial parametrisation (radial_parametrisation.h: any triangulation of a star-shaped surface).
#pragma once

#include <Eigen/Core>

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

// The number of real spherical harmonics of degree <= max_degree: (max_degree + 1)^2.
inline int SphericalHarmonicCount(int max_degree) { return (max_degree + 1) * (max_degree + 1); }

// The real orthonormal spherical harmonics Y_lm, l <= max_degree, at unit directions (3 x n;
// normalised on entry is not required: each column is normalised): an n x (max_degree + 1)^2
// matrix, columns ordered by m = 0..L, then l = m..L (cos then sin for m > 0), with
// integral over the unit sphere of Y_a Y_b = delta_ab. Associated Legendre functions by the
// stable fully normalised recurrence (no factorials). Throws std::invalid_argument for a negative
// degree or a zero direction.
Eigen::MatrixXd RealSphericalHarmonics(const Eigen::Matrix3Xd& directions, int max_degree);

// The subdivision level k if the mesh's triangle list is exactly that of IcosphereMesh(k) (same
// vertex indices in the same order, as every shape mapped from it keeps), else -1. Such a mesh's
// first 10 * 4^j + 2 vertices, with IcosphereMesh(j)'s triangles, are its level-j submesh.
int IcosphereLevel(const TriangleMesh& mesh);

// The level-j submesh of a mesh of icosphere connectivity (j <= IcosphereLevel(mesh)): its first
// 10 * 4^j + 2 vertices at their current positions with IcosphereMesh(j)'s triangles. Throws
// std::invalid_argument if the mesh is not of icosphere connectivity or j is out of range.
TriangleMesh IcosphereSubmesh(const TriangleMesh& mesh, int level);

}  // namespace ehd
