// The 2D Hookean capsule in shear against the project's own boundary-element solution
// (docs/validation_fsi.md section 2c: reference/stokes_bie.h, viscosity ratio 1, unbounded,
// Re = 0, the same MembraneModel force; its self-checks against exact drop results are
// test/reference/stokes_bie_test.cpp). The docs' table was made at the points (+3.0 to +3.3 % at
// a = 16 cells, N = 128, walls at +-4a, Re = 0.05); with the retracted default of issue #42 the
// full form below measured, at t = 6: D_xy +0.92 / +1.23 / -1.16 % from the BEM at Ca = 0.0125 /
// 0.05 / 0.2, theta/pi 0.0007 / 0.0026 / 0.0051 below it (about 20 min of one core under load).
//
// The short form runs a = 8 cells (N = 64), Ca = 0.05, to t = 4 (the BEM's D is within 2 % of its
// steady value from t = 1.25): D_xy 0.37797 against the BEM's 0.38158 (-0.95 %), theta/pi
// 0.14207 against 0.14302. At a = 8 the coarse grid's large-strain stiffness (D too small, issue
// #42) shows; at a = 4 it is -13 %. The test holds D to 2.5 % and theta/pi to 0.005 of the BEM.
// D ~ Ca^0.3 here, so the band sees a modulus error of about 10 % and more: shown once with the
// LBM's Ca off by 15 % (0.0575 / 0.0425: D at t = 4 +3.0 % / -5.6 % from the BEM, theta/pi
// -0.0053 / +0.004), and a = 4's -13 % fails it too.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/reference/stokes_bie.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

const double kPi = std::acos(-1.0);

struct Shape {
  double dxy = 0, theta = 0;
};

// The BEM capsule (mu = k = a = 1, E_s = 1 / Ca) at time t_end, M = 64 markers (M = 128 moves D
// by 4e-4 relative, docs/validation_fsi.md), Heun with dt = 1 / sigma_max of the bench's
// estimate (capsule_bem_bench --cfl 1, its default).
Shape BoundaryElementShape(double ca, double t_end) {
  const int markers = 64;
  MembraneParameters p;
  p.shear_modulus = 1.0 / ca;
  bie::CapsuleBem bem(p, CircleMarkers(markers, 1.0), 1.0, 1.0);
  const double dl = 2.0 * kPi / markers;
  const double dt = 1.0 / (1.5 * p.shear_modulus * kPi / (4.0 * dl));
  while (bem.time() < t_end - 1e-12) bem.Step(dt);
  const bie::SpectralShape s = bie::MeasureSpectralShape(bem.layer(), bem.markers());
  return {s.dxy, s.inclination};
}

// The shipped capsule_shear scene's settings (Re = 0.05, tau = 1, forward Euler, walls at +-4a)
// at a = n / 8 cells.
Shape LatticeShape(double ca, int n, double t_end) {
  Simulation sim(test::TinyScene(2)
                     .Name("capsule_bem")
                     .With("Ca", ca)
                     .With("Re", 0.05)
                     .Grid(n)
                     .With("numerics.tau", 1.0)
                     .With("numerics.integrator", "forward_euler")
                     .With("numerics.threads", 1)
                     .Build());
  while (sim.state().time < t_end) sim.Step();
  return {sim.state().dxy, sim.state().inclination};
}

TEST(CapsuleBem, CapsuleMatchesBoundaryElementsAtEightCells) {
  const double ca = 0.05, t_end = 4.0;
  const Shape bem = BoundaryElementShape(ca, t_end), lbm = LatticeShape(ca, 64, t_end);
  std::printf("Ca = %g, t = %g: D_xy LBM (a = 8) %.5f BEM %.5f (%+.2f %%); theta/pi %.5f %.5f\n",
              ca, t_end, lbm.dxy, bem.dxy, 100.0 * (lbm.dxy / bem.dxy - 1.0), lbm.theta / kPi,
              bem.theta / kPi);
  // The BEM itself against the docs' table (M = 256, steady): 0.38156, theta/pi 0.14266.
  EXPECT_NEAR(bem.dxy, 0.38156, 0.005 * 0.38156);
  EXPECT_NEAR(lbm.dxy / bem.dxy, 1.0, 0.025);
  EXPECT_NEAR(lbm.theta / kPi, bem.theta / kPi, 0.005);
}

// a = 16 cells (N = 128), t = 6: D_xy within 2 % of the BEM (measured +0.92 / +1.23 / -1.16 % at
// Ca = 0.0125 / 0.05 / 0.2), theta/pi within 0.008 below it (measured 0.0007-0.0051). About 5
// min of one core on an idle machine.
TEST(CapsuleBem, FullCapsuleMatchesBoundaryElements) {
  for (double ca : {0.0125, 0.05, 0.2}) {
    const double t_end = 6.0;
    const Shape bem = BoundaryElementShape(ca, t_end), lbm = LatticeShape(ca, 128, t_end);
    std::printf("Ca = %g: D_xy LBM (a = 16) %.5f BEM %.5f (%+.2f %%); theta/pi %.5f %.5f\n", ca,
                lbm.dxy, bem.dxy, 100.0 * (lbm.dxy / bem.dxy - 1.0), lbm.theta / kPi,
                bem.theta / kPi);
    EXPECT_NEAR(lbm.dxy / bem.dxy, 1.0, 0.02) << "Ca " << ca;
    EXPECT_LT(lbm.theta / kPi, bem.theta / kPi + 0.001) << "Ca " << ca;
    EXPECT_GT(lbm.theta / kPi, bem.theta / kPi - 0.008) << "Ca " << ca;
  }
}

}  // namespace
}  // namespace ehd
