// Local Cauchy problem of the correction function method (CFM), song2019 sec. 2.3.3,
// after Marques, Nave & Petitpas (J. Comput. Phys. 230, 2011).
//
// The correction function D = phi+ - phi- solves, near the interface Sigma,
//   Laplace(D) = f_D  in the patch Omega_Sigma^ij,   D = a  and  dD/dn = b  on Sigma,
// (song2019 eqs. (11)-(13)), an ill-posed Cauchy problem that is solved in the least-squares
// sense by minimising over a finite-dimensional space of D (song2019 eq. (18))
//   J_p = l^3 int_patch (Laplace D - f_D)^2 dV + c_p int_{Sigma cap patch} (D - a)^2 dS
//         + c_p l^2 int_{Sigma cap patch} (dD/dn - b)^2 dS,
// l = shortest side of the patch, c_p the penalty coefficient. The three terms have the same
// units (D^2 length), so the minimiser does not depend on the patch size.
//
// The patch is a rectangle in a rotated (p, q) frame (sec. 2.3.2); local coordinates
// xi = (x - c).e_p / half_p, eta = (x - c).e_q / half_q in [-1, 1]^2. Two bases:
//  - kBicubic: the 16 tensor products P_a(xi) P_b(eta), a, b = 0..3 (Legendre polynomials), i.e.
//    the span of Marques et al.'s bicubic Hermite elements. It holds every polynomial of degree
//    <= 3 in (x, y), so such a D is recovered exactly, and a smooth D to O(h^4).
//  - kModifiedBilinear: song2019 sec. 2.3.4, the bilinear element N_1..N_4 plus
//    N_5 with Laplace(N_5) = 1, so that the fifth coefficient is the mean Laplacian (O(h^2)-ish D).
//    Departure from the text: the printed N_5 = (1/4)((1-xi^2) + (1-eta^2)) has Laplacian
//    -(1/half_p^2 + 1/half_q^2)/2 in x-y, not 1, and the printed Laplacians of N_1..N_4 are not
//    zero although the text then says they vanish; we use
//    N_5 = -(1/4)(half_p^2 (1 - xi^2) + half_q^2 (1 - eta^2)), whose Laplacian is exactly 1 and
//    which vanishes at the four corners.
// The minimiser solves the weighted linear least-squares system by column-pivoted Householder QR
// (not the normal equations (26) of the text, which square the condition number of an already
// ill-conditioned Cauchy problem). All storage is fixed-size: no allocation per patch.
#pragma once

#include <Eigen/Core>
#include <Eigen/QR>
#include <array>

namespace ehd {

enum class CfmBasis { kBicubic, kModifiedBilinear };

// A rectangle with sides along the orthonormal axes e_p, e_q (counter-clockwise pair).
struct CfmPatch {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  Eigen::Vector2d axis_p = Eigen::Vector2d::UnitX();
  Eigen::Vector2d axis_q = Eigen::Vector2d::UnitY();
  double half_p = 0.0;
  double half_q = 0.0;

  // Local coordinates (xi, eta) in [-1, 1]^2 inside the patch.
  Eigen::Vector2d Local(const Eigen::Vector2d& x) const {
    const Eigen::Vector2d d = x - center;
    return {d.dot(axis_p) / half_p, d.dot(axis_q) / half_q};
  }
  Eigen::Vector2d Global(const Eigen::Vector2d& local) const {
    return center + local.x() * half_p * axis_p + local.y() * half_q * axis_q;
  }
};

// Interface data at one quadrature point of Sigma cap patch: position, unit normal (out of
// Omega^-), quadrature weight (arc length), a = [phi] and b = [d phi/dn] there.
struct CfmInterfaceSample {
  Eigen::Vector2d position;
  Eigen::Vector2d normal;
  double weight = 0.0;
  double jump_value = 0.0;
  double jump_normal = 0.0;
};

class CfmLocalCauchy {
 public:
  static constexpr int kMaxBasis = 16;
  static constexpr int kAreaPoints = 16;  // 4 x 4 Gauss-Legendre (song2019 sec. 2.3.3)
  static constexpr int kMaxInterfaceSamples = 24;
  static constexpr int kMaxRows = kAreaPoints + 2 * kMaxInterfaceSamples;

  // penalty = c_p of eq. (18), > 0.
  explicit CfmLocalCauchy(CfmBasis basis = CfmBasis::kBicubic, double penalty = 10.0);

  CfmBasis basis() const { return basis_; }
  int basis_size() const { return basis_size_; }
  double penalty() const { return penalty_; }

  // The 16 area quadrature points of a patch (where the caller evaluates f_D = [f]/sigma).
  static std::array<Eigen::Vector2d, kAreaPoints> AreaPoints(const CfmPatch& patch);

  // Minimises J_p over the basis for one patch. f_jump holds f_D at AreaPoints(patch);
  // samples/n_samples the interface quadrature (1..kMaxInterfaceSamples). Returns false (and
  // leaves D = 0) if the patch is degenerate or the system has lower rank than the basis.
  bool Solve(const CfmPatch& patch, const double* f_jump, const CfmInterfaceSample* samples,
             int n_samples);

  // The fitted correction function and its gradient at a point (inside or near the patch).
  double Value(const Eigen::Vector2d& x) const;
  Eigen::Vector2d Gradient(const Eigen::Vector2d& x) const;
  double Laplacian(const Eigen::Vector2d& x) const;

 private:
  // Basis values, p/q derivatives and Laplacians (x-y units) at local point (xi, eta).
  void EvaluateBasis(double xi, double eta, double* value, double* d_p, double* d_q,
                     double* laplacian) const;

  using RowMatrix =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxRows, kMaxBasis>;
  using RowVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxRows, 1>;
  using Coefficients = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxBasis, 1>;

  CfmBasis basis_;
  int basis_size_;
  double penalty_;
  CfmPatch patch_;
  RowMatrix rows_;
  RowVector rhs_;
  Coefficients coefficients_;
  Eigen::ColPivHouseholderQR<RowMatrix> qr_;
};

}  // namespace ehd
