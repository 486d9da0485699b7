// Tangential relaxation of a triangulated surface whose vertices are not material points: a
// drop's (surface tension depends on the shape alone, so where the vertices sit on it is free).
//
// Carried along by the interpolated velocity, a drop's vertices drift along its surface: the
// parasitic currents of the discrete tension force never vanish, and the mesh distorts slowly.
// The cotangent mean-curvature force is not pointwise consistent on an irregular mesh, so the
// distortion feeds the parasitic flow and the shape error (docs/validation_3d_ehd.md, "Long
// runs"). The 2D drop re-spaces its markers along a spline (numerics.redistribute_markers); the
// 3D counterpart moves each vertex by `weight` times the tangential part of its umbrella vector
// (the mean of its neighbours minus itself), then back onto the local cubic fit of the surface
// as it was before the call (LocalSurfaceFit::Project), so the shape changes by the fit's
// O(h^4) while the mesh evens out (Jacobi sweeps, `iterations` of them on the same fit).
#pragma once

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

struct MeshRelaxationReport {
  double max_tangential_move = 0;  // largest vertex move of the call (the mesh's units)
  double max_normal_offset = 0;    // largest distance of a relaxed vertex from the fitted surface
                                   // before its projection (the O(h^2) error the fit removes)
};

// iterations >= 1, weight in (0, 1], bucket > 0 (about the grid spacing: the closest-patch
// search of the fit). Throws std::invalid_argument naming the bad argument.
MeshRelaxationReport RelaxMeshTangentially(TriangleMesh& mesh, int iterations, double weight,
                                           double bucket);

// The velocity a drop's vertices move with: the area-weighted mean velocity (the drop's
// translation) plus the normal part of each vertex's velocity relative to it,
//   V_i = u_mean + ((u_i - u_mean) . n_i) n_i,
// which moves the surface as u does (the kinematic condition needs u . n only) without
// carrying the vertices along it with the surface flow. velocity: one column per vertex
// (std::invalid_argument otherwise).
Eigen::Matrix3Xd DropVertexVelocity(const TriangleMesh& mesh, const Eigen::Matrix3Xd& velocity);

}  // namespace ehd
