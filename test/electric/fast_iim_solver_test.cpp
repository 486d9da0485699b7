// Fast IIM operators one by one and the whole solver, on small grids.
// Expected values come from exact solutions (sec. 2.5 examples, the cylinder in a uniform field),
// exactness of a quadratic fit on quadratics, Taylor remainders of the jump expansion, and the
// observed order of convergence of a second-order method (log2 of the error ratio ~ 2).
#include "ehd_capsule/electric/fast_iim_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "ehd_capsule/electric/electric_field.h"
#include "ehd_capsule/electric/gmres.h"
#include "ehd_capsule/electric/interface_classification.h"
#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/electric/normal_derivative_fit.h"
#include "ehd_capsule/reference/interface_examples.h"
#include "support/interface_case.h"

namespace ehd {
namespace {

Eigen::Matrix2Xd CircleMarkers(int m, double r, Eigen::Vector2d c = Eigen::Vector2d::Zero()) {
  Eigen::Matrix2Xd x(2, m);
  for (int k = 0; k < m; ++k) {
    x.col(k) = c + r * Eigen::Vector2d(std::cos(2 * M_PI * k / m), std::sin(2 * M_PI * k / m));
  }
  return x;
}

TEST(RestartedGmres, SolvesSmallNonsymmetricSystemLikeADirectSolver) {
  // A = 2 I + small random part: well conditioned, non-symmetric; the LU solution is the truth.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-0.3, 0.3);
  const int n = 25;
  Eigen::MatrixXd a = 2.0 * Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) += uni(rng) / std::sqrt(n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b(i) = uni(rng);
  const Eigen::VectorXd exact = a.partialPivLu().solve(b);
  RestartedGmres gmres;
  GmresOptions opt;
  opt.tolerance = 1e-12;
  opt.restart = 5;  // forces restarts
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  const GmresResult r =
      gmres.Solve([&](const Eigen::VectorXd& v, Eigen::VectorXd& y) { y = a * v; }, b, x, opt);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((x - exact).norm(), 1e-10);
  EXPECT_LT((b - a * x).norm(), 1e-11 * b.norm() * 2);
}

TEST(InterfaceClassification, CircleSidesIrregularPointsAndDistancesMatchGeometry) {
  const Grid2D g{40, 40, 0.05, -1, -1};
  const ClosedCurve c(CircleMarkers(80, 0.5));
  InterfaceClassification cls;
  cls.Update(g, c, 3.5 * g.h);
  auto inside = [&](int i, int j) { return std::hypot(g.x(i), g.y(j)) < 0.5; };
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t idx = g.index(i, j);
      // The spline through 80 points deviates from the circle by ~1e-7 << any |r - 0.5| here.
      EXPECT_EQ(cls.side(idx), inside(i, j) ? -1 : 1) << i << "," << j;
      bool irregular = false;
      const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
      for (const auto& q : nb) {
        if (q[0] >= 0 && q[0] < g.nx && q[1] >= 0 && q[1] < g.ny)
          irregular |= inside(q[0], q[1]) != inside(i, j);
      }
      EXPECT_EQ(cls.irregular(idx), irregular) << i << "," << j;
      const double d = std::hypot(g.x(i), g.y(j)) - 0.5;
      const int slot = cls.band_slot(idx);
      EXPECT_EQ(slot >= 0,
                std::abs(d) < 3.5 * g.h - 1e-6 || (slot >= 0 && std::abs(d) < 3.5 * g.h));
      if (slot >= 0) {
        EXPECT_NEAR(cls.band_distance()[slot], d, 1e-6);
        EXPECT_NEAR(cls.band_curvature()[slot], 2.0, 5e-3);  // spline curvature, O(ds^2)
      }
    }
  }
}

TEST(InterfaceClassification, NonCircularCurvesAgreeWithContains) {
  for (const char* name : {"ellipse", "star", "biconcave"}) {
    const InterfaceExample e = MakeInterfaceExample(name);
    const Grid2D g = e.MakeGrid(48);
    const ClosedCurve c(e.Markers(e.DefaultMarkers(48)));
    InterfaceClassification cls;
    cls.Update(g, c, 3.5 * g.h);
    int mismatches = 0;
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i)
        mismatches += (cls.side(g.index(i, j)) < 0) != c.Contains({g.x(i), g.y(j)});
    EXPECT_EQ(mismatches, 0) << name;
    EXPECT_GT(cls.irregular_points().size(), 20u) << name;
  }
}

TEST(NormalDerivativeFit, ReproducesQuadraticsExactly) {
  // With no jump (J = 0), the fit of a quadratic is exact, so phi_n and phi_tau are exact, for
  // the reference's quadratic fit (degree 2) and for the default cubic one.
  const Grid2D g{40, 40, 0.05, -1, -1};
  const ClosedCurve c(CircleMarkers(60, 0.5, {0.03, -0.02}));
  InterfaceClassification cls;
  cls.Update(g, c, 3.5 * g.h);
  for (int degree : {2, 3}) {
    NormalDerivativeFit fit;
    fit.Update(c, cls, 3.0 * g.h, degree);
    auto q = [](double x, double y) { return 1 + 2 * x - 3 * y + x * x - 0.5 * x * y + 2 * y * y; };
    std::vector<double> phi(g.size()), jump(cls.band_size(), 0.0), dn(60), dt(60);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) phi[g.index(i, j)] = q(g.x(i), g.y(j));
    fit.Evaluate(phi.data(), jump.data(), dn.data(), dt.data());
    for (int k = 0; k < 60; ++k) {
      const CurvePoint p = c.AtMarker(k);
      const double x = p.position.x(), y = p.position.y();
      const Eigen::Vector2d grad(2 + 2 * x - 0.5 * y, -3 - 0.5 * x + 4 * y);
      EXPECT_NEAR(dn[k], grad.dot(p.normal), 1e-9);
      EXPECT_NEAR(dt[k], grad.dot(p.tangent), 1e-9);
    }
  }
  EXPECT_THROW(NormalDerivativeFit().Update(c, cls, 3.0 * g.h, 4), std::invalid_argument);
}

TEST(NormalDerivativeFit, ReproducesCubicsExactly) {
  // The fit is cubic where a marker has enough points (all of them here), so phi_n and phi_tau
  // of a cubic polynomial are exact too (a quadratic fit would be off by O(h^2) * 3rd
  // derivatives ~ 1e-2 here).
  const Grid2D g{40, 40, 0.05, -1, -1};
  const ClosedCurve c(CircleMarkers(60, 0.5, {0.03, -0.02}));
  InterfaceClassification cls;
  cls.Update(g, c, 3.5 * g.h);
  NormalDerivativeFit fit;
  fit.Update(c, cls, 3.0 * g.h);
  auto q = [](double x, double y) {
    return 1 + 2 * x - 3 * y + x * x - 0.5 * x * y + 2 * y * y + 3 * x * x * x - 2 * x * x * y +
           x * y * y - 4 * y * y * y;
  };
  std::vector<double> phi(g.size()), jump(cls.band_size(), 0.0), dn(60), dt(60);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) phi[g.index(i, j)] = q(g.x(i), g.y(j));
  fit.Evaluate(phi.data(), jump.data(), dn.data(), dt.data());
  for (int k = 0; k < 60; ++k) {
    const CurvePoint p = c.AtMarker(k);
    const double x = p.position.x(), y = p.position.y();
    const Eigen::Vector2d grad(2 + 2 * x - 0.5 * y + 9 * x * x - 4 * x * y + y * y,
                               -3 - 0.5 * x + 4 * y - 2 * x * x + 2 * x * y - 12 * y * y);
    EXPECT_NEAR(dn[k], grad.dot(p.normal), 1e-8);
    EXPECT_NEAR(dt[k], grad.dot(p.tangent), 1e-8);
  }
}

TEST(NormalDerivativeFit, OneSidedExtrapolationIsExactOnEachSidesQuadratic) {
  // A field that is one quadratic inside and another outside (a jump in value and in normal
  // derivative): each side's fit sees only its own points, so the one-sided limits and normal
  // derivatives at the markers are exact (quadratic side fits); the side averages used before
  // are off by O(h) (checked to be much worse). Also exact for a linear field on coarse data.
  const Grid2D g{40, 40, 0.05, -1, -1};
  const ClosedCurve c(CircleMarkers(50, 0.45, {0.04, 0.01}));
  InterfaceClassification cls;
  cls.Update(g, c, 3.5 * g.h);
  NormalDerivativeFit fit;
  fit.Update(c, cls, 3.0 * g.h);
  auto inner = [](double x, double y) { return 4 - x + 2 * y + 3 * x * x - x * y; };
  auto outer = [](double x, double y) { return -1 + 5 * x + y * y - 2 * x * y; };
  auto inner_grad = [](double x, double y) { return Eigen::Vector2d(-1 + 6 * x - y, 2 - x); };
  auto outer_grad = [](double x, double y) { return Eigen::Vector2d(5 - 2 * y, 2 * y - 2 * x); };
  std::vector<double> field(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t idx = g.index(i, j);
      field[idx] = cls.side(idx) < 0 ? inner(g.x(i), g.y(j)) : outer(g.x(i), g.y(j));
    }
  }
  const int m = c.size();
  std::vector<double> vm(m), vp(m), dm(m), dp(m), am(m), ap(m);
  fit.SideExtrapolation(field.data(), vm.data(), vp.data(), dm.data(), dp.data());
  fit.SideAverages(field.data(), am.data(), ap.data());
  double average_error = 0.0;
  for (int k = 0; k < m; ++k) {
    const CurvePoint p = c.AtMarker(k);
    const double x = p.position.x(), y = p.position.y();
    EXPECT_NEAR(vm[k], inner(x, y), 1e-9);
    EXPECT_NEAR(vp[k], outer(x, y), 1e-9);
    EXPECT_NEAR(dm[k], inner_grad(x, y).dot(p.normal), 1e-8);
    EXPECT_NEAR(dp[k], outer_grad(x, y).dot(p.normal), 1e-8);
    average_error = std::max(average_error, std::abs(ap[k] - am[k] - (outer(x, y) - inner(x, y))));
  }
  EXPECT_GT(average_error, 1e-3);  // the O(h) estimate this replaces
  // Null outputs are allowed.
  fit.SideExtrapolation(field.data(), vm.data(), nullptr, nullptr, nullptr);
  for (int k = 0; k < m; ++k)
    EXPECT_NEAR(vm[k], inner(c.AtMarker(k).position.x(), c.AtMarker(k).position.y()), 1e-9);
}

TEST(FastIimSolver, JumpExpansionWithSourceJumpsMatchesExample3ToFourthOrder) {
  // Example 3 with sigma- = sigma+ = 1 (so G = v exactly): phi^- = r^2, phi^+ = r^4 - 0.1 log 2r
  // + const, F^- = 4, F^+ = 16 r^2: [f/sigma] = -3.6 and [d_xi(f/sigma)] = 16 at r = 1/2. The
  // cubic expansion with both is the Taylor polynomial of phi^+ - phi^- in d, remainder
  // [phi_rrrr] d^4 / 24 = (24 + 9.6) d^4 / 24 = 1.4 d^4, plus spline errors of the curvature
  // and 5th-order terms: bound 2 d^4; dropping
  // [d_xi(f/sigma)] would leave 16 d^3 / 6 (3e-4 at d = h), using side averages for [f/sigma]
  // an O(h) error times d^2 / 2.
  const InterfaceExample e = MakeInterfaceExample("3", 1.0, 1.0);
  const Grid2D g = e.MakeGrid(40);
  const ClosedCurve c(e.Markers(120));
  FastIimSolver solver(g, PoissonBoundaries{});
  std::vector<double> gv, phi;
  solver.Solve(c, SampleInterfaceProblem(e, g, c), gv, phi);
  const auto& cls = solver.classification();
  ASSERT_FALSE(cls.crossing_pairs().empty());
  for (const auto& pair : cls.crossing_pairs()) {
    const int b = pair.neighbour_slot;
    const double d = cls.band_distance()[b];
    const double r = 0.5 + d;  // closest point on the circle r = 1/2: d = r - 1/2
    const double exact = (r * r * r * r - 0.1 * std::log(2 * r) + 0.25 - 0.0625) - r * r;
    EXPECT_NEAR(solver.band_jump()[b], exact, 2.0 * std::pow(d, 4) + 1e-9) << d;
  }
  for (double gk : gv) EXPECT_NEAR(gk, -0.7, 1e-12);
}

TEST(FastIimSolver, InteriorFluxQuadratureIsThirdOrder) {
  // The interior flux (integral of F^- over Omega^-) against the exact curve integral of
  // phi_n^- (divergence theorem, fine trapezoid sum). The cut-cell quadrature with the
  // curvature sliver, the first moment and the (h^2/24) Laplace(F) term is O(h^3); the
  // half-plane fractions with cell-centre F it replaces were O(h^2) with errors 1e-3 (N = 40)
  // and 2e-4 (N = 80) on these two examples.
  for (const char* name : {"2", "ellipse"}) {
    const InterfaceExample e = MakeInterfaceExample(name, 2.0, 1.0);
    const ClosedCurve fine(e.Markers(4000));
    double exact = 0.0;
    for (int k = 0; k < fine.size(); ++k) {
      const CurvePoint p = fine.AtMarker(k);
      const double dl = 0.5 * (fine.SegmentArcLength((k + fine.size() - 1) % fine.size()) +
                               fine.SegmentArcLength(k));
      exact += e.grad_minus(p.position).dot(p.normal) * dl;
    }
    for (int n : {40, 80}) {
      const Grid2D g = e.MakeGrid(n);
      const ClosedCurve c(e.Markers(e.DefaultMarkers(n)));
      FastIimSolver solver(g, PoissonBoundaries{});
      std::vector<double> gv, phi;
      solver.Solve(c, SampleInterfaceProblem(e, g, c), gv, phi);
      EXPECT_NEAR(solver.interior_flux(), exact, n == 40 ? 5e-5 : 1e-5) << name << " N = " << n;
    }
  }
}

TEST(FastIimSolver, JumpExpansionMatchesExactJumpOfExample1) {
  // Example 1: phi^+ - phi^- = log(2r) = log(1 + 2d); the cubic expansion with g = 2, kappa = 2
  // is its Taylor polynomial, so the remainder is bounded by |2d|^4 / (4 (1 - |2d|)).
  const InterfaceExample e = MakeInterfaceExample("1");
  const Grid2D g = e.MakeGrid(40);
  const ClosedCurve c(e.Markers(120));
  FastIimSolver solver(g, PoissonBoundaries{});
  std::vector<double> gv, phi;
  solver.Solve(c, SampleInterfaceProblem(e, g, c), gv, phi);
  const auto& cls = solver.classification();
  // J is evaluated where the method uses it: at the neighbours across each crossing stencil.
  ASSERT_FALSE(cls.crossing_pairs().empty());
  for (const auto& pair : cls.crossing_pairs()) {
    const int b = pair.neighbour_slot;
    const double d = cls.band_distance()[b];
    const double x = std::abs(2 * d);
    EXPECT_NEAR(solver.band_jump()[b], std::log1p(2 * d),
                1.1 * std::pow(x, 4) / (4 * (1 - x)) + 1e-6);
  }
  for (double gk : gv) EXPECT_NEAR(gk, 2.0, 1e-12);  // sigma+ = sigma-: g = v / sigma exactly
}

// The max error of phi on the example's N x N grid with its default markers.
double SolveErrorWith(const InterfaceExample& e, int n, bool deferred,
                      InterfaceSolveReport* report = nullptr) {
  const test::InterfaceCase c(e, n, e.Markers(e.DefaultMarkers(n)));
  FastIimOptions options;
  options.deferred_correction = deferred;
  FastIimSolver solver(c.grid, PoissonBoundaries{}, options);
  std::vector<double> gv, phi;
  const InterfaceSolveReport r = solver.Solve(c.curve, c.problem, gv, phi);
  if (report) *report = r;
  return c.MaxError(phi);
}

double SolveError(const InterfaceExample& e, int n, InterfaceSolveReport* report = nullptr) {
  return SolveErrorWith(e, n, FastIimOptions().deferred_correction, report);
}

TEST(TruncationCorrection, MakesThePeriodicPoissonSolveFourthOrder) {
  // u = sin(2 pi x) sin(4 pi y) on the periodic unit square: L_h u = Laplace(u) + (h^2/12)(u_xxxx
  // + u_yyyy) + O(h^4), so the plain solve is second order and one deferred correction with
  // T = (delta^4_x + delta^4_y) u^1 / (12 h^2) cancels the h^2 term: fourth order.
  const double pi = M_PI;
  const PoissonBoundaries bc{BoundaryKind::kPeriodic, BoundaryKind::kPeriodic,
                             BoundaryKind::kPeriodic, BoundaryKind::kPeriodic};
  double plain[2], corrected[2];
  int level = 0;
  for (int n : {16, 32}) {
    const Grid2D g{n, n, 1.0 / n, 0.0, 0.0};
    FastPoissonSolver poisson(g, bc);
    std::vector<double> rhs(g.size()), exact(g.size()), u;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        exact[g.index(i, j)] = std::sin(2 * pi * g.x(i)) * std::sin(4 * pi * g.y(j));
        rhs[g.index(i, j)] = -20.0 * pi * pi * exact[g.index(i, j)];
      }
    }
    auto max_error = [&](const std::vector<double>& v) {
      double e = 0.0;
      for (std::size_t k = 0; k < v.size(); ++k) e = std::max(e, std::abs(v[k] - exact[k]));
      return e;
    };
    poisson.Solve(rhs, u);
    plain[level] = max_error(u);
    AddTruncationCorrection(g, bc, u, nullptr, nullptr, nullptr, rhs);
    poisson.Solve(rhs, u);
    corrected[level] = max_error(u);
    ++level;
  }
  EXPECT_NEAR(std::log2(plain[0] / plain[1]), 2.0, 0.1);
  EXPECT_GT(std::log2(corrected[0] / corrected[1]), 3.8);
  EXPECT_LT(corrected[1], 0.05 * plain[1]);
}

TEST(FastIimSolver, DeferredCorrectionBeatsTable1OnExample1) {
  // song2019 Table 1 (the CFM on the same problem as example 1; same h): 2.29e-4 / 9.11e-5 /
  // 1.84e-5 at N = 40 / 80 / 160. The plain IIM sits at the regular 5-point truncation floor
  // (3.1e-4 / 7.4e-5 / 1.9e-5, above the table at N = 40 and 160); the deferred correction
  // removes the O(h^2) truncation of phi^+ = 1 + log 2r, leaving the O(h^3) jump-expansion and
  // ghost remainders, so the order over 40 -> 160 is > 2.5.
  const InterfaceExample e = MakeInterfaceExample("1");
  const double table[3] = {2.29e-4, 9.11e-5, 1.84e-5};
  double err[3];
  int level = 0;
  for (int n : {40, 80, 160}) {
    err[level] = SolveErrorWith(e, n, true);
    EXPECT_LT(err[level], table[level]) << "N = " << n;
    ++level;
  }
  EXPECT_GT(0.5 * std::log2(err[0] / err[2]), 2.5);
}

TEST(FastIimSolver, DeferredCorrectionWithUnequalConductivitiesIsThirdOrder) {
  // Example 3 (sigma+ = 10 sigma-, a source jump) and example 1 with sigma+ = 1000 sigma-: the
  // deferred correction is inside every potential solve, so GMRES solves the Schur system of the
  // corrected potential (G consistent with it); the regular O(h^2) truncation is gone, so the
  // order over 40 -> 160 is > 2.5 and the error well below the plain second-order solve.
  for (const auto& [name, sp] : {std::pair<const char*, double>{"3", 10.0}, {"1", 1000.0}}) {
    const InterfaceExample e = MakeInterfaceExample(name, 1.0, sp);
    InterfaceSolveReport r160;
    const double e40 = SolveErrorWith(e, 40, true);
    const double e160 = SolveErrorWith(e, 160, true, &r160);
    EXPECT_GT(0.5 * std::log2(e40 / e160), 2.5) << name;
    EXPECT_LT(e160, 0.5 * SolveErrorWith(e, 160, false)) << name;
    EXPECT_TRUE(r160.converged);
  }
}

TEST(FastIimSolver, SecondOrderOnReferenceExamplesAndBothSigmaOrderings) {
  // Second order: error ratio ~4 per halving of h (averaged over 40 -> 160, as single steps
  // oscillate). GMRES should need few iterations for every sigma ratio.
  struct Case {
    const char* name;
    double sm, sp;
  };
  const Case cases[] = {{"2", 1, 2}, {"3", 1, 10},  {"3", 10, 1},  {"3", 1, 1000}, {"3", 1000, 1},
                        {"4", 1, 1}, {"4", 1, 100}, {"4", 100, 1}, {"1", 1, 1},    {"1", 1000, 1}};
  for (const Case& k : cases) {
    const InterfaceExample e = MakeInterfaceExample(k.name, k.sm, k.sp);
    InterfaceSolveReport r80, r160;
    const double e40 = SolveError(e, 40);
    SolveError(e, 80, &r80);
    const double e160 = SolveError(e, 160, &r160);
    EXPECT_GT(0.5 * std::log2(e40 / e160), 1.75) << k.name << " " << k.sm << "/" << k.sp;
    EXPECT_TRUE(r80.converged && r160.converged);
    EXPECT_LT(r80.iterations, 20) << k.name << " " << k.sm << "/" << k.sp;
    EXPECT_LT(r160.iterations, 20) << k.name << " " << k.sm << "/" << k.sp;
  }
}

TEST(FastIimSolver, ErrorsBelowTheReferenceTablesAtEveryGrid) {
  // song2019 Tables 3-7 (L-inf error at N = 40, 80, 160, 320; same h as ours): the fast IIM
  // must be at or below the published error at every N. Example 1 needs the second-order
  // Dirichlet ghost (the reference's boundary values sit on grid nodes).
  struct Case {
    const char* name;
    double sm, sp;
    double table[4];
  };
  const Case cases[] = {{"1", 1, 1, {3.44e-4, 1.07e-4, 3.11e-5, 6.56e-6}},
                        {"2", 1, 2, {3.08e-4, 7.05e-5, 1.64e-5, 4.11e-6}},
                        {"3", 1, 10, {1.60e-3, 3.68e-4, 8.89e-5, 2.05e-5}},
                        {"3", 1, 100, {3.55e-4, 8.24e-5, 1.95e-5, 4.14e-6}},
                        {"4", 1, 1, {7.39e-5, 2.06e-5, 5.56e-6, 1.38e-6}}};
  for (const Case& k : cases) {
    const InterfaceExample e = MakeInterfaceExample(k.name, k.sm, k.sp);
    int level = 0;
    for (int n : {40, 80, 160, 320}) {
      EXPECT_LT(SolveError(e, n), k.table[level])
          << "example " << k.name << " sigma+ = " << k.sp << " N = " << n;
      ++level;
    }
  }
}

TEST(FastIimSolver, SecondOrderOnEllipseStarAndBiconcave) {
  for (const char* name : {"ellipse", "star", "biconcave"}) {
    const InterfaceExample e = MakeInterfaceExample(name, 1.0, 5.0);
    const double e40 = SolveError(e, 40), e160 = SolveError(e, 160);
    // Average order over two halvings (the per-step ratio of a non-circular curve oscillates).
    EXPECT_GT(0.5 * std::log2(e40 / e160), 1.8) << name << " " << e40 << " " << e160;
  }
}

TEST(FastIimSolver, MeanDeflationKeepsTheSolutionAndCutsIterationsForHighInnerConductivity) {
  // sigma^- = 1000 sigma^+ on the five-petal star: the Schur operator has a near-null mode (the
  // curve's equilibrium density, eigenvalue ~ -sigma^+/sigma^-). Its mean is fixed exactly by
  // the interior flux, so adding -(mean(G) - mu) to the residual changes nothing in the solution
  // (G agrees to the GMRES tolerance) but removes the slow mode: fewer iterations.
  const InterfaceExample e = MakeInterfaceExample("star", 1000.0, 1.0);
  const Grid2D g = e.MakeGrid(80);
  const ClosedCurve c(e.Markers(e.DefaultMarkers(80)));
  const InterfaceProblem p = SampleInterfaceProblem(e, g, c);
  std::vector<double> g_plain, g_deflated, phi;
  FastIimOptions plain, deflated;
  plain.deflate_mean = false;
  plain.gmres.tolerance = deflated.gmres.tolerance = 1e-10;
  // G at every marker (no wavelength-limited Fourier basis, which already removes most of the
  // slow modes: 17 -> 15 iterations there), to see the deflation alone.
  plain.basis_wavelength_h = deflated.basis_wavelength_h = 0.0;
  // This N = 80 grid is coarse for the star at 1000:1 (the verification estimates 10%); the
  // test is about the deflation, so the verifying coarse solve is off.
  plain.verify_min_ratio = deflated.verify_min_ratio = std::numeric_limits<double>::infinity();
  FastIimSolver a(g, PoissonBoundaries{}, plain), b(g, PoissonBoundaries{}, deflated);
  const InterfaceSolveReport ra = a.Solve(c, p, g_plain, phi);
  const InterfaceSolveReport rb = b.Solve(c, p, g_deflated, phi);
  EXPECT_LE(rb.iterations + 3, ra.iterations) << ra.iterations << " " << rb.iterations;
  double scale = 0.0, diff = 0.0;
  for (std::size_t k = 0; k < g_plain.size(); ++k) {
    scale = std::max(scale, std::abs(g_plain[k]));
    diff = std::max(diff, std::abs(g_plain[k] - g_deflated[k]));
  }
  EXPECT_LT(diff, 1e-5 * scale);
}

TEST(FastIimSolver, BunchedMarkersGiveASmoothJumpForHighInnerConductivity) {
  // A cylinder of radius 8 h in a uniform field, sigma^- = 4.75 sigma^+ (Case C), with markers
  // bunched 10x at one side (spacing 0.08 h there, 0.8 h on average; a deforming drop gathers
  // them at its tips like this) and jittered by 0.01 h. Exact: [phi_n] = (sigma_r - 1) a_c
  // sin(theta), a_c = 2 / (1 + sigma_r). Control markers taken every k-th marker sit ~0.16 h
  // apart in the bunch, closer than the grid resolves: near-null modes that the jitter excites
  // (G off by 12%, 11 iterations; the coupled drop blew up on them). Spaced by arc length, G is
  // within 1% of the exact jump in 6 iterations.
  const double a = 8.0, sr = 4.75, amp = 2.0 / (1.0 + sr);
  auto phi_exact = [&](double x, double y) {
    const double r2 = x * x + y * y;
    return r2 < a * a ? amp * y : y * (1.0 + (1.0 - sr) / (1.0 + sr) * a * a / r2);
  };
  const Grid2D g{64, 64, 1.0, -32, -32};
  const int m = 64;
  Eigen::Matrix2Xd x(2, m);
  std::vector<double> theta(m);
  for (int k = 0; k < m; ++k) {
    const double s = 2 * M_PI * k / m;
    theta[k] = s - 0.9 * std::sin(s);  // marker density 1 / (1 - 0.9 cos s): 10x at s = 0
    x.col(k) << a * std::cos(theta[k]), a * std::sin(theta[k]);
    x.col(k) += 0.01 * Eigen::Vector2d(std::sin(12.9898 * k), std::cos(78.233 * k));
  }
  const ClosedCurve c(x);
  InterfaceProblem p;
  p.sigma_minus = sr;
  p.sigma_plus = 1.0;
  p.boundary = SampleBoundaryData(g, PoissonBoundaries{}, phi_exact, nullptr);
  FastIimSolver solver(g, PoissonBoundaries{});
  std::vector<double> gv, phi;
  const InterfaceSolveReport r = solver.Solve(c, p, gv, phi);
  EXPECT_LE(r.iterations, 8);
  const double g_max = (sr - 1.0) * amp;
  double err = 0.0;
  for (int k = 0; k < m; ++k) err = std::max(err, std::abs(gv[k] - g_max * std::sin(theta[k])));
  EXPECT_LT(err, 0.03 * g_max);
}

TEST(FastIimSolver, WarmStartFromSlightlyMovedInterfaceSavesIterations) {
  // The G of the previous curve is within the discretisation error of the new G, so GMRES
  // starts from a residual orders of magnitude below |b|. GMRES converges fast here anyway
  // (superlinearly, ~1 order per iteration), so the saving is a few iterations, not most.
  const InterfaceExample e = MakeInterfaceExample("3", 1000.0, 1.0);
  const Grid2D g = e.MakeGrid(160);
  const int m = e.DefaultMarkers(160);
  const ClosedCurve c0(e.Markers(m));
  FastIimOptions opt;
  opt.gmres.tolerance = 1e-10;
  FastIimSolver solver(g, PoissonBoundaries{}, opt);
  std::vector<double> gv, phi;
  solver.Solve(c0, SampleInterfaceProblem(e, g, c0), gv, phi);
  // Move the markers smoothly by about 0.01 h.
  Eigen::Matrix2Xd moved = e.Markers(m);
  for (int k = 0; k < m; ++k) {
    moved.col(k) += 0.01 * g.h * Eigen::Vector2d(1.0 + 0.5 * std::cos(2 * M_PI * k / m), 0.3);
  }
  const ClosedCurve c1(moved);
  const InterfaceProblem p1 = SampleInterfaceProblem(e, g, c1);
  const InterfaceSolveReport warm = solver.Solve(c1, p1, gv, phi);
  std::vector<double> zero_guess;
  const InterfaceSolveReport cold = solver.Solve(c1, p1, zero_guess, phi);
  EXPECT_TRUE(warm.converged);
  EXPECT_LT(warm.iterations, cold.iterations);
  for (int k = 0; k < m; ++k) EXPECT_NEAR(gv[k], zero_guess[k], 1e-8);  // same solution
}

TEST(FastIimSolver, NonConvergenceIsReportedAsSolverError) {
  const InterfaceExample e = MakeInterfaceExample("3", 1.0, 100.0);
  const Grid2D g = e.MakeGrid(40);
  const ClosedCurve c(e.Markers(e.DefaultMarkers(40)));
  FastIimOptions opt;
  opt.gmres.max_iterations = 1;
  opt.gmres.tolerance = 1e-14;
  FastIimSolver solver(g, PoissonBoundaries{}, opt);
  std::vector<double> gv, phi;
  EXPECT_THROW(solver.Solve(c, SampleInterfaceProblem(e, g, c), gv, phi), SolverError);
}

// Cylinder of radius a in E_inf = (0, -1), sigma_r = sigma^-/sigma^+ (docs/electric_solver.md):
// phi^- = 2/(1+sigma_r) y, phi^+ = y (1 + (1-sigma_r)/(1+sigma_r) a^2/r^2). Exact values are
// imposed on the box sides, so the marker fields must converge to the exact ones.
TEST(ElectricForce, CylinderFieldsAndMaxwellForceMatchExactSolution) {
  const double a = 0.5, sr = 3.0, eps_m = 2.0, eps_p = 1.0, amp = 2.0 / (1.0 + sr);
  auto phi_exact = [&](double x, double y) {
    const double r2 = x * x + y * y;
    return r2 < a * a ? amp * y : y * (1.0 + (1.0 - sr) / (1.0 + sr) * a * a / r2);
  };
  double prev = 0.0;
  for (int n : {40, 80}) {
    const Grid2D g{n, n, 2.0 / n, -1, -1};
    const int m = n * 3 / 2;
    const ClosedCurve c(CircleMarkers(m, a));
    InterfaceProblem p;
    p.sigma_minus = sr;
    p.sigma_plus = 1.0;
    p.boundary = SampleBoundaryData(g, PoissonBoundaries{}, phi_exact, nullptr);
    FastIimSolver solver(g, PoissonBoundaries{});
    std::vector<double> gv, phi;
    solver.Solve(c, p, gv, phi);
    std::vector<double> enm(m), enp(m), etm(m), etp(m);
    double err = 0;
    for (int k = 0; k < m; ++k) {
      enm[k] = -solver.normal_derivative_minus()[k];
      enp[k] = -solver.normal_derivative_plus()[k];
      etm[k] = -solver.tangential_derivative_minus()[k];
      etp[k] = -solver.tangential_derivative_plus()[k];
      const double th = 2 * M_PI * k / m;
      err = std::max({err, std::abs(enm[k] + amp * std::sin(th)),
                      std::abs(enp[k] + sr * amp * std::sin(th)),
                      std::abs(etm[k] + amp * std::cos(th))});
    }
    const Eigen::Matrix2Xd f = MaxwellForce(c, eps_m, eps_p, enm, enp, etm, etp);
    Eigen::Vector2d net(0, 0);
    double ferr = 0;
    for (int k = 0; k < m; ++k) {
      const double th = 2 * M_PI * k / m, s = std::sin(th), co = std::cos(th);
      const double fn =
          0.5 * amp * amp * (eps_p * (sr * sr * s * s - co * co) - eps_m * (s * s - co * co));
      const double ft = amp * amp * s * co * (eps_p * sr - eps_m);
      const CurvePoint cp = c.AtMarker(k);
      ferr = std::max(ferr, (f.col(k) - fn * cp.normal - ft * cp.tangent).norm());
      net += f.col(k) * 0.5 * (c.SegmentArcLength(k) + c.SegmentArcLength((k + m - 1) % m));
    }
    EXPECT_LT(err, n == 40 ? 0.05 : 0.02) << n;
    EXPECT_LT(ferr, n == 40 ? 0.1 : 0.04) << n;
    EXPECT_LT(net.norm(), 1e-10);  // symmetric markers: the cos/sin 2 theta force sums to zero
    if (n == 80) {
      EXPECT_GT(prev / err, 2.5);  // converging (first order or better)
    }
    prev = err;
  }
}

TEST(LeakyDielectricSolver, NeutralDropInUniformFieldFeelsNoNetForce) {
  // Drop of radius 1 in [-4, 4]^2 (sec. 4.2 set-up), sigma_r = 3, eps_r = 2: the net force of a
  // neutral drop vanishes; with a box 8 radii wide the fields are within a few % of the
  // unbounded cylinder solution.
  const Grid2D g{64, 64, 0.125, -4, -4};
  LeakyDielectricSolver<2> solver(g, 3.0, 1.0, 2.0, 1.0);
  solver.SetAppliedField(1.0);
  const ClosedCurve c(CircleMarkers(64, 1.0, {0.1, -0.05}));
  const InterfaceSolveReport& r = solver.Solve(c);
  EXPECT_TRUE(r.converged);
  Eigen::Vector2d net(0, 0);
  double scale = 0;
  for (int k = 0; k < 64; ++k) {
    const double dl = 0.5 * (c.SegmentArcLength(k) + c.SegmentArcLength((k + 63) % 64));
    net += solver.force().col(k) * dl;
    scale += solver.force().col(k).norm() * dl;
    const double th = 2 * M_PI * k / 64;
    EXPECT_NEAR(solver.normal_field_minus()[k], -0.5 * std::sin(th), 0.03);
  }
  EXPECT_LT(net.norm(), 0.01 * scale);
  const std::vector<std::vector<double>> field = solver.GridField();
  EXPECT_EQ(field[0].size(), g.size());
  // Far from the drop E ~ (0, -1) (the finite box keeps an O(a^2/L^2) ~ 8% perturbation).
  EXPECT_NEAR(field[1][g.index(32, 2)], -1.0, 0.12);
}

TEST(LeakyDielectricSolver, DenseMarkersAndHighConductivityRatioStillConvergeQuickly) {
  // Markers 4x denser than the grid (as an immersed boundary may use) with sigma^-/sigma^+ =
  // 100: GMRES works on control markers >= 1.5 h apart, so it needs few iterations; the field
  // inside is within the finite-box error (~10%) of the cylinder value 2/(1+sigma_r) E.
  const Grid2D g{96, 96, 1.0, -48, -48};
  LeakyDielectricSolver<2> solver(g, 100.0, 1.0, 1.0, 1.0);
  solver.SetAppliedField(0.01);
  const int m = 4 * 6 * 15;  // radius 15, spacing ~0.26 h
  const ClosedCurve c(CircleMarkers(m, 15.0));
  const InterfaceSolveReport& r = solver.Solve(c);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.iterations, 15);
  const double amp = 2.0 / 101.0 * 0.01;
  for (int k = 0; k < m; k += 7) {
    EXPECT_NEAR(solver.normal_field_minus()[k], -amp * std::sin(2 * M_PI * k / m), 0.15 * amp);
  }
}

TEST(FastIimSolver, CorrectionTermsMakeTheLocalTruncationErrorSmallAtIrregularPoints) {
  // Example 4 (phi^- = e^x cos y, phi^+ = 0, sigma = 1, so G = v exactly): apply the 5-point
  // Laplacian to the exact solution and subtract F + C. Without C the residual at irregular
  // points is O(jump / h^2); with the corrections it is the Taylor remainder of J (O(d^4 / h^2)
  // = O(h^2), cubic expansion) plus the [d_xi(f/sigma)] term, i.e. it must fall with h.
  const InterfaceExample e = MakeInterfaceExample("4");
  double previous = 0.0;
  for (int n : {40, 80}) {
    const test::InterfaceCase ic(e, n, e.Markers(e.DefaultMarkers(n)));
    const Grid2D& g = ic.grid;
    FastIimSolver solver(g, PoissonBoundaries{});
    std::vector<double> gv, phi;
    solver.Solve(ic.curve, ic.problem, gv, phi);
    const std::vector<double>& u = ic.exact;
    const auto& cls = solver.classification();
    std::vector<double> correction(g.size(), 0.0);
    for (const auto& p : cls.crossing_pairs()) {
      correction[p.centre] += p.neighbour_side * solver.band_jump()[p.neighbour_slot] / (g.h * g.h);
    }
    double with = 0.0, without = 0.0;
    for (int idx : cls.irregular_points()) {
      const int i = idx % n, j = idx / n;
      if (i == 0 || j == 0 || i == n - 1 || j == n - 1) continue;
      const double lap = (u[idx - 1] + u[idx + 1] + u[idx - n] + u[idx + n] - 4 * u[idx]) /
                         (g.h * g.h);  // f = 0 on both sides
      with = std::max(with, std::abs(lap - correction[idx]));
      without = std::max(without, std::abs(lap));
    }
    EXPECT_LT(with, 1e-2 * without) << n;
    // O(h^2) would give 4, O(h) 2; spline errors of w'' and g'' still mix in at N = 80.
    if (previous > 0.0) {
      EXPECT_GT(previous / with, 2.5) << "local error must fall faster than O(h)";
    }
    previous = with;
  }
}

TEST(FastIimSolver, ClockwiseMarkersGiveTheSameSolution) {
  // ClosedCurve orients normal and tangent by geometry, not by marker order; the IIM must be
  // invariant to reversing the markers (same curve, same problem).
  const InterfaceExample e = MakeInterfaceExample("ellipse", 1.0, 10.0);
  const Grid2D g = e.MakeGrid(48);
  const int m = e.DefaultMarkers(48);
  const Eigen::Matrix2Xd ccw = e.Markers(m);
  const Eigen::Matrix2Xd cw = ccw.rowwise().reverse();
  std::vector<double> phi[2], dt[2];
  int k = 0;
  for (const Eigen::Matrix2Xd* x : {&ccw, &cw}) {
    const ClosedCurve c(*x);
    FastIimSolver solver(g, PoissonBoundaries{});
    std::vector<double> gv;
    solver.Solve(c, SampleInterfaceProblem(e, g, c), gv, phi[k]);
    dt[k] = solver.tangential_derivative_minus();
    ++k;
  }
  for (std::size_t i = 0; i < phi[0].size(); ++i) EXPECT_NEAR(phi[0][i], phi[1][i], 1e-9);
  for (int i = 0; i < m; ++i) EXPECT_NEAR(dt[0][i], dt[1][m - 1 - i], 1e-8);  // same point
}

TEST(FastIimSolver, DenseMarkersGiveTheSameSolutionInEitherDirectionAndFromAnyStart) {
  // Markers spaced 0.8 h (denser than the 1.5 h control spacing). For sigma^+ > sigma^- every
  // marker is a control; for sigma^- > sigma^+ G is a Fourier series in arc length with the
  // residual projected on it (ControlBasis::kFourier), whose span does not depend on the first
  // marker nor on the direction. Either way reversing the markers or starting at another one is
  // the same discrete problem. Before, controls were thinned from marker 0 for every
  // sigma^- != sigma^+: on this star (sigma^+/sigma^- = 10, N = 80) the error was 2.5e-3 one
  // way and 8.2e-3 the other; now 5.4e-5 (sigma^+ > sigma^-) and 1.1e-3 (sigma^- > sigma^+; 5.6e-4
  // with as many terms as controls, 1.5 h, before the basis was limited to wavelengths >= 5 h at
  // sigma^-/sigma^+ >= 10, FastIimOptions::basis_wavelength_h: that basis stalls GMRES on
  // sharper curves).
  for (const double ratio : {0.1, 10.0}) {
    const InterfaceExample e = MakeInterfaceExample("star", ratio, 1.0);
    const Grid2D g = e.MakeGrid(80);
    const int m = 190;
    const Eigen::Matrix2Xd ccw = e.Markers(m);
    Eigen::Matrix2Xd shifted(2, m);
    for (int k = 0; k < m; ++k) shifted.col(k) = ccw.col((k + 37) % m);
    const Eigen::Matrix2Xd cw = ccw.rowwise().reverse();
    const Eigen::Matrix2Xd* orders[3] = {&ccw, &cw, &shifted};
    std::vector<double> phi[3];
    int k = 0;
    for (const Eigen::Matrix2Xd* x : orders) {
      const test::InterfaceCase c(e, 80, *x);
      FastIimSolver solver(g, PoissonBoundaries{});
      std::vector<double> gv;
      solver.Solve(c.curve, c.problem, gv, phi[k]);
      const double err = c.MaxError(phi[k]);
      EXPECT_LT(err, ratio < 1.0 ? 1e-4 : 1.5e-3) << "sigma ratio " << ratio << ", order " << k;
      ++k;
    }
    double d_cw = 0.0, d_shift = 0.0;
    for (std::size_t i = 0; i < phi[0].size(); ++i) {
      d_cw = std::max(d_cw, std::abs(phi[0][i] - phi[1][i]));
      d_shift = std::max(d_shift, std::abs(phi[0][i] - phi[2][i]));
    }
    // Same curve through the same points: what remains is the GMRES tolerance (1e-7 relative).
    EXPECT_LT(d_cw, 1e-7) << ratio;
    EXPECT_LT(d_shift, 1e-7) << ratio;
  }
}

// The reproductions of the long-run-trust issue: each solve is accurate or refused with a
// SolverError, never wrong with success.
TEST(FastIimSolver, UnresolvedTipIsRefusedNotSolvedWrong) {
  // The five-petal star at sigma^-/sigma^+ = 1000 on N = 24: its troughs have a curvature radius
  // of 0.95 h; the solver returned a max error of 9.2 on an O(1) potential with "converged".
  const InterfaceExample e = MakeInterfaceExample("star", 1000.0, 1.0);
  const Grid2D g = e.MakeGrid(24);
  const ClosedCurve c(e.Markers(e.DefaultMarkers(24)));
  FastIimSolver solver(g, PoissonBoundaries{});
  std::vector<double> gv, phi;
  try {
    solver.Solve(c, SampleInterfaceProblem(e, g, c), gv, phi);
    ADD_FAILURE() << "expected a SolverError";
  } catch (const SolverError& err) {
    // Refused by the marker-scale oscillation of [phi_n] there (the grid-scale curvature radius
    // is 1.24 h, inside the pre-check's 1 h; a tighter trough is refused before solving).
    EXPECT_NE(std::string(err.what()).find("not resolved"), std::string::npos) << err.what();
    EXPECT_NE(std::string(err.what()).find("refine the grid"), std::string::npos);
  }
}

TEST(FastIimSolver, TipsTighterThanTheGridAreAccurateOrRefusedOnEveryGrid) {
  // A star of our own, r = 0.5 + 0.18 sin(5 theta): its troughs have a curvature radius of
  // 0.0245 (h at N = 82), so on N = 60..120 the tips are at or below the grid scale. At
  // sigma^-/sigma^+ = 1000 the solver used to report success with [phi_n] off by 0.2-5.5
  // (|[phi_n]| <= 2.8) at grids chosen at random in that range. Now every grid either gives
  // [phi_n] within 5% of its maximum (the verification tolerance, plus the margin of its
  // estimate) or throws.
  InterfaceExample e = MakeInterfaceExample("star", 1000.0, 1.0);
  e.curve = [](double t) {
    const double r = 0.5 + 0.18 * std::sin(5.0 * t);
    return Eigen::Vector2d(0.02 + r * std::cos(t), 0.01 + r * std::sin(t));
  };
  int solved = 0, refused = 0;
  for (int n = 60; n <= 120; n += 4) {
    const Grid2D g = e.MakeGrid(n);
    const int m = static_cast<int>(1.25 * e.DefaultMarkers(n));
    const ClosedCurve c(e.Markers(m));
    FastIimSolver solver(g, PoissonBoundaries{});
    std::vector<double> gv, phi;
    try {
      const InterfaceSolveReport r = solver.Solve(c, SampleInterfaceProblem(e, g, c), gv, phi);
      ++solved;
      EXPECT_GE(r.estimated_error, 0.0);
      double g_err = 0.0, g_max = 0.0;
      for (int k = 0; k < m; ++k) {
        const CurvePoint p = c.AtMarker(k);
        const Eigen::Vector2d x = c.markers().col(k);
        const double exact = e.grad_plus(x).dot(p.normal) - e.grad_minus(x).dot(p.normal);
        g_err = std::max(g_err, std::abs(gv[k] - exact));
        g_max = std::max(g_max, std::abs(exact));
      }
      EXPECT_LT(g_err, 0.05 * g_max) << "N = " << n << ": accepted with [phi_n] off by " << g_err;
    } catch (const SolverError& err) {
      ++refused;
      EXPECT_NE(std::string(err.what()).find("refine the grid"), std::string::npos) << err.what();
    }
  }
  EXPECT_GT(refused, 0);  // the coarse end of the range is refused
}

TEST(FastIimSolver, HighInnerConductivityIsAccurateOnUnevenMarkers) {
  // The ellipse at sigma^-/sigma^+ = 1000, N = 80: the mean of [phi_n] is fixed by the flux
  // balance divided by sigma^+ / (sigma^- - sigma^+) = 1/999, so the O(ds^2) error of trapezoid
  // arc weights on its unevenly spaced markers was amplified into a max error of 4.3e-2 (G off
  // by 10%). With spline quadrature weights (O(ds^4)) it is 5.1e-4; bound 1e-3.
  InterfaceSolveReport r;
  const double err = SolveError(MakeInterfaceExample("ellipse", 1000.0, 1.0), 80, &r);
  EXPECT_LT(err, 1e-3);
  // The verification ran (ratio >= 10) and its estimate is an upper bound here.
  EXPECT_GT(r.estimated_error, 0.0);
  EXPECT_LT(r.estimated_error, 0.05);
}

TEST(FastIimSolver, VerificationOnlyAboveItsRatioAndRefusedWhereItCannotRun) {
  const InterfaceExample low = MakeInterfaceExample("ellipse", 4.75, 1.0);
  const InterfaceExample high = MakeInterfaceExample("ellipse", 1000.0, 1.0);
  for (int n : {96, 33}) {
    const Grid2D g = low.MakeGrid(n);
    const ClosedCurve c(low.Markers(low.DefaultMarkers(n)));
    std::vector<double> gv, phi;
    FastIimSolver a(g, PoissonBoundaries{});
    EXPECT_EQ(a.Solve(c, SampleInterfaceProblem(low, g, c), gv, phi).estimated_error, -1.0);
    FastIimSolver b(g, PoissonBoundaries{});
    gv.clear();
    if (n % 2 == 0) {
      EXPECT_GE(b.Solve(c, SampleInterfaceProblem(high, g, c), gv, phi).estimated_error, 0.0);
    } else {
      // An odd grid cannot be coarsened twice: at 1000:1 the answer cannot be verified.
      EXPECT_THROW(b.Solve(c, SampleInterfaceProblem(high, g, c), gv, phi), SolverError);
    }
  }
}

// sigma^- = 1000 sigma^+ on five-petal stars with troughs of curvature radius 2 h at the coarsest
// grid (star_tight: 0.0245 = 2 h at N = 164; star_sharp, petals 0.4 of the mean radius: 0.0191 =
// 2 h at N = 209): G in the Fourier basis of wavelengths >= 5 h (basis_wavelength_h). Every
// solve passes the solver's own checks (resolution, oscillation, the verifying coarse solve),
// [phi_n] is within the verification tolerance of the exact jump, converges at order >= 1.8, and
// GMRES needs a bounded number of iterations. With as many terms as controls (the basis before),
// star_tight took 185 iterations at N = 160 and did not converge in 400 at N = 224 and 320.
TEST(FastIimSolver, SharpStarsAtHighInnerConductivityConvergeWithBoundedIterations) {
  for (const auto& [name, grids] :
       {std::pair<const char*, std::pair<int, int>>{"star_tight", {224, 320}},
        {"star_sharp", {224, 320}}}) {
    const InterfaceExample e = MakeInterfaceExample(name, 1000.0, 1.0);
    double error[2];
    int i = 0;
    for (const int n : {grids.first, grids.second}) {
      const Grid2D g = e.MakeGrid(n);
      const ClosedCurve c(e.Markers(e.DefaultMarkers(n)));
      FastIimSolver solver(g, PoissonBoundaries{});
      std::vector<double> gv, phi;
      InterfaceSolveReport r;
      ASSERT_NO_THROW(r = solver.Solve(c, SampleInterfaceProblem(e, g, c), gv, phi))
          << name << " N = " << n;
      EXPECT_LE(r.iterations, 25) << name << " N = " << n;
      EXPECT_LT(r.estimated_error, 0.05) << name << " N = " << n;
      error[i] = JumpNormalDerivativeError(e, c, gv);
      EXPECT_LT(error[i], 0.05) << name << " N = " << n;
      ++i;
    }
    const double order =
        std::log(error[0] / error[1]) / std::log(double(grids.second) / grids.first);
    EXPECT_GE(order, 1.8) << name << ": [phi_n] errors " << error[0] << ", " << error[1];
  }
}

}  // namespace
}  // namespace ehd
