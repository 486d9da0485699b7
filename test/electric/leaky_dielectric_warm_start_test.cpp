// Warm starts of the leaky dielectric solve in a time-stepping setting
// (LeakyDielectricSolver::Solve(curve, time), SetAppliedField rescaling).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/geometry/closed_curve.h"

namespace ehd {
namespace {

constexpr int kMarkers = 126;
constexpr double kRadius = 20.0;

// A drop of radius 20 (lattice units) that translates and deforms smoothly with time:
// x = r(t, theta) (cos, sin) + (0.6 t, 0.2 t) h, r = R + 0.02 t cos 2 theta. One unit of time moves
// the markers by ~0.6 h, one step of 1/60 by ~0.01 h (what a marker does in an LBM step).
ClosedCurve DropAt(double t) {
  Eigen::Matrix2Xd x(2, kMarkers);
  for (int k = 0; k < kMarkers; ++k) {
    const double th = 2 * M_PI * k / kMarkers, r = kRadius + 0.02 * t * std::cos(2 * th);
    x.col(k) << r * std::cos(th) + 0.6 * t, r * std::sin(th) + 0.2 * t;
  }
  return ClosedCurve(x);
}

double MaxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  return d;
}

double MaxAbs(const std::vector<double>& a) {
  double d = 0.0;
  for (double v : a) d = std::max(d, std::abs(v));
  return d;
}

const Grid2D kGrid{128, 128, 1.0, -64, -64};

// The starting guess a solver would use at time t2 after converged solves at t0 and t1: a third
// solve with a GMRES tolerance so loose that it stops at 0 iterations returns the guess itself.
std::vector<double> StartingGuess(double dt, bool timed) {
  FastIimOptions tight;
  tight.gmres.tolerance = 1e-12;
  LeakyDielectricSolver<2> converged(kGrid, 3.0, 1.0, 2.0, 1.0, tight);
  converged.SetAppliedField(0.01);
  for (int s = 0; s < 2; ++s) {
    if (timed) {
      converged.Solve(DropAt(5.0 + s * dt), s);
    } else {
      converged.Solve(DropAt(5.0 + s * dt));
    }
  }
  // The same state in a solver whose GMRES stops at once (the checkpoint's warm-start state).
  FastIimOptions loose;
  loose.gmres.tolerance = 0.9;
  LeakyDielectricSolver<2> solver(kGrid, 3.0, 1.0, 2.0, 1.0, loose);
  solver.SetAppliedField(0.01);
  solver.set_warm_start(converged.warm_start());
  const InterfaceSolveReport r =
      timed ? solver.Solve(DropAt(5.0 + 2 * dt), 2.0) : solver.Solve(DropAt(5.0 + 2 * dt));
  EXPECT_EQ(r.iterations, 0);
  return solver.warm_start().g;
}

TEST(LeakyDielectricWarmStart, ExtrapolatedGuessIsSecondOrderInTheTimeStep) {
  // G(t) is smooth in t, so the previous G alone misses G(t2) by O(dt) and the linear
  // extrapolation Solve(curve, time) starts from by O(dt^2): halving dt must cut the first error
  // ~2x and the second ~4x, and at dt = 1/60 (markers ~0.01 h per solve) the extrapolated guess
  // must be far closer (< 1/5) than the plain one. The guesses are the solver's own (read back
  // from a 0-iteration solve); the reference is G(t2) converged to 1e-12.
  FastIimOptions tight;
  tight.gmres.tolerance = 1e-12;
  double plain_error[2], extrapolated_error[2];
  int level = 0;
  for (double dt : {1.0 / 30, 1.0 / 60}) {
    LeakyDielectricSolver<2> reference(kGrid, 3.0, 1.0, 2.0, 1.0, tight);
    reference.SetAppliedField(0.01);
    reference.Solve(DropAt(5.0 + 2 * dt));
    const std::vector<double>& g2 = reference.warm_start().g;
    plain_error[level] = MaxAbsDifference(StartingGuess(dt, false), g2);
    extrapolated_error[level] = MaxAbsDifference(StartingGuess(dt, true), g2);
    ++level;
  }
  EXPECT_GT(plain_error[0] / plain_error[1], 1.6);
  EXPECT_LT(plain_error[0] / plain_error[1], 2.5);
  EXPECT_GT(extrapolated_error[0] / extrapolated_error[1], 3.0);
  EXPECT_LT(extrapolated_error[1], 0.2 * plain_error[1]);
}

TEST(LeakyDielectricWarmStart, TimedSolvesNeedFewerIterationsAndAgreeWithColdSolves) {
  // Markers moving ~0.01 h per solve (dt = 1/60): after two timed solves the extrapolated start
  // leaves 0-2 GMRES iterations (0, 0, 1, 2, 1, 1 with the Fourier basis of G, 0, 0, 1, 1, 1, 1
  // with spline controls: the least-squares projection of the guess on the moved curve's basis
  // costs an iteration now and then), fewer in all than the plain warm start (untimed Solve), and
  // every result agrees with a cold solve to the GMRES tolerance (1e-7 relative to |b|, i.e.
  // differences ~1e-6 of max |G|).
  const double dt = 1.0 / 60;
  LeakyDielectricSolver<2> timed(kGrid, 3.0, 1.0, 2.0, 1.0);
  LeakyDielectricSolver<2> untimed(kGrid, 3.0, 1.0, 2.0, 1.0);
  LeakyDielectricSolver<2> cold(kGrid, 3.0, 1.0, 2.0, 1.0);
  for (LeakyDielectricSolver<2>* s : {&timed, &untimed, &cold}) s->SetAppliedField(0.01);
  int timed_iterations = 0, untimed_iterations = 0, cold_iterations = 0;
  for (int s = 0; s < 8; ++s) {
    const ClosedCurve c = DropAt(5.0 + s * dt);
    const int it_timed = timed.Solve(c, s).iterations;
    const int it_untimed = untimed.Solve(c).iterations;
    cold.set_warm_start({});
    const int it_cold = cold.Solve(c).iterations;
    EXPECT_LT(MaxAbsDifference(timed.warm_start().g, cold.warm_start().g),
              1e-5 * MaxAbs(cold.warm_start().g))
        << "solve " << s;
    if (s >= 2) {
      EXPECT_LE(it_timed, 2) << "solve " << s;
      timed_iterations += it_timed;
      untimed_iterations += it_untimed;
      cold_iterations += it_cold;
    }
  }
  EXPECT_LT(timed_iterations, untimed_iterations);
  EXPECT_LT(untimed_iterations, cold_iterations);
}

TEST(LeakyDielectricWarmStart, NewFieldStrengthRescalesTheStartingGuess) {
  // G is linear in E (f = w = v = 0, box data E y): on the same curve, doubling E makes the
  // rescaled previous G the solution, so GMRES stops at once, where a cold start needs >= 3.
  LeakyDielectricSolver<2> solver(kGrid, 3.0, 1.0, 2.0, 1.0);
  const ClosedCurve c = DropAt(1.0);
  solver.SetAppliedField(0.01);
  solver.Solve(c, 0.0);
  const std::vector<double> g_half = solver.warm_start().g;
  solver.SetAppliedField(0.02);
  const InterfaceSolveReport warm = solver.Solve(c, 1.0);
  EXPECT_EQ(warm.iterations, 0);
  EXPECT_TRUE(warm.converged);
  for (int k = 0; k < kMarkers; ++k) {
    EXPECT_NEAR(solver.warm_start().g[k], 2 * g_half[k], 1e-6 * MaxAbs(g_half));
  }
  solver.set_warm_start({});
  EXPECT_GE(solver.Solve(c).iterations, 3);
}

TEST(LeakyDielectricWarmStart, HistoryRoundTripsAndIsForgottenByAnUntimedSolve) {
  LeakyDielectricSolver<2> solver(kGrid, 3.0, 1.0, 2.0, 1.0);
  solver.SetAppliedField(0.01);
  solver.Solve(DropAt(0.0), 10.0);
  solver.Solve(DropAt(0.02), 12.0);
  const LeakyDielectricSolver<2>::WarmStart h = solver.warm_start();
  EXPECT_EQ(h.time_previous, 10.0);
  EXPECT_EQ(h.time_last, 12.0);
  EXPECT_EQ(h.g_previous.size(), static_cast<std::size_t>(kMarkers));
  EXPECT_EQ(h.g.size(), static_cast<std::size_t>(kMarkers));
  solver.Solve(DropAt(0.04));  // untimed: forgets the history, keeps G1
  EXPECT_TRUE(solver.warm_start().g_previous.empty());
  EXPECT_TRUE(std::isnan(solver.warm_start().time_last));
  EXPECT_EQ(solver.warm_start().g.size(), static_cast<std::size_t>(kMarkers));
  solver.set_warm_start(h);
  EXPECT_EQ(solver.warm_start().time_last, 12.0);
  EXPECT_EQ(solver.warm_start().g, h.g);
}

}  // namespace
}  // namespace ehd
