// The fast IIM's Schur solver (electric/interface_schur_system.h) on small affine residuals
// R(g) = A g - b with a known solution: every unknown set reaches it (or its Galerkin projection,
// solved directly), the mean deflation does not change the solution and lifts a near-null
// constant mode, and a guess that is the solution needs no iteration.
#include "ehd_capsule/electric/interface_schur_system.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <vector>

namespace ehd {
namespace {

constexpr int kPoints = 24;

// A = I + 0.3 R (R fixed pseudo-random), then made to map the constant 1 to epsilon 1 (a
// near-null constant mode for small epsilon, as the equilibrium density of a much more
// conducting inside).
Eigen::MatrixXd Operator(double epsilon) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(kPoints, kPoints);
  unsigned state = 12345u;
  for (int i = 0; i < kPoints; ++i) {
    for (int j = 0; j < kPoints; ++j) {
      state = state * 1103515245u + 12345u;
      a(i, j) += 0.3 * (static_cast<double>((state >> 8) & 0xffff) / 65535.0 - 0.5) / kPoints;
    }
  }
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(kPoints);
  const Eigen::VectorXd defect = a * one - epsilon * one;
  a -= defect * one.transpose() / kPoints;
  return a;
}

Eigen::VectorXd Solution() {
  Eigen::VectorXd g(kPoints);
  for (int i = 0; i < kPoints; ++i) g(i) = 1.0 + std::cos(0.7 * i) + 0.1 * i;
  return g;
}

struct Affine {
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  InterfaceSchurSolver::PointResidual Residual() const {
    return [this](const double* g, bool with_data, double* r) {
      Eigen::Map<Eigen::VectorXd> out(r, kPoints);
      out = a * Eigen::Map<const Eigen::VectorXd>(g, kPoints);
      if (with_data) out -= b;
    };
  }
};

GmresOptions Tight() {
  GmresOptions options;
  options.tolerance = 1e-12;
  options.max_iterations = 200;
  return options;
}

TEST(InterfaceSchurSolver, PointUnknownsReachTheSolution) {
  Affine problem{Operator(0.5), {}};
  const Eigen::VectorXd exact = Solution();
  problem.b = problem.a * exact;
  InterfaceSchurSolver solver;
  std::vector<double> g;  // no guess
  const GmresResult r = solver.Solve(PointUnknowns(kPoints), kPoints, problem.Residual(),
                                     MeanDeflation(), Tight(), 0, g);
  ASSERT_TRUE(r.converged);
  ASSERT_EQ(static_cast<int>(g.size()), kPoints);
  EXPECT_LT((Eigen::Map<const Eigen::VectorXd>(g.data(), kPoints) - exact).norm(),
            1e-9 * exact.norm());
  // The solution as the guess: no iteration.
  const GmresResult again = solver.Solve(PointUnknowns(kPoints), kPoints, problem.Residual(),
                                         MeanDeflation(), Tight(), 0, g);
  EXPECT_TRUE(again.converged);
  EXPECT_EQ(again.iterations, 0);
}

TEST(InterfaceSchurSolver, GalerkinUnknownsSolveTheProjectedSystem) {
  Affine problem{Operator(0.5), {}};
  problem.b = problem.a * Solution();
  const int k = 7;
  Eigen::MatrixXd basis(kPoints, k);
  std::vector<double> weight(kPoints);
  for (int i = 0; i < kPoints; ++i) {
    weight[i] = (1.0 + 0.5 * std::sin(0.3 * i)) / kPoints;
    basis(i, 0) = 1.0;
    for (int j = 1; j <= 3; ++j) {
      basis(i, 2 * j - 1) = std::cos(2.0 * M_PI * j * i / kPoints);
      basis(i, 2 * j) = std::sin(2.0 * M_PI * j * i / kPoints);
    }
  }
  GalerkinUnknowns unknowns;
  unknowns.Set(basis, weight);
  InterfaceSchurSolver solver;
  std::vector<double> g;
  ASSERT_TRUE(solver.Solve(unknowns, kPoints, problem.Residual(), MeanDeflation(), Tight(), 0, g)
                  .converged);
  // Direct: (W^T A B) x = W^T b, W = diag(w) B.
  const Eigen::MatrixXd w =
      Eigen::Map<const Eigen::VectorXd>(weight.data(), kPoints).asDiagonal() * basis;
  const Eigen::VectorXd x =
      (w.transpose() * problem.a * basis).lu().solve(w.transpose() * problem.b);
  const Eigen::VectorXd direct = basis * x;
  EXPECT_LT((Eigen::Map<const Eigen::VectorXd>(g.data(), kPoints) - direct).norm(),
            1e-9 * direct.norm());
  // A guess in the span is projected exactly (least squares in the weights): no iteration.
  EXPECT_EQ(solver.Solve(unknowns, kPoints, problem.Residual(), MeanDeflation(), Tight(), 0, g)
                .iterations,
            0);
}

TEST(InterfaceSchurSolver, MeanDeflationKeepsTheSolutionAndLiftsTheNearNullMode) {
  Affine problem{Operator(1e-4), {}};
  const Eigen::VectorXd exact = Solution();
  problem.b = problem.a * exact;
  MeanDeflation deflation;
  deflation.active = true;
  deflation.target = exact.mean();
  deflation.mean = [](const double* g) {
    return Eigen::Map<const Eigen::VectorXd>(g, kPoints).mean();
  };
  GmresOptions loose = Tight();
  loose.tolerance = 1e-8;
  InterfaceSchurSolver solver;
  std::vector<double> plain, deflated;
  const GmresResult r0 = solver.Solve(PointUnknowns(kPoints), kPoints, problem.Residual(),
                                      MeanDeflation(), loose, 0, plain);
  const GmresResult r1 = solver.Solve(PointUnknowns(kPoints), kPoints, problem.Residual(),
                                      deflation, loose, 0, deflated);
  ASSERT_TRUE(r0.converged);
  ASSERT_TRUE(r1.converged);
  const auto error = [&](const std::vector<double>& g) {
    return (Eigen::Map<const Eigen::VectorXd>(g.data(), kPoints) - exact).norm() / exact.norm();
  };
  // The plain system's residual tolerance leaves the near-null mode's error amplified by
  // 1/epsilon; the deflated one's eigenvalue is epsilon - 1.
  EXPECT_LT(error(deflated), 1e-6);
  EXPECT_LT(error(deflated), error(plain));
  EXPECT_LE(r1.iterations, r0.iterations);
}

TEST(InterfaceSchurSolver, WarmStartRefreshSolvesForTheCorrection) {
  Affine problem{Operator(0.5), {}};
  const Eigen::VectorXd exact = Solution();
  problem.b = problem.a * exact;
  InterfaceSchurSolver solver;
  std::vector<double> g;
  ASSERT_TRUE(solver
                  .Solve(PointUnknowns(kPoints), kPoints, problem.Residual(), MeanDeflation(),
                         Tight(), 2, g)
                  .converged);  // cold: sets |b|
  // A slightly changed problem, warm from the old solution, relative to the old |b|.
  problem.b *= 1.001;
  const GmresResult warm = solver.Solve(PointUnknowns(kPoints), kPoints, problem.Residual(),
                                        MeanDeflation(), Tight(), 2, g);
  ASSERT_TRUE(warm.converged);
  EXPECT_NEAR(warm.reference, (problem.b / 1.001).norm(), 1e-12 * problem.b.norm());
  EXPECT_LT((Eigen::Map<const Eigen::VectorXd>(g.data(), kPoints) - 1.001 * exact).norm(),
            1e-9 * exact.norm());
}

}  // namespace
}  // namespace ehd
