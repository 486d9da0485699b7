// Fast IIM cost: wall ms per Solve (median of repeats, plans made beforehand) against N for
// example 3 of song2019 sec. 2.5 at sigma^-/sigma^+ = 1/10 and 10, GMRES iterations, Poisson
// solves per Solve, ms / (N^2 log2 N); then cold vs warm start after moving the markers by
// ~0.01 h (a smooth displacement).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ehd_capsule/electric/fast_iim_solver.h"
#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/reference/interface_examples.h"

int main() {
  using namespace ehd;
  std::printf("%8s %5s %7s %5s %7s %10s %16s\n", "sm/sp", "N", "markers", "iter", "solves",
              "ms/solve", "ns/(N^2 log2 N)");
  for (double ratio : {0.1, 10.0}) {
    const InterfaceExample e =
        MakeInterfaceExample("3", ratio >= 1 ? ratio : 1.0, ratio >= 1 ? 1.0 : 1.0 / ratio);
    for (int n : {40, 80, 160, 320, 640}) {
      const Grid2D g = e.MakeGrid(n);
      const ClosedCurve c(e.Markers(e.DefaultMarkers(n)));
      const InterfaceProblem p = SampleInterfaceProblem(e, g, c);
      FastIimSolver solver(g, PoissonBoundaries{});
      std::vector<double> gv, phi;
      std::vector<double> times;
      InterfaceSolveReport r;
      for (int rep = 0; rep < 7; ++rep) {
        gv.clear();
        r = solver.Solve(c, p, gv, phi);
        times.push_back(r.solve_ms);
      }
      std::nth_element(times.begin(), times.begin() + 3, times.end());
      std::printf("%8g %5d %7d %5d %7d %10.2f %16.2f\n", ratio, n, c.size(), r.iterations,
                  solver.poisson_solves(), times[3],
                  times[3] * 1e6 / (double(n) * n * std::log2(n)));
    }
  }
  std::printf("\nwarm start reusing |b| (markers moved by ~0.01 h), GMRES tolerance 1e-7, 1e-10\n");
  std::printf("%8s %5s %7s %10s %10s %9s %9s\n", "sm/sp", "N", "tol", "cold iter", "warm iter",
              "cold ms", "warm ms");
  for (double tol : {1e-7, 1e-10}) {
    for (double ratio : {0.001, 0.1, 10.0, 1000.0}) {
      const InterfaceExample e =
          MakeInterfaceExample("3", ratio >= 1 ? ratio : 1.0, ratio >= 1 ? 1.0 : 1.0 / ratio);
      const int n = 160;
      const Grid2D g = e.MakeGrid(n);
      const int m = e.DefaultMarkers(n);
      const ClosedCurve c0(e.Markers(m));
      FastIimOptions opt;
      opt.gmres.tolerance = tol;
      opt.warm_start_refresh = 20;  // reuse |b| of the cold solve
      FastIimSolver solver(g, PoissonBoundaries{}, opt);
      std::vector<double> gv, phi;
      solver.Solve(c0, SampleInterfaceProblem(e, g, c0), gv, phi);
      Eigen::Matrix2Xd moved = e.Markers(m);
      for (int k = 0; k < m; ++k) {
        moved.col(k) += 0.01 * g.h * Eigen::Vector2d(1.0 + 0.5 * std::cos(2 * M_PI * k / m), 0.3);
      }
      const ClosedCurve c1(moved);
      const InterfaceProblem p1 = SampleInterfaceProblem(e, g, c1);
      const InterfaceSolveReport warm = solver.Solve(c1, p1, gv, phi);
      std::vector<double> zero;
      const InterfaceSolveReport cold = solver.Solve(c1, p1, zero, phi);
      std::printf("%8g %5d %7.0e %10d %10d %9.2f %9.2f\n", ratio, n, tol, cold.iterations,
                  warm.iterations, cold.solve_ms, warm.solve_ms);
    }
  }
  std::printf(
      "\nleaky dielectric drop (R = 20, 126 markers, 160^2 lattice grid, E = 0.01) "
      "deformed by ~0.01 h: cold, warm (default: |b| recomputed), warm reusing |b| "
      "(warm_start_refresh = 20)\n");
  std::printf("%8s %7s %10s %10s %10s %9s %9s %9s\n", "sm/sp", "tol", "cold iter", "warm iter",
              "reuse iter", "cold ms", "warm ms", "reuse ms");
  for (double tol : {1e-7, 1e-10}) {
    for (double sr : {0.001, 0.1, 3.0, 10.0, 1000.0}) {
      const int n = 160, m = 126;
      const double radius = 20.0;
      const Grid2D g{n, n, 1.0, -n / 2.0, -n / 2.0};
      auto drop = [&](double shift) {
        Eigen::Matrix2Xd x(2, m);
        for (int k = 0; k < m; ++k) {
          const double t = 2 * M_PI * k / m, r = radius + shift * std::cos(2 * t);
          x.col(k) << r * std::cos(t) + 0.3 * shift, r * std::sin(t);
        }
        return ClosedCurve(x);
      };
      InterfaceSolveReport report[3];
      for (int mode = 0; mode < 2; ++mode) {
        FastIimOptions iim;
        iim.gmres.tolerance = tol;
        iim.warm_start_refresh = mode == 0 ? 0 : 20;
        LeakyDielectricSolver<2> solver(g, sr, 1.0, 2.0, 1.0, iim);
        solver.SetAppliedField(0.01);
        solver.Solve(drop(0.0));
        report[mode + 1] = solver.Solve(drop(0.01));
        if (mode == 0) {
          solver.set_warm_start({});
          report[0] = solver.Solve(drop(0.01));
        }
      }
      std::printf("%8g %7.0e %10d %10d %10d %9.2f %9.2f %9.2f\n", sr, tol, report[0].iterations,
                  report[1].iterations, report[2].iterations, report[0].solve_ms,
                  report[1].solve_ms, report[2].solve_ms);
    }
  }
  return 0;
}
