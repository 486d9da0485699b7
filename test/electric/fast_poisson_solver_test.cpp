// FastPoissonSolver: (1) the solve inverts the 5-point cell-centred operator with the stated
// ghost rules exactly (residual at round-off for a random rhs), for every boundary combination;
// (2) with inhomogeneous side data folded in, the discrete solution of a manufactured smooth
// phi converges at second order (the 5-point stencil and the cell-centred ghost rules are both
// O(h^2) consistent), again for all 25 combinations of {DD, NN, DN, ND, periodic} per axis.
#include "ehd_capsule/electric/fast_poisson_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ehd {
namespace {

struct AxisPair {
  BoundaryKind lo, hi;
  const char* name;
};
const AxisPair kAxisPairs[] = {
    {BoundaryKind::kDirichlet, BoundaryKind::kDirichlet, "DD"},
    {BoundaryKind::kNeumann, BoundaryKind::kNeumann, "NN"},
    {BoundaryKind::kDirichlet, BoundaryKind::kNeumann, "DN"},
    {BoundaryKind::kNeumann, BoundaryKind::kDirichlet, "ND"},
    {BoundaryKind::kPeriodic, BoundaryKind::kPeriodic, "PP"},
};

// Applies the homogeneous 5-point operator with the ghost rules of the header.
std::vector<double> ApplyLaplacian(const Grid2D& g, const PoissonBoundaries& bc,
                                   const std::vector<double>& u) {
  auto ghost = [](BoundaryKind kind, double inner, double wrapped) {
    switch (kind) {
      case BoundaryKind::kDirichlet:
        return -inner;
      case BoundaryKind::kNeumann:
        return inner;
      default:
        return wrapped;
    }
  };
  std::vector<double> out(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double c = u[g.index(i, j)];
      const double w = i > 0 ? u[g.index(i - 1, j)] : ghost(bc.x_min, c, u[g.index(g.nx - 1, j)]);
      const double e = i < g.nx - 1 ? u[g.index(i + 1, j)] : ghost(bc.x_max, c, u[g.index(0, j)]);
      const double s = j > 0 ? u[g.index(i, j - 1)] : ghost(bc.y_min, c, u[g.index(i, g.ny - 1)]);
      const double n = j < g.ny - 1 ? u[g.index(i, j + 1)] : ghost(bc.y_max, c, u[g.index(i, 0)]);
      out[g.index(i, j)] = (w + e + s + n - 4.0 * c) / (g.h * g.h);
    }
  }
  return out;
}

double Mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / v.size();
}

TEST(FastPoissonSolver, InvertsFivePointOperatorExactlyForEveryBoundaryCombination) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (const auto& px : kAxisPairs) {
    for (const auto& py : kAxisPairs) {
      const Grid2D g{12, 10, 0.1, -0.3, 0.2};
      const PoissonBoundaries bc{px.lo, px.hi, py.lo, py.hi};
      FastPoissonSolver solver(g, bc);
      std::vector<double> rhs(g.size());
      for (double& r : rhs) r = uni(rng);
      // Singular case: the solver projects out the constant mode, so give it a compatible rhs.
      if (IsSingular(bc)) {
        const double m = Mean(rhs);
        for (double& r : rhs) r -= m;
      }
      std::vector<double> u;
      solver.Solve(rhs, u);
      const std::vector<double> lu = ApplyLaplacian(g, bc, u);
      double err = 0;
      for (std::size_t k = 0; k < rhs.size(); ++k) err = std::max(err, std::abs(lu[k] - rhs[k]));
      EXPECT_LT(err, 1e-10) << px.name << " x " << py.name;
      if (IsSingular(bc)) {
        EXPECT_NEAR(Mean(u), 0.0, 1e-12) << px.name << " x " << py.name;
      }
    }
  }
}

// phi = exp(sin(2 pi x)) cos(2 pi y + 0.4) on [0,1]^2: smooth, periodic with period 1 in both
// directions, and not an eigenfunction of any of the transforms.
double Phi(double x, double y) {
  return std::exp(std::sin(2 * M_PI * x)) * std::cos(2 * M_PI * y + 0.4);
}
Eigen::Vector2d GradPhi(double x, double y) {
  const double u = std::exp(std::sin(2 * M_PI * x));
  return {2 * M_PI * std::cos(2 * M_PI * x) * u * std::cos(2 * M_PI * y + 0.4),
          -2 * M_PI * u * std::sin(2 * M_PI * y + 0.4)};
}
double LapPhi(double x, double y) {
  const double k = 2 * M_PI, u = std::exp(std::sin(k * x));
  const double uxx = k * k * (std::cos(k * x) * std::cos(k * x) - std::sin(k * x)) * u;
  return (uxx - k * k * u) * std::cos(k * y + 0.4);
}

double ManufacturedError(int n, const PoissonBoundaries& bc) {
  const Grid2D g{n, n, 1.0 / n, 0.0, 0.0};
  FastPoissonSolver solver(g, bc);
  std::vector<double> rhs(g.size()), exact(g.size());
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      rhs[g.index(i, j)] = LapPhi(g.x(i), g.y(j));
      exact[g.index(i, j)] = Phi(g.x(i), g.y(j));
    }
  }
  AddBoundaryDataToRhs(g, bc, SampleBoundaryData(g, bc, Phi, GradPhi), rhs);
  std::vector<double> u;
  solver.Solve(rhs, u);
  const bool singular = IsSingular(bc);
  const double shift = singular ? Mean(exact) - Mean(u) : 0.0;
  double err = 0;
  for (std::size_t k = 0; k < u.size(); ++k) err = std::max(err, std::abs(u[k] + shift - exact[k]));
  return err;
}

TEST(FastPoissonSolver, SecondOrderOnManufacturedSolutionForEveryBoundaryCombination) {
  for (const auto& px : kAxisPairs) {
    for (const auto& py : kAxisPairs) {
      const PoissonBoundaries bc{px.lo, px.hi, py.lo, py.hi};
      const double e1 = ManufacturedError(32, bc), e2 = ManufacturedError(64, bc);
      const double order = std::log2(e1 / e2);
      EXPECT_GT(order, 1.8) << px.name << " x " << py.name << " errors " << e1 << " " << e2;
      // |phi| <= e and |Lap phi| ~ 4 pi^2 e: an O(h^2) error at h = 1/64 is ~1e-2 at most.
      EXPECT_LT(e2, 1e-2) << px.name << " x " << py.name;
    }
  }
}

// Local truncation error, in the cells next to the box, of the 5-point operator with the
// folded side data: max |L_h(u) - (F + side terms)| over the boundary cells, where u is the
// exact solution at the cell centres and F = Laplace(u) there.
double BoundaryTruncation(int n, bool ghost_correction) {
  const Grid2D g{n, n, 1.0 / n, 0.0, 0.0};
  const PoissonBoundaries bc{};  // all Dirichlet
  // Curved Dirichlet data on every side: u_tt != 0 and u_nn != 0 at every face.
  auto u = [](double x, double y) {
    return std::sin(1.7 * x + 0.3) * std::exp(0.8 * y) + x * x * y;
  };
  auto lap = [](double x, double y) {
    return (0.64 - 2.89) * std::sin(1.7 * x + 0.3) * std::exp(0.8 * y) + 2.0 * y;
  };
  std::vector<double> exact(g.size()), rhs(g.size());
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      exact[g.index(i, j)] = u(g.x(i), g.y(j));
      rhs[g.index(i, j)] = lap(g.x(i), g.y(j));
    }
  }
  const PoissonBoundaryData data = SampleBoundaryData(g, bc, u, nullptr);
  if (ghost_correction) AddDirichletGhostCorrection(g, bc, data, rhs);
  AddBoundaryDataToRhs(g, bc, data, rhs);
  const std::vector<double> lu = ApplyLaplacian(g, bc, exact);
  double worst = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (i > 0 && j > 0 && i < n - 1 && j < n - 1) continue;
      worst = std::max(worst, std::abs(lu[g.index(i, j)] - rhs[g.index(i, j)]));
    }
  }
  return worst;
}

TEST(FastPoissonSolver, DirichletGhostCorrectionMakesTheGhostValueThirdOrder) {
  // The plain ghost u_{-1} = 2 g - u_0 misses (h^2/4) u_nn at the face, so the truncation error
  // of the boundary cells is u_nn / 4 = O(1) (an O(h^2) error of the effective boundary value):
  // it must not fall with h. The correction uses u_nn = F - g_tt with F at the cell centre (h/2
  // from the face) and g_tt by second differences (one point off at the side ends), both O(h):
  // what is left is an O(h) truncation, i.e. an O(h^3) ghost value, so the boundary truncation
  // must halve with h and be far below the plain one.
  const double plain20 = BoundaryTruncation(20, false), plain40 = BoundaryTruncation(40, false);
  EXPECT_GT(plain40, 0.8 * plain20);  // O(1)
  EXPECT_GT(plain40, 0.1);
  const double fixed20 = BoundaryTruncation(20, true), fixed40 = BoundaryTruncation(40, true);
  const double fixed80 = BoundaryTruncation(80, true);
  EXPECT_GT(fixed20 / fixed40, 1.8) << fixed20 << " " << fixed40;
  EXPECT_GT(fixed40 / fixed80, 1.8) << fixed40 << " " << fixed80;
  EXPECT_LT(fixed80, 0.1 * plain40);
}

TEST(FastPoissonSolver, DirichletGhostCorrectionActsOnlyOnDirichletSides) {
  // Linear side data (g_tt = 0) and F = 1: the corrected ghost subtracts (F - g_tt)/4 = 1/4 in
  // each cell per adjacent Dirichlet side (1/2 in a corner between two), nothing at Neumann or
  // periodic sides, nothing inside.
  const Grid2D g{12, 10, 0.1, -0.6, -0.5};
  const PoissonBoundaries cases[] = {
      PoissonBoundaries{},
      PoissonBoundaries{BoundaryKind::kNeumann, BoundaryKind::kNeumann, BoundaryKind::kDirichlet,
                        BoundaryKind::kDirichlet},
      PoissonBoundaries{BoundaryKind::kPeriodic, BoundaryKind::kPeriodic, BoundaryKind::kDirichlet,
                        BoundaryKind::kNeumann}};
  for (const PoissonBoundaries& bc : cases) {
    const PoissonBoundaryData data = SampleBoundaryData(
        g, bc, [](double x, double y) { return 2 + 3 * x - y; },
        [](double, double) { return Eigen::Vector2d(3, -1); });
    std::vector<double> rhs(g.size(), 1.0);
    AddDirichletGhostCorrection(g, bc, data, rhs);
    const auto is_d = [](BoundaryKind k) { return k == BoundaryKind::kDirichlet ? 1 : 0; };
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const int sides = (i == 0 ? is_d(bc.x_min) : 0) + (i == g.nx - 1 ? is_d(bc.x_max) : 0) +
                          (j == 0 ? is_d(bc.y_min) : 0) + (j == g.ny - 1 ? is_d(bc.y_max) : 0);
        EXPECT_NEAR(rhs[g.index(i, j)], 1.0 - 0.25 * sides, 1e-9) << i << " " << j;
      }
    }
  }
}

TEST(FastPoissonSolver, RejectsUnpairedPeriodicSidesAndBadSizes) {
  const Grid2D g{8, 8, 0.1, 0, 0};
  EXPECT_THROW(
      FastPoissonSolver(g, PoissonBoundaries{BoundaryKind::kPeriodic, BoundaryKind::kDirichlet,
                                             BoundaryKind::kDirichlet, BoundaryKind::kDirichlet}),
      std::invalid_argument);
  EXPECT_THROW(FastPoissonSolver(Grid2D{0, 8, 0.1, 0, 0}, PoissonBoundaries{}),
               std::invalid_argument);
  FastPoissonSolver solver(g, PoissonBoundaries{});
  std::vector<double> wrong(5), out;
  EXPECT_THROW(solver.Solve(wrong, out), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
