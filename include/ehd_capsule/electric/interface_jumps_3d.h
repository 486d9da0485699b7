// The 3D immersed interface corrections of the 7-point Laplacian (issue #13; song2019 sec. 2.4-2.5
// in 3D): the jump of the two smooth extensions u^+_ext - u^-_ext near a closed surface, expanded
// about the foot point X* of a grid node (the 3D form of jump_relations.h), and the right-hand
// side corrections it gives at the irregular nodes.
//
// In normal coordinates (xi along the outward normal, the surface coordinates on the parallel
// surfaces) the Laplacian at xi = 0 is u_xixi + (kappa1 + kappa2) u_xi + Delta_s u, so with
// [u] = w, [u_n] = g and [Delta u] = [f] on the surface:
//   J(x) = w + g d + 1/2 [u_xixi] d^2 + O(d^3),  [u_xixi] = [f] - (kappa1 + kappa2) g - Delta_s w,
// d the signed distance of x from the surface (> 0 outside), everything at X*. In 2D (one
// curvature, Delta_s = d_ss) this is jump_relations.h's second-order part; the 2D cubic term is
// not carried over (it needs the derivatives of the shape operator along the surface): J is
// O(h^3), the local truncation error O(h) at the irregular nodes, and the solution second order.
//
// Corrections: at a node i with a 7-point neighbour j on the other side, the stencil applied to
// the piecewise values sees u(j) - u^{s_i}_ext(j) = +J(x_j) (j outside) or -J(x_j) (j inside),
// so the discrete equation at i is L u = f_i + sum_j (+-J(x_j)) / h^2.
#pragma once

#include <vector>

#include "ehd_capsule/electric/surface_classification_3d.h"
#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/geometry/local_surface_fit.h"

namespace ehd {

// Jump data per vertex of the interface mesh.
struct SurfaceJumps3D {
  std::vector<double> w;       // [u] = u^+ - u^-
  std::vector<double> g;       // [du/dn], n outward
  std::vector<double> f_jump;  // [f] = [Laplacian u]
};

// J(x) from the local reconstruction (the foot point, curvature and the fitted jump data).
double JumpExtension(const LocalSurfaceFit& fit, const SurfaceJumps3D& jumps,
                     const Eigen::Vector3d& x);

// Adds the corrections sum_j (+-J(x_j)) / h^2 to rhs at every node with a neighbour on the other
// side (rhs: grid.size() values). Throws std::invalid_argument for data of the wrong length.
void AddJumpCorrections(const Grid3D& grid, const SurfaceClassification3D& sides,
                        const LocalSurfaceFit& fit, const SurfaceJumps3D& jumps,
                        std::vector<double>& rhs);

}  // namespace ehd
