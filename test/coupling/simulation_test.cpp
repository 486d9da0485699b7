// The coupled step on tiny grids: pipeline composition, capsule in shear, electric drop (Feng's
// sign), run-time changes (also across a checkpoint and a reset), watchdogs, checkpoint/restart
// and the same bits on 1, 2 and 3 threads.
#include "ehd_capsule/coupling/simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ehd_capsule/scene/scene.h"
#include "support/same_state.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

// A Hookean capsule in shear and a leaky-dielectric drop at rest, a = 4 cells on 48^2.
test::TinyScene TinyCapsule() { return test::TinyScene(2).Grid(48); }
test::TinyScene TinyDrop() {
  return test::TinyScene(2).Name("tiny_drop").Drop().AtRest(1).Field(0.2, 4.75).Grid(48);
}

void RunUntil(Simulation& sim, double t) {
  while (sim.state().time < t) sim.Step();
}

using test::ExpectSameState;  // support/same_state.h

// A scene builds only what it needs.
TEST(Simulation, PipelineHasOnlyWhatTheSceneNeeds) {
  Simulation plain(TinyCapsule().Build());
  EXPECT_FALSE(plain.has_electric_field());
  EXPECT_FALSE(plain.has_bending());
  EXPECT_FALSE(plain.has_viscosity_contrast());
  EXPECT_EQ(plain.state().electric_force.cols(), 0);  // no electric buffers
  EXPECT_TRUE(plain.potential().empty());
  EXPECT_NE(plain.Pipeline().find("not built: electric"), std::string::npos) << plain.Pipeline();
  EXPECT_EQ(plain.Pipeline().find("bending"), std::string::npos) << plain.Pipeline();
  EXPECT_EQ(plain.Pipeline().find("Heaviside"), std::string::npos) << plain.Pipeline();
  plain.Step();
  EXPECT_EQ(plain.state().electric_force.cols(), 0);

  Simulation full(
      TinyCapsule().Build({"E_b=0.01", "V=2", "Ca_E=0.1", "sigma_r=1.75", "eps_r=3.5"}));
  EXPECT_TRUE(full.has_electric_field());
  EXPECT_TRUE(full.has_bending());
  EXPECT_TRUE(full.has_viscosity_contrast());
  EXPECT_NE(full.Pipeline().find("bending"), std::string::npos) << full.Pipeline();
  EXPECT_NE(full.Pipeline().find("Heaviside"), std::string::npos) << full.Pipeline();
  full.Step();
  EXPECT_EQ(full.state().electric_force.cols(), 48);
  EXPECT_GT(full.state().gmres_iterations, 0);
}

// At early times the membrane force is negligible and a circle is deformed affinely by the
// straining part of u = (k y, 0): rate k/2 along the 45 degree axis, so L/B = exp(k t) and
// D_xy = tanh(k t / 2) ~ k t / 2, theta = pi/4. Later the membrane resists (D below k t / 2).
// The area is conserved by the incompressible flow (up to the IB leakage, small over this time).
TEST(Simulation, CapsuleInShearDeformsFromZero) {
  Simulation sim(TinyCapsule().Build());
  EXPECT_LT(sim.state().dxy, 1e-6);
  RunUntil(sim, 0.05);
  const double t = sim.state().time;
  EXPECT_NEAR(sim.state().dxy, std::tanh(t / 2), 0.15 * t / 2);
  EXPECT_NEAR(sim.state().inclination, M_PI / 4, 0.05);
  RunUntil(sim, 0.5);
  EXPECT_GT(sim.state().dxy, 0.1);
  EXPECT_LT(sim.state().dxy, std::tanh(sim.state().time / 2));  // elasticity resists
  EXPECT_GT(sim.state().inclination, 0.0);
  EXPECT_LT(sim.state().inclination, M_PI / 4 + 0.02);  // tilts towards the flow
  EXPECT_LT(std::abs(sim.state().area_drift), 0.01);
  EXPECT_LT(sim.state().tt_phase, 0.0);  // the membrane turns clockwise with the flow
}

// Feng (2002), song2019 sec. 4.2.2: D = f_d Ca_E / (3 (1 + sigma_r)^2),
// f_d = sigma_r^2 + sigma_r + 1 - 3 eps_r, D > 0 elongated along the field (y). sigma_r = 4.75,
// eps_r = 3.5: f_d = 17.8, D = +0.0359 (prolate, major axis vertical); sigma_r = 1.75:
// f_d = -4.69, D = -0.0413 (oblate, major axis along x). At Ca_E = 0.2 on a 48^2 grid in a box
// of 4a the steady D agrees within 20% (first-order theory, unbounded domain; confinement at 4a
// alone adds up to 10%, docs/validation_ehd.md sec. 1; the shipped electric_drop, walls at 8a,
// is within 1% for sigma_r = 1.75).
TEST(Simulation, ElectricDropDeformsAsFengPredicts) {
  for (const double sigma_r : {4.75, 1.75}) {
    SCOPED_TRACE(sigma_r);
    Simulation sim(
        TinyDrop().Build({"sigma_r=" + std::to_string(sigma_r), "numerics.electric_every=4"}));
    RunUntil(sim, 6.0);
    const double fd = sigma_r * sigma_r + sigma_r + 1 - 3 * 3.5;
    const double d_feng = fd * 0.2 / (3 * (1 + sigma_r) * (1 + sigma_r));
    const bool vertical = std::abs(sim.state().inclination) > M_PI / 4;
    EXPECT_EQ(vertical, fd > 0) << "inclination " << sim.state().inclination;
    const double d_signed = vertical ? sim.state().dxy : -sim.state().dxy;
    EXPECT_NEAR(d_signed, d_feng, 0.2 * std::abs(d_feng));
    // A neutral drop feels no net electric force (sum F_E dl = 0 up to discretisation).
    const double scale = sim.state().electric_force.cwiseAbs().maxCoeff() * 2 * M_PI * 6;
    EXPECT_LT(sim.state().electric_force_total.norm(), 0.05 * scale);
    EXPECT_LT(std::abs(sim.state().area_drift), 0.01);
    // Linear in Ca_E at first order (docs/validation_ehd.md sec. 1): half the field strength
    // squared, half the deformation. The O(Ca_E^2) term and the grid leave the ratio within 5 %
    // of 2 (measured 2.054 for sigma_r = 4.75, 1.994 for 1.75); a force scaled as Ca_E^2 or
    // sqrt(Ca_E) would give 4 or 1.4.
    Simulation half(TinyDrop().Build(
        {"sigma_r=" + std::to_string(sigma_r), "numerics.electric_every=4", "Ca_E=0.1"}));
    RunUntil(half, 6.0);
    const double ratio = sim.state().dxy / half.state().dxy;
    std::printf("sigma_r = %.2f: D_xy(Ca_E = 0.2) / D_xy(0.1) = %.4f\n", sigma_r, ratio);
    EXPECT_NEAR(ratio, 2.0, 0.1);
  }
}

TEST(Simulation, SetCaAndSetCaETakeEffectAtTheNextStep) {
  Simulation sim(TinyCapsule().Build({"electric={}", "Ca_E=0", "sigma_r=2", "eps_r=1"}));
  EXPECT_DOUBLE_EQ(sim.state().ca_e, 0.0);
  sim.Step();
  EXPECT_EQ(sim.state().gmres_iterations, 0);  // field built but off
  const double t1 = sim.state().time;
  sim.SetCa(0.2);
  sim.SetCaE(0.4);
  EXPECT_DOUBLE_EQ(sim.state().ca, 0.1);  // queued, not applied yet
  EXPECT_DOUBLE_EQ(sim.state().ca_e, 0.0);
  sim.Step();
  EXPECT_DOUBLE_EQ(sim.state().ca, 0.2);
  EXPECT_DOUBLE_EQ(sim.state().ca_e, 0.4);
  // Doubling Ca at fixed E_s doubles k: the step advances twice the time.
  EXPECT_NEAR(sim.state().time - t1, 2 * sim.units().shear_rate, 1e-15);
  EXPECT_GT(sim.state().gmres_iterations, 0);
  EXPECT_GT(sim.state().electric_force.cwiseAbs().maxCoeff(), 0.0);

  EXPECT_THROW(sim.SetCaE(-0.1), std::invalid_argument);
  EXPECT_THROW(sim.SetCaE(5.5), std::invalid_argument);
  EXPECT_THROW(sim.SetCa(-1), std::invalid_argument);
  // The scene's measured live limit (max_Ca) bounds SetCa and the scene's own Ca.
  Simulation limited(TinyCapsule().Build({"max_Ca=0.15"}));
  EXPECT_NO_THROW(limited.SetCa(0.15));
  try {
    limited.SetCa(0.2);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_Ca"), std::string::npos) << e.what();
  }
  EXPECT_THROW(TinyCapsule().Build({"max_Ca=0.05"}), SceneError);  // its Ca = 0.1
  Simulation no_field(TinyCapsule().Build());
  try {
    no_field.SetCaE(0.3);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("without"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(no_field.SetCaE(0.0));
}

// A membrane stiffer than the explicit limit (membrane_stability.h) is refused at set-up with a
// suggestion; the suggested time-step refinement is then accepted (the limit scales with n since
// E_s ~ nu^2 and mu ~ nu at fixed Re and Ca).
TEST(Simulation, MembraneLimitFailsEarlyWithAUsableSuggestion) {
  const std::vector<std::string> stiff = {"Ca=0.00005"};
  std::string what;
  try {
    Simulation sim(TinyCapsule().Build(stiff));
    FAIL() << "expected the membrane limit to be exceeded";
  } catch (const SceneError& e) {
    what = e.what();
  }
  const std::size_t at = what.find("membrane_substeps >= ");
  ASSERT_NE(at, std::string::npos) << what;
  const int n = std::stoi(what.substr(at + 21));
  EXPECT_GT(n, 1);
  std::vector<std::string> fixed = stiff;
  fixed.push_back("numerics.membrane_substeps=" + std::to_string(n));
  EXPECT_NO_THROW(Simulation(TinyCapsule().Build(fixed)));
}

// A capsule within 2 h of a wall is refused before the run; one started on the margin (its top at
// y = 14 cells, the wall at 16) is carried across it by the shear and stops with an error naming
// the step, the marker and the wall (step 11, measured).
TEST(Simulation, WatchdogNamesStepAndQuantity) {
  try {
    Simulation refused(TinyCapsule().Build({"geometry.center_y=2.8"}));
    ADD_FAILURE() << "a capsule 0.8 cells from the wall was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("within 2 h of the wall y = 4 a"), std::string::npos)
        << e.what();
  }
  Simulation sim(test::TinyScene(2).Build({"geometry.center_y=2.5"}));  // a = 4 cells
  try {
    for (int i = 0; i < 30; ++i) sim.Step();
    FAIL() << "the capsule was not stopped at the wall";
  } catch (const SimulationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("step 11:"), std::string::npos) << what;
    EXPECT_NE(what.find("marker"), std::string::npos) << what;
    EXPECT_NE(what.find("within 2h of the wall y = 16"), std::string::npos) << what;
  }
}

// The figures docs/validation_ehd.md sec. 1 states for the shipped electric_drop (a = 8 cells,
// walls at 8a, N = 128, the retracted immersed boundary of issue #42): D at t = 10 against Feng's
// first-order theory, Case A (sigma_r = 1.75, oblate) -5.4 %, Case C (sigma_r = 4.75, prolate)
// +1.4 %. The resolution study there: at a = 16 (N = 256) A is -4.1 % and C +3.9 %, so the
// retracted boundary converges at first order from below (the points did from above: A -1.0 %,
// C +7.1 % at a = 8), towards about -2.6 % (A) and +6.6 % (C): Feng's theory plus the O(Ca_E^2)
// term (C: +0.4 % at Ca_E = 0.05, +5.5 % at 0.2, 4a box) and the walls (C: -0.8 % from 8a to
// 16a). Tolerances: A in [-8, -3] %, C in [-2, +5] %. D is linear in the Maxwell force, so a force
// or a permittivity off by 5 % moves either out of its band. About 3-5 s each.
TEST(Simulation, ShippedElectricDropMatchesFeng) {
  struct Case {
    double sigma_r, lo, hi;  // D / D_Feng - 1 accepted in [lo, hi]
  };
  for (const Case c : {Case{1.75, -0.08, -0.03}, Case{4.75, -0.02, 0.05}}) {
    SCOPED_TRACE(c.sigma_r);
    Simulation sim(
        LoadScene("electric_drop", {"sigma_r=" + std::to_string(c.sigma_r), "numerics.threads=1"}));
    RunUntil(sim, 10.0);
    const double fd = c.sigma_r * c.sigma_r + c.sigma_r + 1 - 3 * 3.5;
    const double d_feng = fd * 0.2 / (3 * (1 + c.sigma_r) * (1 + c.sigma_r));
    const bool vertical = std::abs(sim.state().inclination) > M_PI / 4;
    const double d_signed = vertical ? sim.state().dxy : -sim.state().dxy;
    std::printf("electric_drop sigma_r = %.2f, t = 10: D = %+.5f, Feng %+.5f (%+.2f %%)\n",
                c.sigma_r, d_signed, d_feng, 100.0 * (d_signed / d_feng - 1.0));
    EXPECT_GE(d_signed / d_feng - 1.0, c.lo);
    EXPECT_LE(d_signed / d_feng - 1.0, c.hi);
  }
}

// Save, continue; restore into a fresh simulation, continue: identical bits (markers, fluid,
// diagnostics), with the field re-solved every 3 steps, AB2 markers, a Kelvin-Voigt history and
// a viscosity contrast (whose band indicator is rebuilt from the markers on restore).
TEST(Simulation, CheckpointRestartIsBitForBit) {
  const Scene scene =
      TinyCapsule().Build({"eta=1", "V=2", "Ca_E=0.2", "sigma_r=1.75", "eps_r=3.5",
                           "numerics.electric_every=3", "numerics.integrator=adams_bashforth2"});
  const std::string path = test::ExpectCheckpointRestartIsBitForBit(scene, 7, 8);

  // A checkpoint of another scene is refused.
  Simulation other(TinyCapsule().Build());
  EXPECT_THROW(other.Restore(path), std::runtime_error);
  std::remove(path.c_str());
}

// Live Ca and Ca_E changes together survive a checkpoint, restore and reset
// (support/same_state.h).
TEST(Simulation, LiveChangesSurviveCheckpointRestoreAndReset) {
  const Scene scene =
      TinyCapsule().Build({"Ca_E=0.2", "sigma_r=1.75", "eps_r=3.5", "numerics.electric_every=3",
                           "numerics.integrator=adams_bashforth2"});
  test::ExpectLiveChangeSurvivesCheckpointAndReset(scene, [](Simulation& sim) {
    sim.SetCa(0.15);
    sim.SetCaE(0.1);
  });
}

// The coupled step gives the same bits on any thread count (docs/lbm.md: the LBM kernel's rows
// are independent, "1 thread == 2 threads bit-for-bit"; no stage has an OpenMP reduction; the 2D
// electric, membrane and marker stages are serial). numerics.threads reaches the LBM, which runs
// a thread per 8192 nodes at most: the tiny capsule on 160^2 (25600 nodes, 3 threads; a = 20
// cells, 160 markers) with a field (re-solved every 3 steps) and a viscosity contrast (the
// variable-viscosity kernel), 20 steps: the markers, the velocity and every CSV scalar are equal
// bit for bit between 1, 2 and 3 threads (measured: equal).
TEST(Simulation, CoupledStepIsBitForBitOverThreadCounts) {
  std::vector<SimulationState> states;
  std::vector<std::vector<double>> ux;
  for (const int threads : {1, 2, 3}) {
    Simulation sim(TinyCapsule().Grid(160).Build({"V=2", "Ca_E=0.2", "sigma_r=1.75", "eps_r=3.5",
                                                  "numerics.electric_every=3",
                                                  "numerics.threads=" + std::to_string(threads)}));
    for (int i = 0; i < 20; ++i) sim.Step();
    states.push_back(sim.state());
    ux.push_back(sim.ux());
  }
  EXPECT_GT(states[0].dxy, 0.0);
  for (std::size_t k = 1; k < states.size(); ++k) {
    SCOPED_TRACE(k + 1);
    ExpectSameState(states[0], states[k]);
    EXPECT_EQ(ux[0], ux[k]);
  }
}

TEST(Simulation, ResetReturnsToTheInitialState) {
  Simulation sim(TinyCapsule().Build());
  const Eigen::Matrix3Xd x0 = sim.state().markers;
  for (int i = 0; i < 5; ++i) sim.Step();
  sim.Reset();
  EXPECT_EQ(sim.state().step, 0);
  EXPECT_TRUE((sim.state().markers.array() == x0.array()).all());
}

// After Reset the run repeats a newly built one bit for bit, also with the stages that keep
// history (viscosity contrast band, Kelvin-Voigt, AB2, electric warm start, tank-treading).
TEST(Simulation, ResetRunRepeatsAFreshRun) {
  const Scene scene = TinyCapsule().Build({"eta=1", "V=2", "Ca_E=0.2", "sigma_r=1.75", "eps_r=3.5",
                                           "numerics.integrator=adams_bashforth2"});
  Simulation fresh(scene), reset(scene);
  for (int i = 0; i < 9; ++i) reset.Step();
  reset.Reset();
  for (int i = 0; i < 6; ++i) {
    fresh.Step();
    reset.Step();
  }
  EXPECT_TRUE((fresh.state().markers.array() == reset.state().markers.array()).all());
  EXPECT_EQ(fresh.ux(), reset.ux());
  EXPECT_EQ(fresh.state().tt_phase, reset.state().tt_phase);
  EXPECT_EQ(fresh.state().dxy, reset.state().dxy);
}

// The printed pipeline lists the stages in run order and names those not built.
TEST(Simulation, PipelineListsStagesInRunOrder) {
  Simulation full(TinyCapsule().Build({"V=2", "Ca_E=0.2", "sigma_r=1.75", "eps_r=3.5"}));
  const std::string p = full.Pipeline();
  const char* order[] = {"1. electric:", "2. membrane:", "3. spread:",     "4. viscosity:",
                         "5. fluid:",    "6. markers:",  "7. diagnostics:"};
  std::size_t at = 0;
  for (const char* label : order) {
    const std::size_t found = p.find(label);
    ASSERT_NE(found, std::string::npos) << label << " in\n" << p;
    EXPECT_GT(found, at) << label;
    at = found;
  }
  EXPECT_EQ(p.find("not built"), std::string::npos) << p;
  Simulation plain(TinyCapsule().Build());
  EXPECT_NE(plain.Pipeline().find("not built: electric (no field in the scene), viscosity (V = 1)"),
            std::string::npos)
      << plain.Pipeline();
  EXPECT_NE(plain.Pipeline().find("4. markers:"), std::string::npos) << plain.Pipeline();
}

}  // namespace
}  // namespace ehd
