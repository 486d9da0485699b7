// SteadyStateMonitor on signals with a known answer.
#include "ehd_capsule/coupling/steady_state.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ehd {
namespace {

// D(t) = 1 - exp(-t) (theta constant): the change over the last unit of time is
// exp(-(t - 1)) - exp(-t) = (e - 1) exp(-t), below TOL once t > ln((e - 1) / TOL). Sampled every
// dt, the first steady sample lies within dt of that time.
TEST(SteadyStateMonitor, ExponentialApproachStopsWhenTheTheoryPredicts) {
  const double tol = 1e-3, dt = 1e-3;
  SteadyStateMonitor monitor(tol);
  double t_stop = -1;
  for (int n = 0; n < 20000; ++n) {
    const double t = n * dt;
    if (monitor.Update(t, 1 - std::exp(-t), 0.3)) {
      t_stop = t;
      break;
    }
  }
  EXPECT_NEAR(t_stop, std::log((std::exp(1.0) - 1) / tol), 2 * dt);
}

// A signal that oscillates with amplitude 0.01 in theta (tumbling-like) is never steady at a
// tolerance below its peak-to-peak range 0.02, and is at a tolerance above it.
TEST(SteadyStateMonitor, OscillationIsNotSteady) {
  SteadyStateMonitor strict(0.015), loose(0.025);
  bool strict_steady = false, loose_steady = false;
  for (int n = 0; n < 5000; ++n) {
    const double t = n * 1e-3;
    const double theta = 0.5 + 0.01 * std::sin(2 * M_PI * 3 * t);
    strict_steady |= strict.Update(t, 0.2, theta);
    loose_steady |= loose.Update(t, 0.2, theta);
  }
  EXPECT_FALSE(strict_steady);
  EXPECT_TRUE(loose_steady);
  EXPECT_THROW(SteadyStateMonitor(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
