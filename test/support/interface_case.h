// Interface cases: one manufactured example of include/ehd_capsule/reference/interface_examples*.h
// set up on a grid, ready to solve and to compare with its exact solution.
//
//   const InterfaceCase c("ellipse", 48, 1.0, 10.0);   // markers: example.DefaultMarkers(48)
//   FastIimSolver solver(c.grid, PoissonBoundaries{});
//   solver.Solve(c.curve, c.problem, g, phi);
//   EXPECT_LT(c.MaxError(phi), 1e-3);
//
// 2D: the example, its N x N grid, the curve through its markers (or through given ones), the
// sampled problem (Dirichlet sides unless given) and the exact phi at every grid point.
// 3D: the example, its N^3 grid, the mesh the example chooses for the grid spacing (or a given
// one), the node classification and the sampled problem; the exact phi depends on the side the
// solver classified each node on (MaxNodeError).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ehd_capsule/electric/fast_iim_solver_3d.h"
#include "ehd_capsule/electric/surface_classification_3d.h"
#include "ehd_capsule/reference/interface_examples.h"
#include "ehd_capsule/reference/interface_examples_3d.h"

namespace ehd::test {

struct InterfaceCase {
  // `markers` <= 0: the example's DefaultMarkers(n).
  InterfaceCase(const std::string& name, int n, double sigma_minus = 1.0, double sigma_plus = 1.0,
                int markers = 0, const PoissonBoundaries& bc = PoissonBoundaries{});
  // The example's curve replaced by one through `x` (moved or perturbed markers).
  InterfaceCase(const InterfaceExample& example, int n, const Eigen::Matrix2Xd& x,
                const PoissonBoundaries& bc = PoissonBoundaries{});

  InterfaceExample example;
  Grid2D grid;
  ClosedCurve curve;
  InterfaceProblem problem;
  std::vector<double> exact;  // phi at every grid point (region by curve.Contains)

  // max |phi - exact| over the grid points.
  double MaxError(const std::vector<double>& phi) const;
};

struct InterfaceCase3D {
  InterfaceCase3D(const std::string& name, int n, double sigma_minus = 1.0,
                  double sigma_plus = 1.0);
  // A modified example (other phi, faces) or a given mesh (moved, refined).
  InterfaceCase3D(const InterfaceExample3D& example, int n, const TriangleMesh& mesh);
  explicit InterfaceCase3D(const InterfaceExample3D& example, int n);

  InterfaceExample3D example;
  Grid3D grid;
  TriangleMesh mesh;
  SurfaceClassification3D sides;
  InterfaceProblem3D problem;

  // max |phi - exact| over the nodes, exact on the side the solver classified each node on.
  double MaxNodeError(const FastIimSolver3D& solver, const std::vector<double>& phi) const;
  // max |g - [phi_n]| at the vertices (the exact jump along the exact normal).
  double MaxJumpError(const std::vector<double>& g) const;
};

}  // namespace ehd::test
