// Flow validation of LatticeBoltzmann2D (song2019 section 3.1.1, forcing eqs. (107)-(108)) against
// exact Navier-Stokes solutions, plus the class's contract (validation, restart, threads).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "ehd_capsule/lbm/d2q9.h"
#include "ehd_capsule/lbm/lattice_boltzmann.h"

namespace ehd {
namespace {

constexpr double kPi = 3.14159265358979323846;

double Mass(const LatticeBoltzmann2D& lb) {
  const auto& f = lb.populations();
  return std::accumulate(f.begin(), f.end(), 0.0);
}

TEST(LatticeBoltzmann2D, RejectsTauAtOrBelowOneHalfNamingTheParameter) {
  for (double nu : {0.0, -0.01}) {
    LbmParameters p;
    p.nx = p.ny = 8;
    p.viscosity = nu;
    try {
      LatticeBoltzmann2D lb(p);
      FAIL() << "viscosity " << nu << " accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("viscosity"), std::string::npos) << what;
      EXPECT_NE(what.find("tau > 0.5"), std::string::npos) << what;
    }
  }
  LbmParameters p;
  p.nx = 0;
  p.ny = 8;
  EXPECT_THROW(LatticeBoltzmann2D{p}, std::invalid_argument);
  p.nx = 8;
  p.s_q = 2.0;
  EXPECT_THROW(LatticeBoltzmann2D{p}, std::invalid_argument);
  p.s_q = 1.9;
  LatticeBoltzmann2D lb(p);
  std::vector<double> nu(64, 0.1);
  nu[5] = -1.0;
  EXPECT_THROW(lb.SetViscosityField(nu), std::invalid_argument);
  EXPECT_THROW(lb.SetViscosityField(std::vector<double>(3, 0.1)), std::invalid_argument);
  EXPECT_THROW(lb.SetPopulations(std::vector<double>(10, 0.1)), std::invalid_argument);
}

TEST(LatticeBoltzmann2D, GridIsCentredWithWallsOnTheEdges) {
  LbmParameters p;
  p.nx = 10;
  p.ny = 6;
  const Grid2D g = LatticeBoltzmann2D(p).grid();
  EXPECT_EQ(g.x0, -5.0);
  EXPECT_EQ(g.y0, -3.0);
  EXPECT_EQ(g.h, 1.0);
  EXPECT_EQ(g.y(0), -2.5);  // first fluid node half a spacing above the bottom wall
}

TEST(LatticeBoltzmann2D, PlaneCouetteIsExactWithMovingWalls) {
  // Half-way bounce-back with the moving-wall term reproduces a linear profile exactly (the
  // Chapman-Enskog stress of a linear flow has no higher-order term): start at rest, walls at
  // -/+U, steady state u(y) = 2U y / H to round-off. The density is not exactly uniform: the
  // quadratic equilibria (e^eq = -2 rho + 3 u^2) make it vary at O(Ma^2), bounded by U^2.
  LbmParameters p;
  p.nx = 4;
  p.ny = 16;
  p.viscosity = 1.0 / 6.0;
  p.boundary = FluidBoundary::kShearWalls;
  const double wall_u = 0.02;
  p.wall_velocity_bottom = -wall_u;
  p.wall_velocity_top = wall_u;
  LatticeBoltzmann2D lb(p);
  for (int s = 0; s < 6000; ++s) lb.Step();  // e-folding time H^2/(pi^2 nu) ~ 156 steps
  const Grid2D g = lb.grid();
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      EXPECT_NEAR(lb.ux()[g.index(i, j)], 2.0 * wall_u * g.y(j) / g.height(), 1e-15);
      EXPECT_NEAR(lb.uy()[g.index(i, j)], 0.0, 1e-15);
      EXPECT_NEAR(lb.rho()[g.index(i, j)], 1.0, wall_u * wall_u);
    }
  }
}

TEST(LatticeBoltzmann2D, InitializeShearIsHeldExactly) {
  // The consistent initial state (equilibrium + Chapman-Enskog stress) of u = (k y, 0) is the
  // steady Couette solution up to the O(Ma^2) density adjustment of the previous test (rho = 1 is
  // imposed initially), so the velocity may move by at most O(Ma^2) relative, u_max^3; without
  // the stress term it would relax by O(k) near the walls. InitializeShear sets the walls to
  // -/+kH/2. Mass is conserved by the collision and by the moving walls (sum w_i c_i.u_w = 0).
  LbmParameters p;
  p.nx = 32;
  p.ny = 24;
  p.viscosity = 0.1;
  LatticeBoltzmann2D lb(p);
  const double k = 1e-3;
  lb.InitializeShear(k);
  EXPECT_DOUBLE_EQ(lb.parameters().wall_velocity_top, k * 12.0);
  EXPECT_DOUBLE_EQ(lb.parameters().wall_velocity_bottom, -k * 12.0);
  const double mass0 = Mass(lb);
  for (int s = 0; s < 200; ++s) lb.Step();
  const Grid2D g = lb.grid();
  double max_error = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      max_error = std::max(max_error, std::abs(lb.ux()[g.index(i, j)] - k * g.y(j)));
      max_error = std::max(max_error, std::abs(lb.uy()[g.index(i, j)]));
    }
  }
  const double u_max = k * 11.5;
  EXPECT_LT(max_error, u_max * u_max * u_max);
  EXPECT_NEAR(Mass(lb), mass0, 1e-13 * mass0);
  EXPECT_NEAR(lb.MaxSpeed(), u_max, u_max * u_max * u_max);
}

// Steady force-driven channel between resting walls at y = +-H/2 (nx = 3 columns, periodic x):
// Navier-Stokes gives u(y) = F/(2 nu) (H^2/4 - y^2). For two-relaxation-time-like schemes with
// half-way bounce-back and Guo forcing the discrete solution is that parabola with the effective
// half-width^2 H^2/4 + (16 Lambda - 3)/12, Lambda = (1/s_nu - 1/2)(1/s_q - 1/2) (Ginzburg &
// d'Humieres, PRE 68 066614 (2003); Ginzburg, Adv. Water Res. 28 (2005)) - exact for
// Lambda = 3/16. The split forcing (107)-(108) equals Guo's scheme with q^eq shifted by
// (1/s_q - 1/2) F, which bounce-back turns into an extra uniform slip -(1/s_q - 1/2) F.
double PoiseuilleMaxError(ForcingScheme forcing, double nu, double s_q, double* u_center) {
  LbmParameters p;
  p.nx = 3;
  p.ny = 16;
  p.viscosity = nu;
  p.s_q = s_q;
  p.forcing = forcing;
  p.boundary = FluidBoundary::kShearWalls;
  LatticeBoltzmann2D lb(p);
  const double force = 1e-5, half = 8.0;
  const Grid2D g = lb.grid();
  std::vector<double> ux(g.size()), uy(g.size(), 0.0);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      ux[g.index(i, j)] = force / (2 * nu) * (half * half - g.y(j) * g.y(j));
    }
  }
  lb.InitializeVelocity({ux, uy});
  for (double& v : lb.force_x()) v = force;
  const int steps = static_cast<int>(40 * 4 * half * half / (kPi * kPi * nu));  // 40 e-folds
  for (int s = 0; s < steps; ++s) lb.Step();
  const double s_nu = d2q9::ShearRateFromViscosity(nu);
  const double lambda = (1 / s_nu - 0.5) * (1 / s_q - 0.5);
  double slip = force * (16 * lambda - 3) / (24 * nu);
  if (forcing == ForcingScheme::kSplitMomentum) slip -= (1 / s_q - 0.5) * force;
  double max_error = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    const double exact = force / (2 * nu) * (half * half - g.y(j) * g.y(j));
    max_error = std::max(max_error, std::abs(lb.ux()[g.index(1, j)] - exact - slip));
  }
  *u_center = force / (2 * nu) * half * half;
  return max_error;
}

TEST(LatticeBoltzmann2D, ForceDrivenPoiseuilleMatchesTheParabola) {
  for (double nu : {0.05, 1.0 / 6.0, 0.5}) {
    const double s_nu = d2q9::ShearRateFromViscosity(nu);
    const double magic_s_q = 1.0 / ((3.0 / 16.0) / (1 / s_nu - 0.5) + 0.5);  // Lambda = 3/16
    for (double s_q : {1.9, magic_s_q}) {
      for (ForcingScheme forcing : {ForcingScheme::kSplitMomentum, ForcingScheme::kGuo}) {
        double u_center = 0.0;
        const double error = PoiseuilleMaxError(forcing, nu, s_q, &u_center);
        EXPECT_LT(error, 1e-10 * u_center) << "nu " << nu << " s_q " << s_q;
      }
    }
  }
}

TEST(LatticeBoltzmann2D, TwoLayerCouetteWithViscosityJump) {
  // Walls at -/+U, nu_1 below y = 0 and nu_2 above. Continuity of velocity and shear stress
  // (rho nu du/dy) gives a piecewise-linear profile with slopes k_1 nu_1 = k_2 nu_2 and
  // k_1 + k_2 = 4U/H. The jump sits on the link between the two middle rows; the discrete
  // stress across that link is continuous (each node relaxes its own p_xy), so like the one-layer
  // Couette flow the piecewise-linear profile is reproduced to round-off.
  LbmParameters p;
  p.nx = 3;
  p.ny = 32;
  p.boundary = FluidBoundary::kShearWalls;
  const double wall_u = 0.01, nu1 = 0.05, nu2 = 0.4, h = 32.0;
  p.wall_velocity_bottom = -wall_u;
  p.wall_velocity_top = wall_u;
  LatticeBoltzmann2D lb(p);
  const Grid2D g = lb.grid();
  std::vector<double> nu(g.size());
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) nu[g.index(i, j)] = g.y(j) < 0 ? nu1 : nu2;
  }
  lb.SetViscosityField(nu);
  lb.InitializeAtRest();
  for (int s = 0; s < 40000; ++s) lb.Step();
  const double k1 = 4 * wall_u / (h * (1 + nu1 / nu2)), k2 = k1 * nu1 / nu2;
  const double u_interface = wall_u - k2 * h / 2;
  double max_error = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    const double y = g.y(j);
    const double exact = u_interface + (y < 0 ? k1 : k2) * y;
    max_error = std::max(max_error, std::abs(lb.ux()[g.index(1, j)] - exact));
  }
  std::printf("two-layer Couette: max error %.3e of wall speed %.3e (k1 %.3e, k2 %.3e)\n",
              max_error, wall_u, k1, k2);
  EXPECT_LT(max_error, 1e-12 * wall_u);  // observed exact to round-off, as for one layer
}

}  // namespace
}  // namespace ehd

namespace ehd {
namespace {

// A non-trivial forced state used by the contract tests below: a vortex-like force in a box.
void FillSwirlForce(LatticeBoltzmann2D& lb, double amplitude) {
  const Grid2D g = lb.grid();
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.x(i) / g.width(), y = g.y(j) / g.height();
      lb.force_x()[g.index(i, j)] = -amplitude * y * std::exp(-20 * (x * x + y * y));
      lb.force_y()[g.index(i, j)] = amplitude * x * std::exp(-20 * (x * x + y * y));
    }
  }
}

TEST(LatticeBoltzmann2DContract, ClosedBoxConservesMassAndStaysAtRestWithoutForce) {
  // Resting bounce-back walls on four sides: nothing crosses them, so the total mass is exact
  // (to round-off) even while a force stirs the fluid; without force the rest state is kept.
  LbmParameters p;
  p.nx = 40;
  p.ny = 30;
  p.viscosity = 0.1;
  p.boundary = FluidBoundary::kClosedBox;
  LatticeBoltzmann2D lb(p);
  for (int s = 0; s < 50; ++s) lb.Step();
  EXPECT_EQ(lb.MaxSpeed(), 0.0);
  const double mass0 = Mass(lb);
  FillSwirlForce(lb, 1e-4);
  for (int s = 0; s < 500; ++s) lb.Step();
  EXPECT_GT(lb.MaxSpeed(), 1e-4);
  EXPECT_NEAR(Mass(lb), mass0, 1e-12 * mass0);
  EXPECT_TRUE(lb.AllFinite());
  // The wall nodes see no-slip: velocity next to the side walls is much smaller than inside.
  const Grid2D g = lb.grid();
  EXPECT_LT(std::abs(lb.uy()[g.index(0, g.ny / 2)]), 0.5 * lb.MaxSpeed());
}

TEST(LatticeBoltzmann2DContract, RestartFromPopulationsContinuesBitForBit) {
  // The state of the scheme is the post-collision populations plus the (caller-held) force, so
  // restoring them must reproduce the continued run exactly.
  LbmParameters p;
  p.nx = 48;
  p.ny = 32;
  p.viscosity = 0.08;
  p.forcing = ForcingScheme::kGuo;
  LatticeBoltzmann2D a(p);
  a.InitializeShear(2e-4);
  FillSwirlForce(a, 5e-5);
  for (int s = 0; s < 30; ++s) a.Step();
  const std::vector<double> saved = a.populations();
  const long saved_step = a.step();
  LatticeBoltzmann2D b(p);
  b.force_x() = a.force_x();
  b.force_y() = a.force_y();
  b.SetWallVelocities(a.parameters().wall_velocity_bottom, a.parameters().wall_velocity_top);
  b.SetPopulations(saved);
  b.SetStep(saved_step);
  for (std::size_t k = 0; k < a.ux().size(); ++k) {
    EXPECT_NEAR(b.ux()[k], a.ux()[k], 1e-16);  // moments re-summed: round-off only
    EXPECT_NEAR(b.rho()[k], a.rho()[k], 1e-15);
  }
  for (int s = 0; s < 30; ++s) {
    a.Step();
    b.Step();
  }
  EXPECT_EQ(a.populations(), b.populations());
  EXPECT_EQ(a.ux(), b.ux());
  EXPECT_EQ(a.step(), b.step());
}

TEST(LatticeBoltzmann2DContract, OneAndTwoThreadsGiveIdenticalResults) {
  // Each node's update reads only the previous buffer, so the row split cannot change a bit.
  LbmParameters p;
  p.nx = 128;  // >= 2 x 8192 nodes, so the kernel really uses two threads
  p.ny = 130;
  p.viscosity = 0.05;
  LatticeBoltzmann2D one(p), two([&] {
    LbmParameters q = p;
    q.threads = 2;
    return q;
  }());
  p.threads = 1;
  one = LatticeBoltzmann2D(p);
  for (LatticeBoltzmann2D* lb : {&one, &two}) {
    lb->InitializeShear(1e-4);
    FillSwirlForce(*lb, 1e-4);
    std::vector<double> nu(lb->grid().size(), 0.05);
    for (std::size_t k = 0; k < nu.size() / 2; ++k) nu[k] = 0.2;
    lb->SetViscosityField(nu);
    for (int s = 0; s < 20; ++s) lb->Step();
  }
  EXPECT_EQ(one.populations(), two.populations());
}

// A band update must leave the solver exactly where a full SetViscosityField of the same field
// would: nodes outside the band keep their rate, nodes inside take the new one.
TEST(LatticeBoltzmann2DContract, BandViscosityUpdateEqualsFullUpdate) {
  LbmParameters p;
  p.nx = 32;
  p.ny = 32;
  p.viscosity = 0.05;
  p.threads = 1;
  LatticeBoltzmann2D full(p), band(p);
  std::vector<double> nu(full.grid().size(), 0.05);
  for (std::size_t k = 0; k < nu.size() / 2; ++k) nu[k] = 0.2;
  std::vector<double> moved = nu;
  std::vector<std::size_t> changed;
  for (std::size_t k = nu.size() / 2 - 64; k < nu.size() / 2 + 64; ++k) {
    moved[k] = 0.12;
    changed.push_back(k);
  }
  EXPECT_THROW(band.UpdateViscosityField(moved, changed), std::logic_error);
  full.SetViscosityField(moved);
  band.SetViscosityField(nu);
  band.UpdateViscosityField(moved, changed);
  for (LatticeBoltzmann2D* lb : {&full, &band}) {
    lb->InitializeShear(1e-4);
    FillSwirlForce(*lb, 1e-4);
    for (int s = 0; s < 10; ++s) lb->Step();
  }
  EXPECT_EQ(full.populations(), band.populations());
  moved[changed.front()] = 0.0;  // tau = 1/2: refused, naming the node
  EXPECT_THROW(band.UpdateViscosityField(moved, changed), std::invalid_argument);
}

TEST(LatticeBoltzmann2DContract, StreamingStoresGiveIdenticalResults) {
  // Streaming (non-temporal) stores only change how the same values reach memory; rows longer
  // than one scratch chunk (256) and odd lengths exercise the chunking and alignment peeling.
  for (int threads : {1, 2}) {
    LbmParameters p;
    p.nx = 601;
    p.ny = 28;  // >= 2 x 8192 nodes: two threads when asked
    p.viscosity = 0.05;
    p.threads = threads;
    p.forcing = ForcingScheme::kGuo;
    p.stores = PopulationStores::kCached;
    LatticeBoltzmann2D cached(p);
    p.stores = PopulationStores::kStreaming;
    LatticeBoltzmann2D streaming(p);
    for (LatticeBoltzmann2D* lb : {&cached, &streaming}) {
      lb->InitializeShear(1e-4);
      FillSwirlForce(*lb, 1e-4);
      for (int s = 0; s < 10; ++s) lb->Step();
    }
    EXPECT_EQ(cached.populations(), streaming.populations());
    EXPECT_EQ(cached.ux(), streaming.ux());
    EXPECT_EQ(cached.uy(), streaming.uy());
    EXPECT_EQ(cached.rho(), streaming.rho());
  }
}

// In-place (AA) streaming gives the two-lattice kernel's results bit for bit, after odd and even
// numbers of steps, with moving walls and a wall-speed change, a closed box, a viscosity field,
// both forcings and two threads; populations() reconstructs the canonical post-collision state
// either way, so a restart from it continues bit for bit.
TEST(LatticeBoltzmann2DContract, InPlaceStreamingEqualsTwoLattices) {
  struct Case {
    FluidBoundary boundary;
    ForcingScheme forcing;
    bool viscosity_field;
    int threads;
    int nx, ny;
  };
  // 181 x 100 >= 2 x 8192 nodes, so threads = 2 really runs two; 2 x 7 takes the general path
  // (nx < 3) everywhere.
  const Case cases[] = {
      {FluidBoundary::kShearWalls, ForcingScheme::kSplitMomentum, false, 1, 19, 12},
      {FluidBoundary::kShearWalls, ForcingScheme::kGuo, true, 2, 181, 100},
      {FluidBoundary::kClosedBox, ForcingScheme::kSplitMomentum, true, 1, 17, 13},
      {FluidBoundary::kClosedBox, ForcingScheme::kGuo, false, 2, 181, 100},
      {FluidBoundary::kPeriodic, ForcingScheme::kGuo, false, 1, 16, 11},
      {FluidBoundary::kPeriodic, ForcingScheme::kSplitMomentum, true, 2, 181, 100},
      {FluidBoundary::kShearWalls, ForcingScheme::kGuo, true, 1, 2, 7}};
  for (const Case& c : cases) {
    LbmParameters p;
    p.nx = c.nx;
    p.ny = c.ny;
    p.viscosity = 0.1;
    p.boundary = c.boundary;
    p.forcing = c.forcing;
    p.threads = c.threads;
    p.wall_velocity_bottom = -0.01;
    p.wall_velocity_top = 0.02;
    LbmParameters q = p;
    p.pattern = StreamingPattern::kTwoLattice;
    q.pattern = StreamingPattern::kInPlace;
    auto nu_field = [](std::size_t nodes) {
      std::vector<double> nu(nodes, 0.1);
      for (std::size_t node = 0; node < nu.size(); node += 4) nu[node] = 0.3;
      return nu;
    };
    LatticeBoltzmann2D two(p), one(q);
    EXPECT_FALSE(two.in_place());
    EXPECT_TRUE(one.in_place());
    for (LatticeBoltzmann2D* lb : {&two, &one}) {
      if (c.viscosity_field) lb->SetViscosityField(nu_field(lb->nodes()));
      lb->InitializeShear(2e-3);
      FillSwirlForce(*lb, 1e-4);
      for (std::size_t node = 0; node < lb->nodes(); ++node)
        lb->force_x()[node] += 1e-6 * (node % 5);
    }
    ASSERT_EQ(two.populations(), one.populations()) << "initial state";
    for (int s = 1; s <= 9; ++s) {
      two.Step();
      one.Step();
      if (s == 3) {  // a wall speed change mid-run (as SetCa does)
        two.SetWallVelocities(-0.02, 0.03);
        one.SetWallVelocities(-0.02, 0.03);
      }
      ASSERT_EQ(two.populations(), one.populations()) << "step " << s << ", nx " << c.nx;
      ASSERT_EQ(two.rho(), one.rho()) << "step " << s;
      ASSERT_EQ(two.ux(), one.ux()) << "step " << s;
      ASSERT_EQ(two.uy(), one.uy()) << "step " << s;
    }
    // Restart from the canonical state after an odd step count, into an in-place and a
    // two-lattice fluid (checkpoints do not depend on the layout).
    for (const LbmParameters* r : {&q, &p}) {
      LatticeBoltzmann2D restarted(*r);
      if (c.viscosity_field) restarted.SetViscosityField(nu_field(restarted.nodes()));
      restarted.force_x() = one.force_x();
      restarted.force_y() = one.force_y();
      restarted.SetWallVelocities(-0.02, 0.03);
      restarted.SetPopulations(one.populations());
      restarted.SetStep(one.step());
      LatticeBoltzmann2D reference = one;
      for (int s = 0; s < 4; ++s) {
        reference.Step();
        restarted.Step();
      }
      EXPECT_EQ(reference.populations(), restarted.populations());
      EXPECT_EQ(reference.ux(), restarted.ux());
      EXPECT_EQ(reference.rho(), restarted.rho());
    }
  }
  // Streaming stores belong to the two-lattice kernel.
  LbmParameters bad;
  bad.nx = bad.ny = 8;
  bad.pattern = StreamingPattern::kInPlace;
  bad.stores = PopulationStores::kStreaming;
  EXPECT_THROW(LatticeBoltzmann2D{bad}, std::invalid_argument);
}

TEST(LatticeBoltzmann2DContract, UniformForceAcceleratesPeriodicFluidByExactlyF) {
  // Fully periodic box, uniform force F: total momentum grows by F per node per step (eq. (108))
  // and the reported velocity is j + F/2, so after n steps u = (n + 1/2) F everywhere.
  LbmParameters p;
  p.nx = 20;
  p.ny = 12;
  p.boundary = FluidBoundary::kPeriodic;
  LatticeBoltzmann2D lb(p);
  for (double& v : lb.force_x()) v = 1e-6;
  for (double& v : lb.force_y()) v = -2e-6;
  for (int s = 0; s < 10; ++s) lb.Step();
  for (std::size_t k = 0; k < lb.ux().size(); ++k) {
    EXPECT_NEAR(lb.ux()[k], 9.5e-6, 1e-16);  // round-off of sums of O(0.1) populations
    EXPECT_NEAR(lb.uy()[k], -19e-6, 1e-16);
  }
  lb.ClearForce();
  EXPECT_EQ(lb.force_x()[3], 0.0);
}

}  // namespace
}  // namespace ehd
