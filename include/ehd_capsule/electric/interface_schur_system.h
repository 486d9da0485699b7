// The Schur system of the fast immersed interface method, one solver for the curve (2D,
// fast_iim_solver.h) and the surface (3D, fast_iim_solver_3d.h): song2019 eq. (57), (59)-(61).
//
// G = [phi_n] lives at the n interface points (the markers of a curve, the vertices of a
// surface). The scaled flux residual R(G) = phi_n^-(G) + (sigma^+/[sigma]) G - v/[sigma] at the
// points is affine in G; each dimension's solver gives it as a callback (one potential solve per
// call). GMRES solves R(G) = 0 in a set of unknowns (InterfaceUnknowns): G at every point, or a
// reduced basis G = B x whose residual is tested against the same basis (Galerkin: the Fourier
// series in arc length of the curve, the spherical harmonics of the surface), the mat-vec being
// R(G) - R(0).
//
// Mean deflation (for sigma^- > sigma^+; not in the text, derived in fast_iim_solver.h and
// docs/electric_solver_3d.md): when the flux balance fixes the weighted mean of every solution,
// mean(G) = mu, the solver works on R(G) - (mean(G) - mu) 1 = 0 (the same solution), which moves
// the near-null eigenvalue sigma^+/[sigma] of the equilibrium-density mode to sigma^+/[sigma] - 1.
// The shift is applied in the unknowns' space: the tested residual minus (mean(G) - mu) times the
// tested constant 1.
//
// Warm start: a guess at the points is projected on the unknowns and is GMRES's initial guess,
// with the tolerance relative to |b| = |R(0)| of the current problem (the result depends only on
// the problem and the guess, so a checkpointed G restarts bit for bit). With warm_start_refresh
// = k > 0 a guess instead solves for the correction from -R(G_0), relative to |b| of the last cold
// solve (one potential solve fewer; every k-th warm solve is cold again): the result then depends
// on the solve history (docs/electric_solver.md sec. 3, "Warm start").
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "ehd_capsule/electric/gmres.h"

namespace ehd {

// How G at the n interface points is represented by GMRES's unknowns.
class InterfaceUnknowns {
 public:
  virtual ~InterfaceUnknowns() = default;
  virtual int count() const = 0;
  // G at the points (n values) from the unknowns x (count() values).
  virtual void Expand(const double* x, double* g) const = 0;
  // A residual at the points, tested into the unknowns' space (count() values).
  virtual void Restrict(const double* r, double* rx) const = 0;
  // The unknowns of a guess G at the points.
  virtual void Project(const double* g, double* x) const = 0;
};

// G at every point: the identity.
class PointUnknowns final : public InterfaceUnknowns {
 public:
  explicit PointUnknowns(int points) : points_(points) {}
  int count() const override { return points_; }
  void Expand(const double* x, double* g) const override;
  void Restrict(const double* r, double* rx) const override;
  void Project(const double* g, double* x) const override;

 private:
  int points_;
};

// G = B x (B: n x k, the basis at the points), the residual tested against the columns of B with
// the point weights w (quadrature weights of the interface, normalised by its measure):
// r_x = (diag(w) B)^T r. A guess is projected by least squares in the same weights (the Gram
// matrix (diag(w) B)^T B), or, for a basis orthonormal in other weights a (the harmonics on the
// unit sphere), by x = B^T (a g).
class GalerkinUnknowns final : public InterfaceUnknowns {
 public:
  // basis must outlive this object. Least-squares projection of a guess.
  void Set(const Eigen::MatrixXd& basis, const std::vector<double>& test_weight);
  // The same, with a guess projected by B^T (orthonormal_weight g).
  void Set(const Eigen::MatrixXd& basis, const Eigen::VectorXd& test_weight,
           const Eigen::VectorXd& orthonormal_weight);
  int count() const override { return static_cast<int>(basis_->cols()); }
  void Expand(const double* x, double* g) const override;
  void Restrict(const double* r, double* rx) const override;
  void Project(const double* g, double* x) const override;

 private:
  const Eigen::MatrixXd* basis_ = nullptr;
  Eigen::MatrixXd weighted_basis_;  // diag(w) B
  Eigen::LDLT<Eigen::MatrixXd> gram_;
  Eigen::VectorXd orthonormal_weight_;  // empty: least squares
};

// The deflated mean (see the file comment); inactive by default.
struct MeanDeflation {
  bool active = false;
  double target = 0.0;                          // mu
  std::function<double(const double* g)> mean;  // the weighted mean of G at the points
};

class InterfaceSchurSolver {
 public:
  // residual(g, with_data, r): R(g) at the points into r (with_data), or R(g) - R(0).
  using PointResidual = std::function<void(const double* g, bool with_data, double* r)>;

  // g: on entry a guess at the points (size `points`; any other size: no guess), on exit the
  // solution at the points. Returns GMRES's result; the caller decides what non-convergence
  // means (each solver throws its SolverError).
  GmresResult Solve(const InterfaceUnknowns& unknowns, int points, const PointResidual& residual,
                    const MeanDeflation& deflation, const GmresOptions& options,
                    int warm_start_refresh, std::vector<double>& g);
  // Forget |b| of the last cold solve: the next warm-start solve is cold.
  void ResetWarmStart() { reference_norm_ = 0.0; }

 private:
  RestartedGmres gmres_;
  std::vector<double> g_points_, r_points_;
  double reference_norm_ = 0.0;  // |R(0)| of the last cold solve
  int reference_unknowns_ = 0;
  int warm_solves_ = 0;
};

}  // namespace ehd
