// The correction function method (song2019 sec. 2.3) as a whole: consistency of the corrected
// 5-point stencil, second-order convergence in the max norm on the sec. 2.3.5 examples and on
// non-circular curves, and refusal of unequal conductivities.
#include "ehd_capsule/reference/correction_function_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "ehd_capsule/electric/gmres.h"
#include "ehd_capsule/reference/interface_examples.h"

namespace ehd {
namespace {

struct SolveRun {
  double max_error = 0.0;
  double max_residual = 0.0;  // of the corrected stencil applied to the exact solution
  int irregular = 0;
  int failed = 0;
};

SolveRun SolveExample(const std::string& name, int n, CfmBasis basis = CfmBasis::kBicubic) {
  const InterfaceExample example = MakeInterfaceExample(name);
  const Grid2D grid = example.MakeGrid(n);
  const ClosedCurve curve(example.Markers(example.DefaultMarkers(n)));
  const InterfaceProblem problem = SampleInterfaceProblem(example, grid, curve);
  CorrectionFunctionOptions options;
  options.basis = basis;
  CorrectionFunctionSolver solver(grid, PoissonBoundaries{}, options);
  std::vector<double> phi;
  solver.Solve(curve, problem, phi);
  const std::vector<double> exact = ExactSolution(example, grid, curve);
  SolveRun run;
  run.irregular = solver.irregular_points();
  run.failed = solver.failed_patches();
  for (std::size_t k = 0; k < exact.size(); ++k) {
    run.max_error = std::max(run.max_error, std::abs(phi[k] - exact[k]));
  }
  // Residual of L_h u = f/sigma + C on the exact solution at interior points.
  const double sigma = problem.sigma_minus;
  for (int j = 1; j < grid.ny - 1; ++j) {
    for (int i = 1; i < grid.nx - 1; ++i) {
      const std::size_t c = grid.index(i, j);
      const double lap =
          (exact[c + 1] + exact[c - 1] + exact[c + grid.nx] + exact[c - grid.nx] - 4.0 * exact[c]) /
          (grid.h * grid.h);
      const double residual = lap - problem.f[c] / sigma - solver.correction()[c];
      run.max_residual = std::max(run.max_residual, std::abs(residual));
    }
  }
  return run;
}

// Second order: the bicubic correction function is O(h^4), so C_ij is O(h^2) and the corrected
// scheme has an O(h^2) truncation error everywhere; the max-norm error then halves twice per
// halving of h (observed order ~2; the reference's CFM tables 1-2 show 1.4-3.3 per step because
// the circle's position relative to the grid changes, so we require > 1.6 over a two-step span).
void ExpectSecondOrder(const std::string& name) {
  const int sizes[3] = {40, 80, 160};
  SolveRun runs[3];
  for (int r = 0; r < 3; ++r) {
    runs[r] = SolveExample(name, sizes[r]);
    EXPECT_EQ(runs[r].failed, 0) << name << " N = " << sizes[r];
    EXPECT_GT(runs[r].irregular, 0);
  }
  const double order = 0.5 * std::log2(runs[0].max_error / runs[2].max_error);
  const double residual_order = 0.5 * std::log2(runs[0].max_residual / runs[2].max_residual);
  std::printf(
      "%-8s errors %.3e %.3e %.3e  order %.2f | stencil residual %.3e %.3e %.3e order %.2f\n",
      name.c_str(), runs[0].max_error, runs[1].max_error, runs[2].max_error, order,
      runs[0].max_residual, runs[1].max_residual, runs[2].max_residual, residual_order);
  EXPECT_GT(order, 1.6) << name;
  // Consistency: the corrected stencil's truncation error is O(h^2) at every point, irregular
  // ones included (an uncorrected or wrongly signed stencil gives O(1/h) there).
  EXPECT_GT(residual_order, 1.6) << name;
  EXPECT_LT(runs[2].max_error, 1e-3) << name;
}

TEST(CorrectionFunctionSolver, SecondOrderOnCfmExample1) { ExpectSecondOrder("cfm1"); }

TEST(CorrectionFunctionSolver, DeferredCorrectionBeatsTable1OnCfmExample1) {
  // song2019 Table 1 (this problem, same h): 2.29e-4 / 9.11e-5 / 1.84e-5 at N = 40 / 80 / 160.
  // The plain CFM sits at the regular 5-point truncation floor of phi^+ = 1 + log 2r (3.2e-4 /
  // 7.8e-5 / 1.9e-5, above the table at N = 40 and 160); with the deferred correction (T from
  // the first solution on one-sided arms) the O(h^2) regular truncation is cancelled, so the
  // error drops below the table and the order over 40 -> 160 exceeds 2.5 (what is left is
  // O(h^3): the ~2-cell band without T, the box ghost).
  const InterfaceExample example = MakeInterfaceExample("cfm1");
  const double table[3] = {2.29e-4, 9.11e-5, 1.84e-5};
  double err[3];
  int level = 0;
  for (int n : {40, 80, 160}) {
    const Grid2D grid = example.MakeGrid(n);
    const ClosedCurve curve(example.Markers(example.DefaultMarkers(n)));
    CorrectionFunctionOptions options;
    options.deferred_correction = true;
    CorrectionFunctionSolver solver(grid, PoissonBoundaries{}, options);
    std::vector<double> phi;
    solver.Solve(curve, SampleInterfaceProblem(example, grid, curve), phi);
    const std::vector<double> exact = ExactSolution(example, grid, curve);
    err[level] = 0.0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
      err[level] = std::max(err[level], std::abs(phi[k] - exact[k]));
    }
    EXPECT_LT(err[level], table[level]) << "N = " << n;
    ++level;
  }
  EXPECT_GT(0.5 * std::log2(err[0] / err[2]), 2.5);
}
TEST(CorrectionFunctionSolver, DeferredCorrectionIsRobustOnNonCircularCurves) {
  // The deferred correction must not depend on luck with the curve: on the ellipse and the
  // five-petal star (f and [f] != 0) it raises the order over 40 -> 160 above 2.5 and is more
  // accurate than the plain solve at N = 160 (measured: 23x on the ellipse, 1.5x on the star,
  // whose petals leave little regular region at N = 160). A version that continued arms across
  // Sigma with the patches' D jumped to 1e-2 at some N on these curves.
  for (const char* name : {"ellipse", "star"}) {
    const InterfaceExample example = MakeInterfaceExample(name);
    double err[2][2];
    for (int deferred = 0; deferred < 2; ++deferred) {
      int level = 0;
      for (int n : {40, 160}) {
        const Grid2D grid = example.MakeGrid(n);
        const ClosedCurve curve(example.Markers(example.DefaultMarkers(n)));
        CorrectionFunctionOptions options;
        options.deferred_correction = deferred == 1;
        CorrectionFunctionSolver solver(grid, PoissonBoundaries{}, options);
        std::vector<double> phi;
        solver.Solve(curve, SampleInterfaceProblem(example, grid, curve), phi);
        const std::vector<double> exact = ExactSolution(example, grid, curve);
        double e = 0.0;
        for (std::size_t k = 0; k < exact.size(); ++k) e = std::max(e, std::abs(phi[k] - exact[k]));
        err[deferred][level++] = e;
      }
    }
    EXPECT_GT(0.5 * std::log2(err[1][0] / err[1][1]), 2.5) << name;
    EXPECT_LT(err[1][1], err[0][1]) << name;
  }
}
TEST(CorrectionFunctionSolver, SecondOrderOnCfmExample2) { ExpectSecondOrder("cfm2"); }
TEST(CorrectionFunctionSolver, SecondOrderOnEllipse) { ExpectSecondOrder("ellipse"); }
TEST(CorrectionFunctionSolver, SecondOrderOnStar) { ExpectSecondOrder("star"); }

// The text's own basis (modified bilinear, sec. 2.3.4) is also second order in practice (song2019
// Tables 1-2 show orders 1.4-3.3 per step, average ~2); on the ellipse, with [f] != 0 and a
// varying jump, we require > 1.6 over two halvings.
TEST(CorrectionFunctionSolver, ModifiedBilinearBasisIsSecondOrderOnEllipse) {
  const double e40 = SolveExample("ellipse", 40, CfmBasis::kModifiedBilinear).max_error;
  const double e160 = SolveExample("ellipse", 160, CfmBasis::kModifiedBilinear).max_error;
  EXPECT_GT(0.5 * std::log2(e40 / e160), 1.6) << e40 << " " << e160;
}

// Without correction the 5-point scheme cannot see [phi] = w: on cfm2 ([phi] = y^2 - x^2, up to
// 0.25) a solver that ignored the jumps would be O(1) wrong. This guards the sign of C_ij.
TEST(CorrectionFunctionSolver, CorrectionCarriesTheJump) {
  const SolveRun run = SolveExample("cfm2", 40);
  EXPECT_LT(run.max_error, 0.01);
}

TEST(CorrectionFunctionSolver, RefusesUnequalConductivities) {
  const InterfaceExample example = MakeInterfaceExample("cfm1");
  const Grid2D grid = example.MakeGrid(16);
  const ClosedCurve curve(example.Markers(32));
  InterfaceProblem problem = SampleInterfaceProblem(example, grid, curve);
  problem.sigma_plus = 2.0;
  CorrectionFunctionSolver solver(grid, PoissonBoundaries{});
  std::vector<double> phi;
  try {
    solver.Solve(curve, problem, phi);
    FAIL() << "sigma^+ != sigma^- accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sigma_minus = 1"), std::string::npos) << what;
    EXPECT_NE(what.find("sigma_plus = 2"), std::string::npos) << what;
  }
  problem.sigma_plus = 1.0;
  problem.w.resize(5);
  EXPECT_THROW(solver.Solve(curve, problem, phi), std::invalid_argument);
}

}  // namespace
}  // namespace ehd

namespace ehd {
namespace {

// Convergence/timing table for docs/correction_function_method.md (not a default test: run with
// --gtest_also_run_disabled_tests --gtest_filter='*Table*'). CFM_TABLE_BASIS=bilinear selects
// the modified bilinear basis of song2019 sec. 2.3.4.
TEST(CorrectionFunctionSolver, DISABLED_ConvergenceTable) {
  const char* basis_name = std::getenv("CFM_TABLE_BASIS");
  CorrectionFunctionOptions options;
  if (basis_name != nullptr && std::string(basis_name) == "bilinear") {
    options.basis = CfmBasis::kModifiedBilinear;
  }
  std::printf("basis: %s\n", options.basis == CfmBasis::kBicubic ? "bicubic" : "modified bilinear");
  for (const std::string name : {"cfm1", "cfm2", "ellipse", "star"}) {
    std::printf("\nexample %s\n%6s %8s %14s %8s %10s %10s\n", name.c_str(), "N", "markers",
                "Linf error", "order", "ms/solve", "irregular");
    double previous = 0.0;
    for (const int n : {20, 40, 80, 160, 320, 640}) {
      const InterfaceExample example = MakeInterfaceExample(name);
      const Grid2D grid = example.MakeGrid(n);
      const int markers = example.DefaultMarkers(n);
      const ClosedCurve curve(example.Markers(markers));
      const InterfaceProblem problem = SampleInterfaceProblem(example, grid, curve);
      CorrectionFunctionSolver solver(grid, PoissonBoundaries{}, options);
      std::vector<double> phi;
      solver.Solve(curve, problem, phi);  // warm-up
      const int repeats = n <= 160 ? 10 : 3;
      double ms = 0.0;
      for (int r = 0; r < repeats; ++r) ms += solver.Solve(curve, problem, phi).solve_ms;
      const std::vector<double> exact = ExactSolution(example, grid, curve);
      double error = 0.0;
      for (std::size_t k = 0; k < exact.size(); ++k) {
        error = std::max(error, std::abs(phi[k] - exact[k]));
      }
      char order[16] = "-";
      if (previous > 0.0) std::snprintf(order, sizeof order, "%.2f", std::log2(previous / error));
      std::printf("%6d %8d %14.5e %8s %10.2f %10d\n", n, markers, error, order, ms / repeats,
                  solver.irregular_points());
      previous = error;
    }
  }
}

}  // namespace
}  // namespace ehd
