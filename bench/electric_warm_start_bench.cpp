// Warm starts of the leaky dielectric solve along a time series (issue #3: "with a warm start
// from a slightly moved interface ... report both"). A drop of radius 20 (126 markers, 160^2
// lattice grid, E = 0.01) translates and deforms smoothly; consecutive solves are `move` cells
// apart (largest marker displacement). For each sigma_r and move: mean GMRES iterations per solve
// over 20 solves for a cold start, the plain warm start (previous G, LeakyDielectricSolver<2>::
// Solve(curve)) and the extrapolated one (Solve(curve, time)), the error of each starting guess
// relative to max |G|, and ms per solve. Tolerance 1e-7 relative to |b| (the default).
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/geometry/closed_curve.h"

namespace {

using ehd::ClosedCurve;

constexpr int kMarkers = 126;
constexpr double kRadius = 20.0;

// Unit of s: markers move by ~0.6 h (translation 0.6 h, deformation amplitude 0.02 h per unit
// plus a slow rotation of the deformation).
ClosedCurve DropAt(double s) {
  Eigen::Matrix2Xd x(2, kMarkers);
  for (int k = 0; k < kMarkers; ++k) {
    const double th = 2 * M_PI * k / kMarkers;
    const double r = kRadius + (1.0 + 0.02 * s) * std::cos(2 * (th - 0.05 * s));
    x.col(k) << r * std::cos(th) + 0.6 * s, r * std::sin(th) + 0.2 * s;
  }
  return ClosedCurve(x);
}

double MaxAbs(const std::vector<double>& a) {
  double d = 0.0;
  for (double v : a) d = std::max(d, std::abs(v));
  return d;
}

double MaxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

}  // namespace

int main() {
  using namespace ehd;
  const Grid2D grid{160, 160, 1.0, -80, -80};
  const int solves = 20;
  std::printf(
      "leaky drop R = 20, %d markers, 160^2 grid, E = 0.01, GMRES tolerance 1e-7; %d solves "
      "after 2 start-up solves\n",
      kMarkers, solves);
  std::printf("%8s %7s %10s %10s %10s %12s %12s %9s %9s %9s\n", "sigma_r", "move/h", "cold it",
              "warm it", "extrap it", "warm g err", "extrap g err", "cold ms", "warm ms",
              "extrap ms");
  for (double sigma_r : {0.001, 0.1, 3.0, 10.0, 1000.0}) {
    for (double move : {0.01, 0.05, 0.2}) {
      const double ds = move / 0.63;  // largest displacement per unit s ~ 0.63 h
      LeakyDielectricSolver<2> cold(grid, sigma_r, 1.0, 2.0, 1.0);
      LeakyDielectricSolver<2> warm(grid, sigma_r, 1.0, 2.0, 1.0);
      LeakyDielectricSolver<2> extrapolated(grid, sigma_r, 1.0, 2.0, 1.0);
      for (LeakyDielectricSolver<2>* s : {&cold, &warm, &extrapolated}) s->SetAppliedField(0.01);
      double it[3] = {0, 0, 0}, ms[3] = {0, 0, 0}, guess_error[2] = {0, 0};
      std::vector<double> g_prev, g_prev2;
      for (int step = 0; step < solves + 2; ++step) {
        const ClosedCurve c = DropAt(5.0 + step * ds);
        cold.set_warm_start({});
        const InterfaceSolveReport rc = cold.Solve(c);
        const InterfaceSolveReport rw = warm.Solve(c);
        const InterfaceSolveReport re = extrapolated.Solve(c, step);
        const std::vector<double>& g = cold.warm_start().g;
        if (step >= 2) {
          it[0] += rc.iterations;
          it[1] += rw.iterations;
          it[2] += re.iterations;
          ms[0] += rc.solve_ms;
          ms[1] += rw.solve_ms;
          ms[2] += re.solve_ms;
          std::vector<double> guess(g.size());
          for (std::size_t k = 0; k < g.size(); ++k) guess[k] = 2 * g_prev[k] - g_prev2[k];
          guess_error[0] = std::max(guess_error[0], MaxAbsDifference(g_prev, g) / MaxAbs(g));
          guess_error[1] = std::max(guess_error[1], MaxAbsDifference(guess, g) / MaxAbs(g));
        }
        g_prev2 = g_prev;
        g_prev = g;
      }
      std::printf("%8g %7.2f %10.2f %10.2f %10.2f %12.2e %12.2e %9.2f %9.2f %9.2f\n", sigma_r, move,
                  it[0] / solves, it[1] / solves, it[2] / solves, guess_error[0], guess_error[1],
                  ms[0] / solves, ms[1] / solves, ms[2] / solves);
    }
  }
  return 0;
}
