// Helfrich bending of a triangulated membrane (song2019 sec. 3.4.3, eqs. (144)-(145)) with
// spontaneous curvature c0:
//   E_b = (E_B / 2) int (2H - c0)^2 dA                                             (144)
// with H the mean curvature (H = 1/R on a sphere, outward normal n). Its first variation under
// a normal displacement psi n (delta dA = 2 H psi dA, delta H = -(1/2) Delta psi - (2H^2 - K) psi)
// gives the force density on the membrane
//   f_b = E_B [ 2 Delta_LB H + (2H - c0)(2H^2 - 2K + c0 H) ] n.
// Departure from the text: eq. (145) writes (E_B/2)[(2 kappa + c0)(2 kappa^2 - 2 kappa_g -
// c0 kappa) + 2 Delta kappa] n, which is -1/2 times this with kappa = -H (mean curvature of
// the opposite sign convention): its sign follows from the convention, but the factor 1/2 is
// not the variation of (144). The code uses the variation (tested against the energy).
// Check on a sphere of radius R: E_b = 2 pi E_B (2 - c0 R)^2, so f_b.n = -(dE_b/dR)/(4 pi R^2) =
// E_B c0 (2 - c0 R)/R^2; zero for c0 = 0.
//
// Discretisation (Meyer et al. 2003, geometry/triangle_mesh.h): H_i from the cotangent mean
// curvature normal, K_i by the angle deficit, Delta_LB H by the cotangent Laplacian of the H_i,
// n_i the area-weighted vertex normal; the force per vertex is f_b(x_i) A_i with the mixed
// Voronoi area A_i. This is the pointwise formula on discrete operators, not the exact gradient
// of a discrete energy: it converges to it (tests), but the forces of a closed surface sum to
// zero only up to the discretisation error.
#pragma once

#include <Eigen/Core>
#include <string>

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

struct HelfrichParameters {
  double bending_modulus = 1.0;        // E_B
  double spontaneous_curvature = 0.0;  // c0 (in 1/length; 0: no internal/external asymmetry)
};

class HelfrichBending {
 public:
  explicit HelfrichBending(const HelfrichParameters& p);  // throws for E_B < 0 or non-finite c0
  // Force per vertex (3 x V) at the mesh's current vertex positions; returns the discrete energy
  // (E_B / 2) sum A_i (2 H_i - c0)^2.
  double ComputeForces(const TriangleMesh& mesh, Eigen::Matrix3Xd& forces) const;
  double Energy(const TriangleMesh& mesh) const;
  const HelfrichParameters& parameters() const { return params_; }
  std::string Describe() const;

 private:
  HelfrichParameters params_;
};

}  // namespace ehd
