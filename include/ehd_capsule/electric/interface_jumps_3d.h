// The 3D immersed interface corrections of the 7-point Laplacian (issue #13; song2019 sec. 2.4-2.5
// in 3D): the jump of the two smooth extensions u^+_ext - u^-_ext near a closed surface, expanded
// about the foot point X* of a grid node (the 3D form of jump_relations.h), and the right-hand
// side corrections it gives at the irregular nodes.
//
// In normal coordinates (xi along the outward normal; B the shape operator, H = kappa1 + kappa2,
// |B|^2 = kappa1^2 + kappa2^2 = H^2 - 2K) the Laplacian near the surface is
//   u_xixi + H(xi) u_xi + Delta_{S_xi} u,   H(xi) = sum kappa_i / (1 + kappa_i xi),
// and, from the metric of the parallel surfaces g_xi = g + 2 xi b + O(xi^2) and Codazzi's
// div_s B = grad_s H,
//   d/dxi (Delta_{S_xi} u) at xi = 0 = Delta_s u_xi - 2 B : Hess_s u - grad_s H . grad_s u.
// So with [u] = w, [u_n] = g, [Laplacian u] = [f], [d_xi f] on the surface:
//   J(x) = w + g d + [u_xixi] d^2 / 2 + [u_xixixi] d^3 / 6 + O(d^4),
//   [u_xixi]   = [f] - H g - Delta_s w,
//   [u_xixixi] = [d_xi f] - H [u_xixi] + |B|^2 g - Delta_s g + 2 B : Hess_s w + grad_s H . grad_s
//   w,
// d the signed distance of x (> 0 outside), everything at X*. In 2D (B = kappa, Delta_s = d_ss)
// these are jump_relations.h's relations. J is linear in the vertex values of w and g through the
// local quadratic fits of geometry/local_surface_fit.h (value at the foot point; Laplacian,
// Hessian and gradient at the patch vertex, which is enough for the d^2 and d^3 terms), so it is
// stored as rows (JumpStencil3D) for operators applied many times.
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
  std::vector<double> w;           // [u] = u^+ - u^-
  std::vector<double> g;           // [du/dn], n outward
  std::vector<double> f_jump;      // [f] = [Laplacian u]
  std::vector<double> f_dxi_jump;  // [d f / dn]; empty means 0
};

// J(x) = sum_q (w_row_q w[support_q] + g_row_q g[support_q]) + f_coefficient [f](vertex)
//        + f_dxi_coefficient [d_xi f](vertex), support = fit.patch(vertex).support.
struct JumpStencil3D {
  int vertex = -1;
  double distance = 0;
  std::vector<double> w_row, g_row;
  double f_coefficient = 0, f_dxi_coefficient = 0;
};
JumpStencil3D MakeJumpStencil(const LocalSurfaceFit& fit, const Eigen::Vector3d& x);
double ApplyJumpStencil(const LocalSurfaceFit& fit, const JumpStencil3D& stencil,
                        const SurfaceJumps3D& jumps);

// J(x) (MakeJumpStencil then ApplyJumpStencil).
double JumpExtension(const LocalSurfaceFit& fit, const SurfaceJumps3D& jumps,
                     const Eigen::Vector3d& x);

// Adds the corrections sum_j (+-J(x_j)) / h^2 to rhs at every node with a neighbour on the other
// side (rhs: grid.size() values). Throws std::invalid_argument for data of the wrong length.
void AddJumpCorrections(const Grid3D& grid, const SurfaceClassification3D& sides,
                        const LocalSurfaceFit& fit, const SurfaceJumps3D& jumps,
                        std::vector<double>& rhs);

}  // namespace ehd
