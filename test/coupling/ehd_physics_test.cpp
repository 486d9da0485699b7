// Physical trends of the coupled EHD step on tiny grids (the measured tables are in
// docs/validation_ehd.md; these are the fast checks of their signs).
//
// 1. Induced circulation of a leaky-dielectric drop (song2019 sec. 4.2.2; Taylor 1966): inside
//    the drop the field is uniform, E^- = E0 e_y, and current continuity sigma+ E+_n = sigma- E-_n
//    gives the free surface charge q = eps+ E+_n - eps- E-_n = (sigma_r - eps_r) E-_n (eps+ =
//    sigma+ = 1). The tangential electric stress q E_t = (sigma_r - eps_r) E0^2 sin(phi) cos(phi)
//    along the counter-clockwise tangent is, in the first quadrant, clockwise for sigma_r < eps_r
//    (Cases A, B) and counter-clockwise for sigma_r > eps_r (Case C); the surface drags the
//    interior the same way, so the vorticity integrated over the first quadrant of the drop has
//    the sign of sigma_r - eps_r. That is the steady flow: while the drop deforms (t < ~4 mu a /
//    gamma at N = 48) the shape-change flow can dominate (Case C turns clockwise first), so the
//    check is made at t = 8, when D is within 2% of its steady value.
// 2. Capsule in shear and field (sec. 4.3, 5.1): the field alone aligns an oblate-type capsule
//    (Case A, f_d < 0) across the field (theta -> 0) and a prolate-type one (Case C, f_d > 0)
//    along it (theta -> pi/2), so with shear Case A tilts toward the flow and Case C toward the
//    field relative to Ca_E = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/scene/scene.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

Scene DropScene(double sigma_r) {
  return test::TinyScene(2).Name("ehd_drop").Drop().AtRest(1).Field(0.4, sigma_r).Grid(48).Build();
}

Scene CapsuleScene(double sigma_r, double ca_e) {
  return test::TinyScene(2)
      .Name("ehd_capsule")
      .With("Ca", 0.04)
      .With("Re", 0.05)
      .Field(ca_e, sigma_r)
      .Build();
}

// Vorticity du_y/dx - du_x/dy integrated over x > 0, y > 0, r < 0.8 a (central differences).
double FirstQuadrantCirculation(const Simulation& sim) {
  const Grid2D& g = sim.grid();
  const auto& ux = sim.ux();
  const auto& uy = sim.uy();
  const double a = sim.units().radius;
  double total = 0.0;
  for (int j = 1; j < g.ny - 1; ++j) {
    for (int i = 1; i < g.nx - 1; ++i) {
      const double x = g.x(i), y = g.y(j);
      if (x <= 0 || y <= 0 || x * x + y * y >= 0.64 * a * a) continue;
      const int c = j * g.nx + i;
      total += 0.5 * (uy[c + 1] - uy[c - 1]) - 0.5 * (ux[c + g.nx] - ux[c - g.nx]);
    }
  }
  return total;
}

double RunDropCirculation(double sigma_r) {
  Simulation sim(DropScene(sigma_r));
  while (sim.state().time < 8.0) sim.Step();
  return FirstQuadrantCirculation(sim);
}

TEST(EhdPhysics, InducedCirculationHasTheSignOfSigmaRMinusEpsR) {
  EXPECT_LT(RunDropCirculation(1.75), 0.0) << "Case A: sigma_r < eps_r, clockwise";
  EXPECT_LT(RunDropCirculation(3.25), 0.0) << "Case B: sigma_r < eps_r, clockwise";
  EXPECT_GT(RunDropCirculation(4.75), 0.0) << "Case C: sigma_r > eps_r, counter-clockwise";
}

double RunCapsuleInclination(double sigma_r, double ca_e) {
  Simulation sim(CapsuleScene(sigma_r, ca_e));
  while (sim.state().time < 1.5) sim.Step();
  return sim.state().inclination;
}

TEST(EhdPhysics, CaseATiltsTowardTheFlowAndCaseCTowardTheField) {
  const double theta0 = RunCapsuleInclination(1.75, 0.0);
  const double theta_a = RunCapsuleInclination(1.75, 0.3);
  const double theta_c = RunCapsuleInclination(4.75, 0.3);
  EXPECT_GT(theta0, 0.0);
  EXPECT_LT(theta0, M_PI / 4);  // a capsule in shear alone leans below 45 degrees
  EXPECT_LT(theta_a, theta0 - 0.01 * M_PI) << "Case A (f_d < 0) should tilt toward the flow";
  EXPECT_GT(theta_c, theta0 + 0.01 * M_PI) << "Case C (f_d > 0) should tilt toward the field";
}

}  // namespace
}  // namespace ehd
