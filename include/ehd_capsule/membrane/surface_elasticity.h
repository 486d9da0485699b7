// Finite-element elastic membrane on a triangulated surface (song2019 sec. 3.4.1-3.4.2, after
// Charrier, Shrivastava & Wu 1989): linear triangles, homogeneous deformation in each, nodal
// forces from the principle of virtual work (eqs. (133)-(136)).
//
// Formulation (equivalent to mapping both triangles to the plane z = 0, written without the
// rotations): each reference triangle x1 x2 x3 gets a local 2D frame (e1 along x2 - x1) in which
// its edges are the columns of D (2 x 2). The deformed edges X2 - X1, X3 - X1 (3D) are the
// columns of E (3 x 2), and F = E D^-1 (3 x 2) maps reference tangent vectors to deformed ones.
// Then C = F^T F (2 x 2) is the right Cauchy-Green tensor of eqs. (127)-(130), its eigenvalues
// are lambda_1^2, lambda_2^2 (eqs. (131)-(132)), and every law is a function of
//   I = tr C = lambda_1^2 + lambda_2^2   and   J = sqrt(det C) = lambda_1 lambda_2.
// The element energy is A_0 W(I, J) (A_0 the reference area: eq. (134) with zero thickness) and
// the nodal forces f_i = -A_0 dW/dX_i, with the first Piola-Kirchhoff stress
//   P = dW/dF = 2 W_I F + W_J J F C^-1   (3 x 2),   dW/dE = P D^-T,
// so f_2, f_3 are the columns of -A_0 P D^-T and f_1 = -(f_2 + f_3): eq. (136) evaluated in
// closed form. The forces of any element sum to zero and exert no torque.
//
// Laws (G_s the membrane shear modulus; Ca = mu k a / G_s as in the published 3D results):
//   neo-Hookean   W = (G_s/2) (I - 2 + 1/J^2 - 1)            (eq. (137))
//   zero-thickness W = (G_s/2) (I - 2 - 2 ln J + 2 (ln J)^2)    (eq. (138))
//   Skalak        W = (G_s/4) ((I - 2)^2 + 2 (I - 2) - 2 (J^2 - 1) + C (J^2 - 1)^2)   (eq. (139))
// with principal tensions (force per deformed length) tau_1 = (1/lambda_2) dW/dlambda_1:
//   neo-Hookean    tau_1 = G_s / (l1 l2) (l1^2 - 1 / (l1 l2)^2)
//   zero-thickness tau_1 = G_s / (l1 l2) (l1^2 - 1 + 2 ln(l1 l2))
//   Skalak         tau_1 = G_s (l1 / l2) (l1^2 - 1 + C l2^2 (l1^2 l2^2 - 1))
// (and 1 <-> 2). Departures from the text, which is not self-consistent here: (137)-(138) are
// printed with E_s/6 in front while (140)-(141) give the tension with E_s / (l1 l2); the two
// agree only for E_s = 3 G_s. The code uses G_s/2 (the incompressible-shell neo-Hookean law of
// Ramanujan & Pozrikidis 1998 and Barthes-Biesel), so (140)-(141) hold with E_s = G_s and all
// three laws share the small-strain tension G_s (4 e_1 + 2 e_2) (Skalak with C = 1). Eq. (139)
// lost its squares in transcription ("(l1 + l2 - 2)^2 + 2 (l1 + l2 - 2)^2"): the Skalak law is
// written here in its standard form in I_1 = l1^2 + l2^2 - 2 and I_2 = l1^2 l2^2 - 1, and the
// printed tensions (142)-(143) miss the "- 1" of I_2 ("C (l1 l2)^2 (l1^2 l2^2)"): derived above.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

enum class SurfaceLaw { kNeoHookean, kZeroThickness, kSkalak };
const char* ToString(SurfaceLaw law);

struct SurfaceLawParameters {
  SurfaceLaw law = SurfaceLaw::kNeoHookean;
  double shear_modulus = 1.0;  // G_s
  double area_dilation = 1.0;  // C (Skalak only; song2019 uses C = 15 for the red cell)
};

// W(I, J) and its partial derivatives W_I, W_J for the law.
struct StrainEnergyDensity {
  double w, w_i, w_j;
};
StrainEnergyDensity EvaluateSurfaceLaw(const SurfaceLawParameters& p, double i, double j);
// Principal tensions (tau_1, tau_2) per unit deformed length at stretches (l1, l2).
Eigen::Vector2d PrincipalTensions(const SurfaceLawParameters& p, double l1, double l2);

class SurfaceElasticity {
 public:
  // The reference shape: the mesh's current vertex positions. Throws std::invalid_argument for
  // a non-positive modulus, C <= 0 for Skalak, or a degenerate reference triangle (naming it).
  SurfaceElasticity(const SurfaceLawParameters& p, const TriangleMesh& reference);

  // Nodal forces (3 x V, force per vertex, not density) of the deformed vertex positions X
  // (same topology as the reference); returns the total elastic energy. Throws
  // std::runtime_error naming the triangle if one has collapsed (J^2 <= 1e-12).
  double ComputeForces(const Eigen::Matrix3Xd& X, Eigen::Matrix3Xd& forces) const;
  // Energy alone.
  double Energy(const Eigen::Matrix3Xd& X) const;
  // Principal stretches (l1 >= l2) of each triangle.
  std::vector<Eigen::Vector2d> Stretches(const Eigen::Matrix3Xd& X) const;
  // Mean principal tension (tau_1 + tau_2) / 2 at each vertex: each triangle's, from its
  // stretches, averaged over the vertex's triangles with their deformed areas as weights (what
  // the node colours the surface by; no bending part).
  std::vector<double> VertexMeanTension(const Eigen::Matrix3Xd& X) const;

  const SurfaceLawParameters& parameters() const { return params_; }
  double reference_area() const { return reference_area_; }
  std::string Describe() const;

 private:
  SurfaceLawParameters params_;
  std::vector<TriangleMesh::Triangle> triangles_;
  std::vector<Eigen::Matrix2d> d_inverse_;  // D^-1 per triangle
  std::vector<double> area0_;
  double reference_area_ = 0;
};

}  // namespace ehd
