// Manufactured 3D interface problems with exact solutions, shared by the 3D fast IIM tests and
// `ehd_sim iim --dim 3` (issue #13's targets): on the box [-1, 1]^3, with the exact phi^- inside
// and phi^+ outside, their gradients and the sources f^+- = sigma^+- Laplacian(phi^+-); the jumps
// at the vertices follow from the exact solution with the exact surface normal:
// w = phi^+ - phi^-, v = sigma^+ grad phi^+ . n - sigma^- grad phi^- . n.
//
//   "sphere_field"  sphere r = 1/2 in the uniform field E = z_hat (the leaky-dielectric
//                   conduction problem): phi^- = -A z, phi^+ = -z + B R^3 z / r^3,
//                   A = 3 s^+ / (s^- + 2 s^+), B = (s^- - s^+) / (s^- + 2 s^+); f = 0, w = v = 0;
//                   Neumann on the x and y faces, Dirichlet on z (song2019 ch. 6's box).
//   "sphere"        sphere r = 1/2: phi^- = exp(x) cos(y) + z^2, phi^+ = x y + z + (x^2 - z^2)/2
//                   + 0.05/|x - c|, c = (0.1, -0.05, 0.02) inside (f^- = 2 sigma^-, f^+ = 0);
//                   Dirichlet faces.
//   "ellipsoid"     semi-axes 0.6, 0.45, 0.35, the same phi.
//   "biconcave"     the red-cell surface (geometry/triangle_mesh.h's BiconcaveMesh, a = 0.45:
//                   diameter 1.25, dimple 0.13 thick): non-convex; the same phi with c =
//                   (0.38, 0, 0.15), in the rim.
// The mesh level for a grid of spacing h is the coarsest whose longest edge is <= 1.5 h.
// Any sigma^-, sigma^+ > 0.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "ehd_capsule/electric/fast_iim_solver_3d.h"
#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

struct InterfaceExample3D {
  std::string name, description;
  double sigma_minus = 1, sigma_plus = 1;
  PoissonBoundaries3D boundaries;
  std::function<double(const Eigen::Vector3d&)> phi_minus, phi_plus;
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> grad_minus, grad_plus;
  double laplacian_minus = 0, laplacian_plus = 0;  // constant Laplacians of phi^-, phi^+
  double inside_volume = 0;  // exact volume of the inside (the flux balance's source integral)
  // The exact unit outward normal at a point of the surface.
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> normal;
  std::function<TriangleMesh(int level)> mesh;

  Grid3D MakeGrid(int n) const { return Grid3D{n, n, n, 2.0 / n, -1, -1, -1}; }
  TriangleMesh MeshFor(double h) const;  // coarsest level (<= 6) with max edge <= 1.5 h
};

// Throws std::invalid_argument for an unknown name (the message lists the names) or sigma <= 0.
InterfaceExample3D MakeInterfaceExample3D(const std::string& name, double sigma_minus = 1,
                                          double sigma_plus = 1);

// The problem for a grid and a mesh: f at the nodes by the mesh's classification, [f/sigma] at the
// vertices, the exact integral of f^-/sigma^- over the inside, w, v from the exact solution, face
// data from phi^+.
InterfaceProblem3D SampleInterfaceProblem3D(const InterfaceExample3D& e, const Grid3D& grid,
                                            const TriangleMesh& mesh,
                                            const SurfaceClassification3D& sides);

// The Maxwell traction jump [M_E].n (eq. (149)-(150) in 3D) on a leaky-dielectric sphere of
// the given radius centred at the origin, in free space, in the uniform field E_inf = (0, 0, -e),
// at the surface point p: phi^- = A e z, phi^+ = e z - B e R^3 z / r^3 with
// A = 3 sigma+ / (sigma- + 2 sigma+), B = (sigma- - sigma+) / (sigma- + 2 sigma+). The reference
// the 3D electric tests and `ehd_sim eforce --dim 3` compare with.
Eigen::Vector3d FreeSpaceSphereTraction(const Eigen::Vector3d& p, double radius, double e,
                                        double sigma_minus, double sigma_plus, double eps_minus,
                                        double eps_plus);

}  // namespace ehd
