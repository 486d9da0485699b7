// Restarted GMRES (Saad & Schultz 1986; song2019 sec. 2.4.1, eq. (62)-(65)) for the Schur
// system (E - D L^{-1} B) G = V_bar of the fast IIM, eq. (57), whose matrix is only available as
// a mat-vec (one fast Poisson solve each).
//
// Arnoldi with modified Gram-Schmidt builds A Q_n = Q_{n+1} H_n; Givens rotations keep the
// least-squares residual |H_n y - beta e_1| = |b - A x_n| available at every step without
// forming x_n. Stops when |b - A x| <= tolerance * reference, where reference = |b| unless the
// caller gives another one. Workspace is kept between calls (no allocation once sized).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>

namespace ehd {

struct GmresOptions {
  double tolerance = 1e-7;  // relative to |b| (the residual of the zero guess)
  int restart = 40;         // Krylov dimension before a restart
  int max_iterations = 400;
};

struct GmresResult {
  int iterations = 0;      // Arnoldi steps (mat-vecs, not counting the one for the guess)
  double residual = 0.0;   // |b - A x| at exit (from the Givens recurrence, then recomputed)
  double reference = 0.0;  // the norm the tolerance was relative to
  bool converged = false;
};

// Thrown by solvers that need GMRES to converge.
struct SolverError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class RestartedGmres {
 public:
  using MatVec = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& y)>;

  // Solves A x = b; x holds the initial guess on entry (size of b). reference <= 0 means |b|.
  GmresResult Solve(const MatVec& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                    const GmresOptions& options, double reference = -1.0);

 private:
  Eigen::MatrixXd basis_;       // n x (restart + 1)
  Eigen::MatrixXd hessenberg_;  // (restart + 1) x restart
  Eigen::VectorXd cs_, sn_, g_, r_, w_;
};

}  // namespace ehd
