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
// 3. The 3D leaky-dielectric drop (docs/validation_3d_ehd.md, "Theory" and "Deformation"):
//    oblate for Taylor's Phi < 0 (Case A), prolate for Phi > 0 (Case C), D linear in Ca_E and of
//    Taylor's size (its first-order transient, on a tiny grid).
// 4. Its circulation (the same page's table): the surface flows from the poles to the equator
//    for Q > R (Cases A, B), the other way for Q < R (Case C), with Taylor's dependence on the
//    case; Case B is prolate with the circulation of an oblate drop.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/scene/scene.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

Scene DropScene(double sigma_r) {
  return test::TinyScene(2).Name("ehd_drop").Drop().AtRest(1).Field(0.4, sigma_r).Grid(48).Build();
}

// The capsule has a = 4 cells: in the field its tips reach a curvature radius of ~1.5 h, where
// the interface solver's fit-agreement check (cubic against quadratic phi_n^-) measures up to
// 0.26 by t = 1.5 (0.12 on N = 48; second order), above the default 0.1 that refuses the
// potential as unresolved there (it would stop the run at step 903). The test asks only for the
// sign of the tilt, so it raises the limit rather than refine the grid (N = 64 would take
// minutes).
Scene CapsuleScene(double sigma_r, double ca_e) {
  test::TinyScene scene(2);
  scene.Name("ehd_capsule").With("Ca", 0.04).With("Re", 0.05).Field(ca_e, sigma_r);
  if (ca_e > 0) scene.With("electric.max_fit_disagreement", 0.3);
  return scene.Build();
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

// The 3D drop in a field along z (the scene electric_drop_3d's physics, docs/validation_3d_ehd.md:
// "Theory" gives D = 9 Ca_E Phi / (16 (2 + R)^2), "Deformation" claims the sign of Phi and D
// linear in Ca_E, doubling Ca_E doubling D to 1 %). Tiny: a = 4 cells on 20^3, walls and field
// faces at L = 2.5 a, Oh = 1, lambda = 1, to t = 4 mu a / gamma (2.8 s for the four runs on one
// core). D is the state's d_field. At first order a drop relaxes to Taylor's D as
// D(t) = D_T (1 - exp(-t / tau)), tau = (2 lambda + 3)(19 lambda + 16) / (40 (lambda + 1)) =
// 2.1875 mu a / gamma (the l = 2 shape mode; the field's charge relaxes at once in the model).
// Measured at t = 4.01: Case A (R = 1.75, Phi = -5.56) D = -0.008101 / -0.016145 at Ca_E = 0.05 /
// 0.1, -13.3 / -13.6 % from that transient; Case C (R = 4.75, Phi = +18.4) D = +0.009037 /
// +0.018300, -5.5 / -4.3 %; the ratio D(0.1) / D(0.05) 1.993 (A) and 2.025 (C), the O(Ca_E^2)
// term of D. The a = 8 runs at L = 2.5 a give -12.6 % (A) and -0.9 % (C) at steady state (the
// table "With the retracted immersed boundary"): A's error is there at a = 8 too (the box and the
// retraction more than this grid). Tolerances: D within 20 % of the transient (A's -14 % with
// room), and the ratio within 3 % of 2 (the measured 1.3 % with room; a field scaled with Ca_E
// instead of sqrt(Ca_E) would give 4). Shown once by scaling the electric stage's load: x 1.3
// fails (Case C +25.4 %), x 2 fails (+97 %), x -1 fails (every sign); x 1.2 passes (C +15.4 %).
double TaylorDropD(double sigma_r, double eps_r, double ca_e) {
  const double lambda = 1.0, r = sigma_r, q = eps_r;
  const double phi = r * r + 1 - 2 * q + 3 * (r - q) * (2 + 3 * lambda) / (5 * (1 + lambda));
  return 9 * ca_e * phi / (16 * (2 + r) * (2 + r));
}

// The state of the tiny drop in a field at t_end.
SimulationState RunDrop3DTo(double sigma_r, double ca_e, double t_end) {
  Simulation sim(test::TinyScene(3)
                     .Name("tiny_electric_drop3d")
                     .Drop()
                     .AtRest(1)
                     .Field(ca_e, sigma_r, 3.5)
                     .With("geometry.half_width", 2.5)
                     .Grid(20)
                     .With("numerics.electric_every", 50)
                     .With("numerics.electric_move_tolerance", 0.02)
                     .With("numerics.ib_kernel", "roma3")  // as measured
                     .Build());
  while (sim.state().time < t_end) sim.Step();
  return sim.state();
}

// d_field and the time reached, of the tiny drop in a field after t = 4.
std::pair<double, double> RunDrop3D(double sigma_r, double ca_e) {
  const SimulationState state = RunDrop3DTo(sigma_r, ca_e, 4.0);
  return {state.d_field, state.time};
}

TEST(EhdPhysics, Drop3DDeformsWithTheSignOfPhiAndLinearlyInCaE) {
  const double tau = (2 + 3) * (19 + 16) / (40.0 * 2);  // lambda = 1
  for (const double sigma_r : {1.75, 4.75}) {
    SCOPED_TRACE(sigma_r);
    double d[2];
    for (int k = 0; k < 2; ++k) {
      const double ca_e = 0.05 * (k + 1);
      const auto [d_field, t] = RunDrop3D(sigma_r, ca_e);
      const double expected = TaylorDropD(sigma_r, 3.5, ca_e) * (1 - std::exp(-t / tau));
      std::printf(
          "3D drop sigma_r = %.2f, Ca_E = %.2f: D = %+.6f at t = %.3f, Taylor's transient "
          "%+.6f (%+.1f %%)\n",
          sigma_r, ca_e, d_field, t, expected, 100 * (d_field / expected - 1));
      EXPECT_GT(d_field * expected, 0.0) << "D must have the sign of Taylor's Phi";
      EXPECT_NEAR(d_field, expected, 0.2 * std::abs(expected));
      d[k] = d_field;
    }
    std::printf("  D(0.1) / D(0.05) = %.4f\n", d[1] / d[0]);
    EXPECT_NEAR(d[1] / d[0], 2.0, 0.06);
  }
}

// Taylor's surface flow U = 9 Ca_E (Q - R) / (5 (1 + lambda) (2 + R)^2), lambda = 1, in a per
// mu a / gamma (docs/validation_3d_ehd.md, "Theory"): > 0 from the poles to the equator.
double TaylorDropU(double sigma_r, double eps_r, double ca_e) {
  return 9 * ca_e * (eps_r - sigma_r) / (5 * 2 * (2 + sigma_r) * (2 + sigma_r));
}

// The circulation's sign for Cases A, B, C and Case B's deformation (docs/validation_3d_ehd.md:
// Case B, R = 3.25 < Q = 3.5 and Phi = +4.19, is prolate yet flows from the poles to the equator
// like an oblate drop; D within 10 % of Taylor, as C; A within 15 %, as its -12.6 % in the page's
// table at a = 8 in this box, an open item there). The tiny drop of RunDrop3DTo at Ca_E = 0.1 to
// t = 12 mu a / gamma (5.5 tau: D within 0.5 % of its steady value; 5 s for the three runs on one
// core at load 4.7). The steady flow is needed: while the drop stretches into a prolate shape the
// stretching drags the surface to the poles, and Case B's surface_flow is negative until t = 6.5
// (measured -0.00048 at t = 4, +0.00015 at t = 8). Measured at t = 12: D = -0.019406 (A), +0.008268
// (B), +0.022833 (C), -12.4 / -2.9 / +0.7 % from Taylor's transient; surface_flow = +0.003436 (A),
// +0.000266 (B), -0.000829 (C), 0.307 / 0.325 / 0.336 of Taylor's U. That fraction is the immersed
// boundary's (the kernel smooths the velocity's kink at r = a: 0.6 at a = 8 with roma3, about a
// third at this a = 4) and the same in every case: the three fractions within 15 % of their mean
// (measured 4.9 %) check surface_flow against Taylor's (Q - R) / (2 + R)^2. Shown once: the
// electric stage's tangential load scaled by (2 + R) / 5.25 (a traction off by a factor 2 + R, Case
// B unchanged) gives fractions 0.222 / 0.325 / 0.395 (-29 % and +26 % from the mean), A's D off by
// 24 %, and fails; a common factor on all cases would pass this check (the signs and D remain).
TEST(EhdPhysics, Drop3DCirculationHasTheSignOfQMinusRAndCaseBIsProlate) {
  const double ca_e = 0.1, eps_r = 3.5, t_end = 12.0;
  const double tau = (2 + 3) * (19 + 16) / (40.0 * 2);  // lambda = 1
  const double sigma_r[3] = {1.75, 3.25, 4.75};
  double fraction[3];
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE(sigma_r[c]);
    const SimulationState state = RunDrop3DTo(sigma_r[c], ca_e, t_end);
    const double d = TaylorDropD(sigma_r[c], eps_r, ca_e) * (1 - std::exp(-state.time / tau));
    const double u = TaylorDropU(sigma_r[c], eps_r, ca_e);
    fraction[c] = state.surface_flow / u;
    std::printf(
        "3D drop sigma_r = %.2f at t = %.3f: D = %+.6f (Taylor's transient %+.6f, %+.1f %%), "
        "surface_flow = %+.6f (Taylor %+.6f, fraction %.3f)\n",
        sigma_r[c], state.time, state.d_field, d, 100 * (state.d_field / d - 1), state.surface_flow,
        u, fraction[c]);
    EXPECT_GT(state.d_field * d, 0.0) << "D must have the sign of Taylor's Phi";
    EXPECT_GT(state.surface_flow * u, 0.0) << "the circulation must have the sign of Q - R";
    EXPECT_NEAR(state.d_field, d, (c == 0 ? 0.15 : 0.1) * std::abs(d));
  }
  const double mean = (fraction[0] + fraction[1] + fraction[2]) / 3;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(fraction[c], mean, 0.15 * mean) << "sigma_r = " << sigma_r[c];
  }
}

}  // namespace
}  // namespace ehd
