// The fast IIM's Schur system for curves and surfaces (see interface_schur_system.h).
#include "ehd_capsule/electric/interface_schur_system.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ehd {

void PointUnknowns::Expand(const double* x, double* g) const { std::copy(x, x + points_, g); }

void PointUnknowns::Restrict(const double* r, double* rx) const { std::copy(r, r + points_, rx); }

void PointUnknowns::Project(const double* g, double* x) const { std::copy(g, g + points_, x); }

void GalerkinUnknowns::Set(const Eigen::MatrixXd& basis, const std::vector<double>& test_weight) {
  if (static_cast<Eigen::Index>(test_weight.size()) != basis.rows()) {
    throw std::invalid_argument("GalerkinUnknowns: " + std::to_string(test_weight.size()) +
                                " weights for a basis at " + std::to_string(basis.rows()) +
                                " points");
  }
  basis_ = &basis;
  weighted_basis_ = basis;
  for (Eigen::Index k = 0; k < basis.rows(); ++k) weighted_basis_.row(k) *= test_weight[k];
  gram_.compute(weighted_basis_.transpose() * basis);
  orthonormal_weight_.resize(0);
}

void GalerkinUnknowns::Set(const Eigen::MatrixXd& basis, const Eigen::VectorXd& test_weight,
                           const Eigen::VectorXd& orthonormal_weight) {
  if (test_weight.size() != basis.rows() || orthonormal_weight.size() != basis.rows()) {
    throw std::invalid_argument("GalerkinUnknowns: weights of size " +
                                std::to_string(test_weight.size()) + " and " +
                                std::to_string(orthonormal_weight.size()) + " for a basis at " +
                                std::to_string(basis.rows()) + " points");
  }
  basis_ = &basis;
  weighted_basis_ = basis;
  for (Eigen::Index k = 0; k < basis.rows(); ++k) weighted_basis_.row(k) *= test_weight(k);
  orthonormal_weight_ = orthonormal_weight;
}

void GalerkinUnknowns::Expand(const double* x, double* g) const {
  Eigen::Map<Eigen::VectorXd>(g, basis_->rows()) =
      *basis_ * Eigen::Map<const Eigen::VectorXd>(x, basis_->cols());
}

void GalerkinUnknowns::Restrict(const double* r, double* rx) const {
  Eigen::Map<Eigen::VectorXd>(rx, basis_->cols()) =
      weighted_basis_.transpose() * Eigen::Map<const Eigen::VectorXd>(r, basis_->rows());
}

void GalerkinUnknowns::Project(const double* g, double* x) const {
  const Eigen::Map<const Eigen::VectorXd> guess(g, basis_->rows());
  Eigen::Map<Eigen::VectorXd> unknowns(x, basis_->cols());
  if (orthonormal_weight_.size() > 0) {
    unknowns = basis_->transpose() * orthonormal_weight_.cwiseProduct(guess);
  } else {
    unknowns = gram_.solve(weighted_basis_.transpose() * guess);
  }
}

GmresResult InterfaceSchurSolver::Solve(const InterfaceUnknowns& unknowns, int points,
                                        const PointResidual& residual,
                                        const MeanDeflation& deflation, const GmresOptions& options,
                                        int warm_start_refresh, std::vector<double>& g) {
  const int k = unknowns.count();
  g_points_.resize(points);
  r_points_.resize(points);
  // The tested residual of the unknowns x (R(G(x)), or its linear part).
  auto tested_residual = [&](const double* x, bool with_data, double* rx) {
    unknowns.Expand(x, g_points_.data());
    residual(g_points_.data(), with_data, r_points_.data());
    unknowns.Restrict(r_points_.data(), rx);
  };
  auto mean_of = [&](const double* x) {
    unknowns.Expand(x, g_points_.data());
    return deflation.mean(g_points_.data());
  };
  // The tested constant residual 1 (the deflation's shift).
  Eigen::VectorXd tested_one(k);
  if (deflation.active) {
    std::vector<double> ones(points, 1.0);
    unknowns.Restrict(ones.data(), tested_one.data());
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(k);
  const bool has_guess = static_cast<int>(g.size()) == points;
  if (has_guess) unknowns.Project(g.data(), x.data());
  const RestartedGmres::MatVec apply = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) {
    out.resize(k);
    tested_residual(in.data(), false, out.data());
    if (deflation.active) out -= deflation.mean(g_points_.data()) * tested_one;
  };
  const bool warm = has_guess && warm_start_refresh > 0 && reference_norm_ > 0.0 &&
                    reference_unknowns_ == k && warm_solves_ < warm_start_refresh;
  GmresResult result;
  if (warm) {
    // A dx = -R(x0) from dx = 0, relative to |b| of the last cold solve.
    Eigen::VectorXd rhs(k), dx = Eigen::VectorXd::Zero(k);
    tested_residual(x.data(), true, rhs.data());
    rhs = -rhs;
    if (deflation.active) rhs -= (deflation.target - mean_of(x.data())) * tested_one;
    result = gmres_.Solve(apply, rhs, dx, options, reference_norm_);
    x += dx;
    ++warm_solves_;
  } else {
    // b = -R(0), GMRES from the guess.
    Eigen::VectorXd b(k);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(k);
    tested_residual(zero.data(), true, b.data());
    b = -b;
    if (deflation.active) b -= deflation.target * tested_one;
    result = gmres_.Solve(apply, b, x, options);
    reference_norm_ = result.reference;
    reference_unknowns_ = k;
    warm_solves_ = 0;
  }
  g.resize(points);
  unknowns.Expand(x.data(), g.data());
  return result;
}

}  // namespace ehd
