// Restarted GMRES with modified Gram-Schmidt Arnoldi and Givens rotations (see gmres.h).
#include "ehd_capsule/electric/gmres.h"

#include <cmath>

namespace ehd {

GmresResult RestartedGmres::Solve(const MatVec& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                  const GmresOptions& options, double reference) {
  const int n = static_cast<int>(b.size());
  if (x.size() != n) {
    throw std::invalid_argument("RestartedGmres::Solve: guess has " + std::to_string(x.size()) +
                                " entries, rhs has " + std::to_string(n));
  }
  if (options.restart < 1 || options.max_iterations < 0 || !(options.tolerance > 0.0)) {
    throw std::invalid_argument(
        "GmresOptions: need restart >= 1, max_iterations >= 0, tolerance > 0");
  }
  const int m = std::min(options.restart, std::max(n, 1));
  if (basis_.rows() != n || basis_.cols() != m + 1) {
    basis_.resize(n, m + 1);
    hessenberg_.resize(m + 1, m);
    cs_.resize(m);
    sn_.resize(m);
    g_.resize(m + 1);
    r_.resize(n);
    w_.resize(n);
  }
  GmresResult result;
  result.reference = reference > 0.0 ? reference : b.norm();
  const double target = options.tolerance * result.reference;
  // Residual of the guess (skip the mat-vec for a zero guess).
  if (x.squaredNorm() > 0.0) {
    apply(x, w_);
    r_ = b - w_;
  } else {
    r_ = b;
  }
  double beta = r_.norm();
  result.residual = beta;
  if (beta <= target || result.reference == 0.0) {
    result.converged = true;
    return result;
  }
  while (result.iterations < options.max_iterations) {
    basis_.col(0) = r_ / beta;
    g_.setZero();
    g_(0) = beta;
    int k = 0;
    for (; k < m && result.iterations < options.max_iterations; ++k) {
      apply(basis_.col(k), w_);
      ++result.iterations;
      for (int i = 0; i <= k; ++i) {
        hessenberg_(i, k) = basis_.col(i).dot(w_);
        w_ -= hessenberg_(i, k) * basis_.col(i);
      }
      const double hnext = w_.norm();
      hessenberg_(k + 1, k) = hnext;
      if (hnext > 0.0) basis_.col(k + 1) = w_ / hnext;
      for (int i = 0; i < k; ++i) {
        const double a = hessenberg_(i, k), c = hessenberg_(i + 1, k);
        hessenberg_(i, k) = cs_(i) * a + sn_(i) * c;
        hessenberg_(i + 1, k) = -sn_(i) * a + cs_(i) * c;
      }
      const double a = hessenberg_(k, k), c = hessenberg_(k + 1, k);
      const double rho = std::hypot(a, c);
      cs_(k) = rho > 0.0 ? a / rho : 1.0;
      sn_(k) = rho > 0.0 ? c / rho : 0.0;
      hessenberg_(k, k) = rho;
      hessenberg_(k + 1, k) = 0.0;
      g_(k + 1) = -sn_(k) * g_(k);
      g_(k) = cs_(k) * g_(k);
      result.residual = std::abs(g_(k + 1));
      if (result.residual <= target || hnext == 0.0) {
        ++k;
        break;
      }
    }
    // x += Q_k y with H_k y = g (upper triangular after the rotations).
    Eigen::VectorXd y = g_.head(k);
    for (int i = k - 1; i >= 0; --i) {
      for (int j = i + 1; j < k; ++j) y(i) -= hessenberg_(i, j) * y(j);
      y(i) /= hessenberg_(i, i);
    }
    x += basis_.leftCols(k) * y;
    if (result.residual <= target) break;
    // Restart from the true residual.
    apply(x, w_);
    r_ = b - w_;
    beta = r_.norm();
    result.residual = beta;
    if (beta <= target) break;
  }
  result.converged = result.residual <= target;
  return result;
}

}  // namespace ehd
