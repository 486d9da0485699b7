// The tiny 2D capsule of CapsuleSmallCa (a = 4, 32 markers, Ca = 0.0025, Re = 0.2) with the roma3
// kernel grows tangential modes at the grid Nyquist and stops on the Mach watchdog at one
// membrane substep (t = 5.3), and runs to t = 20 with two (docs/validation_3d.md, "The kernel";
// a slower growth still stops it at t = 25, which no limit here covers): the grid-Nyquist limit
// (membrane_stability.h) refuses the first with advice to substep and accepts the second; the
// cosine kernel (the default) is accepted at one substep. roma3_even_odd, which does not couple
// to that mode, is accepted at one substep and runs with a flat Mach number to t = 40, where
// roma3 with two substeps stopped at t = 25 (docs/validation_3d.md, "Damping the grid-Nyquist
// mode").
#include <gtest/gtest.h>

#include <string>

#include "ehd_capsule/coupling/simulation.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

test::TinyScene SmallCaCapsule() { return test::TinyScene::SmallCaCapsule(0.0025); }

TEST(KernelStabilityLimit, Roma3CapsuleNeedsTwoSubsteps) {
  std::string what;
  try {
    Simulation sim(SmallCaCapsule().Build({"numerics.ib_kernel=roma3"}));
    FAIL() << "roma3 at one substep accepted";
  } catch (const SceneError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("grid-Nyquist"), std::string::npos) << what;
  EXPECT_NE(what.find("numerics.membrane_substeps >= 2"), std::string::npos) << what;
  EXPECT_NO_THROW(Simulation(
      SmallCaCapsule().Build({"numerics.ib_kernel=roma3", "numerics.membrane_substeps=2"})));
  EXPECT_NO_THROW(Simulation(SmallCaCapsule().Build()));
}

TEST(KernelStabilityLimit, Roma3EvenOddCapsuleRunsLongAtOneSubstep) {
  Simulation sim(SmallCaCapsule().Build({"numerics.ib_kernel=roma3_even_odd"}));
  double mach_at_10 = 0.0;
  while (sim.state().time < 40.0) {
    sim.Step();  // throws on the Mach watchdog
    if (mach_at_10 == 0.0 && sim.state().time >= 10.0) mach_at_10 = sim.state().max_mach;
  }
  EXPECT_NEAR(sim.state().max_mach, mach_at_10, 1e-4 * mach_at_10);
  EXPECT_LT(sim.state().area_drift, 0.02);
}

}  // namespace
}  // namespace ehd
