// The 3D coupled step on a small grid (N = 24, a = 4 cells, 642 vertices): a neo-Hookean sphere
// in shear deforms and tilts as a capsule does, keeps its volume, restarts bit for bit (also after
// a live Ca or Ca_E change), resets to a fresh run, gives the same bits on 1, 2 and 3 threads and
// is stopped at a wall; the electric field acts on it (traction against the free-space sphere);
// 3D scene keys are validated.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/reference/interface_examples_3d.h"
#include "support/same_state.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

// A neo-Hookean sphere in shear, a = 4 cells on 24^3, 642 vertices.
// The roma3 kernel (retracted 0.37 h), with which these tests' figures were measured.
test::TinyScene TinySphere() { return test::TinyScene(3).With("numerics.ib_kernel", "roma3"); }

using test::ExpectSameState;  // support/same_state.h

TEST(Simulation3D, SphereInShearDeformsTiltsAndKeepsItsVolume) {
  Simulation sim(TinySphere().Build());
  EXPECT_EQ(sim.dimension(), 3);
  EXPECT_EQ(sim.state().markers.cols(), 642);
  EXPECT_EQ(sim.triangles().size(), 1280u);
  EXPECT_NE(sim.Pipeline().find("D3Q19"), std::string::npos) << sim.Pipeline();
  EXPECT_NE(sim.Pipeline().find("not built: electric"), std::string::npos);
  while (sim.state().time < 1.5) sim.Step();
  const SimulationState& s = sim.state();
  EXPECT_EQ(s.dimension, 3);
  EXPECT_GT(s.dxy, 0.08);
  EXPECT_LT(s.dxy, 0.25);
  EXPECT_GT(s.inclination / M_PI, 0.15);  // tilted towards the extension axis (pi/4 at t = 0)
  EXPECT_LT(s.inclination / M_PI, 0.26);
  EXPECT_LT(std::abs(s.area_drift), 2e-3);  // enclosed volume
  EXPECT_LT(s.tt_phase, -0.3);              // the membrane turns clockwise (tank-treading)
  EXPECT_THROW(sim.grid(), std::logic_error);
  EXPECT_EQ(sim.grid3d().nz, 24);
}

// What the node colours the surface by: the tension is zero on the initial (reference) shape
// and positive once the shear stretches the capsule, largest where it is stretched most; the
// vertices move with the imposed shear u_x = k y, i.e. y / a in units of a k, at the first step
// (the fluid starts as the undisturbed shear flow).
TEST(Simulation3D, VertexTensionAndVelocityFollowTheShape) {
  Simulation sim(TinySphere().Build());
  for (double t : sim.VertexTension()) EXPECT_NEAR(t, 0.0, 1e-12);
  EXPECT_EQ(sim.VertexVelocity().cols(), 642);
  EXPECT_EQ(sim.VertexVelocity().norm(), 0.0);
  sim.Step();
  const double a = sim.units().radius;
  const Eigen::Matrix3Xd u = sim.VertexVelocity();
  ASSERT_EQ(u.cols(), sim.state().markers.cols());
  const double yc = sim.state().markers.row(1).mean();
  double worst = 0;
  for (int v = 0; v < u.cols(); ++v) {
    worst = std::max(worst, std::abs(u(0, v) - (sim.state().markers(1, v) - yc) / a));
  }
  std::printf("first step: max |u_x - y/a| = %.3e (u_x up to 1)\n", worst);
  EXPECT_LT(worst, 0.05);
  while (sim.state().time < 0.5) sim.Step();
  const std::vector<double> tension = sim.VertexTension();
  double mean = 0, top = -1e300;
  int at = 0;
  for (int v = 0; v < static_cast<int>(tension.size()); ++v) {
    mean += tension[v] / tension.size();
    if (tension[v] > top) top = tension[v], at = v;
  }
  const Eigen::Vector3d r = sim.state().markers.col(at) - sim.state().markers.rowwise().mean();
  std::printf("t = 0.5: mean tension %.4f G_s, max %.4f at r = (%.2f, %.2f, %.2f) a\n", mean, top,
              r.x() / a, r.y() / a, r.z() / a);
  EXPECT_GT(mean, 0.0);
  EXPECT_LT(top, 1.0);
  EXPECT_GT(top, 2.0 * mean);
  EXPECT_THROW(Simulation(LoadScene("shear_field")).VertexTension(), std::logic_error);
}

// The volume correction holds the enclosed volume at its initial value, and what it restores is
// the leak the same run has without it (to first order the correction does not change the
// flow), which the watchdog still sees. A coarse mesh (162 vertices, edges up to 1.5 h) leaks
// fast enough to measure in a short run. The immersed boundary at the points with the cosine
// kernel (song2019): the retracted one removes the leak from the vertices' velocity each step (its
// drift here is 2.6e-6 instead of 2.4e-4), so there is nothing to restore.
TEST(Simulation3D, VolumeCorrectionRestoresTheLeakItReports) {
  const std::vector<std::string> coarse = {"mesh_subdivisions=2", "numerics.threads=1",
                                           "numerics.ib_kernel=cosine", "numerics.ib_retraction=0"};
  std::vector<std::string> corrected = coarse;
  corrected.push_back("numerics.volume_correction_every=50");
  Simulation plain(TinySphere().Build(coarse)), fixed(TinySphere().Build(corrected));
  EXPECT_NE(fixed.Pipeline().find("volume restored"), std::string::npos) << fixed.Pipeline();
  while (plain.state().time < 1.0) plain.Step();
  while (fixed.state().step < plain.state().step) fixed.Step();
  const double leak = plain.state().area_drift;
  ASSERT_GT(std::abs(leak), 2e-4) << "the coarse mesh should leak measurably";
  EXPECT_EQ(plain.state().volume_corrected, 0.0);
  // Between two corrections (50 steps of ~3800 per unit) the drift is at most a few % of it.
  EXPECT_LT(std::abs(fixed.state().area_drift), 0.05 * std::abs(leak));
  EXPECT_NEAR(fixed.state().volume_corrected, -leak, 0.1 * std::abs(leak));
  EXPECT_NEAR(fixed.state().dxy, plain.state().dxy, 0.02 * plain.state().dxy);
}

// Small-deformation limit (Barthes-Biesel & Rallison 1981): D = (25/4) mu k a / E_s with the
// surface Young modulus E_s = 3 G_s of the neo-Hookean law, i.e. D = (25/12) Ca for the
// shear-modulus capillary number Ca = mu k a / G_s used here.
TEST(Simulation3D, SmallDeformationIsNearTheLinearTheory) {
  Simulation sim(TinySphere().Build({"Ca=0.0125"}));
  while (sim.state().time < 2.0) sim.Step();
  const double theory = 25.0 / 12.0 * 0.0125;
  std::printf("Ca = 0.0125: D = %.4f, linear theory %.4f\n", sim.state().dxy, theory);
  // Measured 0.0263 (+1.0 %) with the roma3 kernel retracted 0.37 h at
  // this a = 4 grid; the cosine kernel retracted 0.5 h gave 0.0255 (-2 %) and at the points it
  // was about +25 %. A modulus 5 % off moves D by 5 %: it fails the 3.5 % band either way.
  EXPECT_GT(sim.state().dxy, 0.965 * theory);
  EXPECT_LT(sim.state().dxy, 1.035 * theory);
}

// A drop (surface tension gamma, Ca = mu k a / gamma, viscosity ratio 1) obeys Taylor's small-
// deformation result D = (35/32) Ca. With the immersed boundary at the points the coarse grid's
// effective radius made it 41 % larger here (0.077 for 0.055; 0.064 at a = 8 cells,
// docs/validation_3d.md); with the roma3 kernel retracted 0.37 h it is measured at 0.0514,
// -6.0 % at a = 4 (the cosine kernel retracted 0.5 h: 0.0521). A tension 5 % off fails one side.
TEST(Simulation3D, DropIsNearTaylorsSmallDeformationResult) {
  Simulation sim(TinySphere().Name("tiny_drop3d").Drop().Build());
  while (sim.state().time < 1.0) sim.Step();
  const double taylor = 35.0 / 32.0 * 0.05;
  std::printf("drop Ca = 0.05: D = %.4f, Taylor %.4f, theta/pi %.4f\n", sim.state().dxy, taylor,
              sim.state().inclination / M_PI);
  EXPECT_GT(sim.state().dxy, 0.92 * taylor);
  EXPECT_LT(sim.state().dxy, 1.08 * taylor);
  EXPECT_GT(sim.state().inclination / M_PI, 0.2);  // Taylor: pi/4 at small Ca
  EXPECT_LT(sim.state().inclination / M_PI, 0.26);
}

// The mesh watchdogs: a soft drop (Ca = 1.5, above the critical Ca of breakup) stretches until
// its 642 vertices (not remeshed: only relaxed along the surface) no longer cover it: edges
// grow past 2 h and the volume leaks through the gaps. The run stops naming the volume and the
// edges, before a fold or a NaN.
TEST(Simulation3D, OutstretchedMeshStopsTheRunWithTheReason) {
  Simulation sim(TinySphere().Name("soft_drop3d").Drop().With("Ca", 1.5).Build());
  try {
    while (sim.state().time < 8.0) sim.Step();
    ADD_FAILURE() << "the stretched mesh was not caught";
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("edges > 2 h leak: raise mesh_subdivisions"),
              std::string::npos)
        << e.what();
    EXPECT_TRUE(sim.state().markers.allFinite());
    EXPECT_GT(sim.state().dxy, 0.5);
  }
  // A capsule's vertices are material: a very soft one (Ca = 3, no mesh filter) shears its
  // triangles until the smallest angle falls below 5 degrees, which stops the run naming it.
  Simulation capsule(TinySphere().Build({"Ca=3", "numerics.marker_filter_every=0"}));
  try {
    while (capsule.state().time < 8.0) capsule.Step();
    ADD_FAILURE() << "the sheared mesh was not caught";
  } catch (const SimulationError& e) {
    EXPECT_NE(std::string(e.what()).find("smallest triangle angle"), std::string::npos) << e.what();
    EXPECT_TRUE(capsule.state().markers.allFinite());
  }
}

// The crossing count of a grid column through a vertex: on N = 21 the centred capsule of
// sphere_shear_field keeps its pole vertices on the column x = y = 0 (the flow's symmetry), and
// when the two triangles of an edge rounded its edge function differently the column was counted
// as crossed twice and the capsule refused as folded at step 75. 100 steps must run.
TEST(Simulation3D, CentredCapsuleOnAnOddGridIsNotRefusedAsFolded) {
  Simulation sim(
      LoadScene("sphere_shear_field", {"geometry.half_width=1.3", "N=21", "numerics.threads=1"}));
  for (int i = 0; i < 100; ++i) ASSERT_NO_THROW(sim.Step()) << "step " << i;
  EXPECT_GT(sim.state().dxy, 0.0);
}

// A box longer along x and z than across the walls (geometry.half_length) is the lattice's and
// the electric solver's grid, and the capsule is centred in it.
TEST(Simulation3D, LongBoxIsTheGridOfEveryStage) {
  Simulation sim(TinySphere().Build(
      {"geometry.half_length=4", "Ca_E=0.1", "sigma_r=2", "eps_r=3.5", "numerics.threads=1"}));
  EXPECT_EQ(sim.grid3d().nx, 32);
  EXPECT_EQ(sim.grid3d().ny, 24);
  EXPECT_EQ(sim.grid3d().nz, 32);
  EXPECT_NE(sim.Pipeline().find("D3Q19 MRT LBM 32 x 24 x 32"), std::string::npos) << sim.Pipeline();
  for (int i = 0; i < 20; ++i) sim.Step();
  const Eigen::Vector3d centroid = sim.state().markers.rowwise().mean();
  EXPECT_LT(centroid.norm(), 1e-3);
  EXPECT_GT(sim.state().dxy, 0.0);
  EXPECT_GT(sim.state().electric_force.colwise().norm().maxCoeff(), 0.0);
}

TEST(Simulation3D, CheckpointRestartAndResetAreBitForBit) {
  // With the volume correction too (every 4 steps: on both sides of the checkpoint), whose
  // running total is part of the checkpoint.
  for (const char* correction : {"0", "4"}) {
    const Scene scene =
        TinySphere().Build({"numerics.integrator=adams_bashforth2", "E_b=0.05",
                            std::string("numerics.volume_correction_every=") + correction});
    const std::string path = ::testing::TempDir() + "/ehd_checkpoint_3d_test.bin";
    Simulation a(scene);
    for (int i = 0; i < 6; ++i) a.Step();
    a.Save(path);
    for (int i = 0; i < 5; ++i) a.Step();
    Simulation b(scene);
    b.Restore(path);
    EXPECT_EQ(b.state().step, 6);
    for (int i = 0; i < 5; ++i) b.Step();
    EXPECT_TRUE((a.state().markers.array() == b.state().markers.array()).all());
    EXPECT_EQ(a.ux(), b.ux());
    EXPECT_EQ(a.state().tt_phase, b.state().tt_phase);
    EXPECT_EQ(a.state().volume_corrected, b.state().volume_corrected);
    if (std::string(correction) != "0") {
      EXPECT_NE(a.state().volume_corrected, 0.0);
    }
  }
  const Scene scene = TinySphere().Build({"numerics.integrator=adams_bashforth2", "E_b=0.05"});
  const std::string path = ::testing::TempDir() + "/ehd_checkpoint_3d_test.bin";
  Simulation a(scene);
  for (int i = 0; i < 6; ++i) a.Step();
  a.Save(path);
  Simulation b(scene);
  b.Restore(path);
  // A 2D checkpoint is refused by a 3D simulation and the other way round.
  Simulation plain2d(test::TinyScene(2).Build());
  EXPECT_THROW(plain2d.Restore(path), std::runtime_error);
  std::remove(path.c_str());

  Simulation fresh(scene);
  for (int i = 0; i < 4; ++i) b.Step();
  b.Reset();
  for (int i = 0; i < 5; ++i) {
    fresh.Step();
    b.Step();
  }
  EXPECT_TRUE((fresh.state().markers.array() == b.state().markers.array()).all());
  EXPECT_EQ(fresh.state().dxy, b.state().dxy);
}

// The 3D electric stage (song2019 ch. 6: E_inf along z, phi = E z on the z faces): the force per
// unit area at the vertices of the initial sphere matches the free-space traction of a
// leaky-dielectric sphere (box effect (a/L)^3 ~ 4 %: 10 % of the largest), the net force is
// small, a checkpoint restarts bit for bit with the field, and Ca_E changes live (0 removes the
// force, out of range is refused).
TEST(Simulation3D, ElectricFieldActsOnTheMembrane) {
  const Scene scene =
      TinySphere().Build({"Ca_E=0.3", "sigma_r=1.75", "eps_r=3.5", "numerics.electric_every=5"});
  Simulation sim(scene);
  EXPECT_TRUE(sim.has_electric_field());
  EXPECT_NE(sim.Pipeline().find("3D fast IIM"), std::string::npos) << sim.Pipeline();
  sim.Step();
  const SimulationState& s = sim.state();
  ASSERT_EQ(s.electric_force.cols(), s.markers.cols());
  EXPECT_GT(s.gmres_iterations, 0);
  const double e = sim.units().field, sm = 1.75, sp = 1.0, em = 3.5, ep = 1.0;
  const Eigen::Vector3d centre = s.markers.rowwise().mean();
  const double radius = (s.markers.colwise() - centre).colwise().norm().mean();
  double worst = 0, scale = 0;
  for (int v = 0; v < s.markers.cols(); ++v) {
    const Eigen::Vector3d exact =
        FreeSpaceSphereTraction(s.markers.col(v) - centre, radius, e, sm, sp, em, ep);
    worst = std::max(worst, (s.electric_force.col(v) - exact).norm());
    scale = std::max(scale, exact.norm());
  }
  std::printf("3D electric stage: traction error %.3e of %.3e, net force %.3e, %d GMRES its\n",
              worst, scale, s.electric_force_total.norm(), s.gmres_iterations);
  EXPECT_LT(worst, 0.1 * scale);
  EXPECT_LT(s.electric_force_total.norm(), 1e-2 * scale * 4 * 3.14159 * radius * radius);

  const std::string path = ::testing::TempDir() + "/ehd_checkpoint_3d_field_test.bin";
  for (int i = 0; i < 7; ++i) sim.Step();
  sim.Save(path);
  Simulation other(scene);
  other.Restore(path);
  for (int i = 0; i < 9; ++i) {
    sim.Step();
    other.Step();
  }
  EXPECT_TRUE((sim.state().markers.array() == other.state().markers.array()).all());
  EXPECT_TRUE((sim.state().electric_force.array() == other.state().electric_force.array()).all());
  std::remove(path.c_str());

  EXPECT_THROW(sim.SetCaE(50), std::invalid_argument);
  sim.SetCaE(0.0);
  sim.Step();
  EXPECT_EQ(sim.state().ca_e, 0.0);
  EXPECT_EQ(sim.state().electric_force.cwiseAbs().maxCoeff(), 0.0);
}

// numerics.electric_shape_tolerance: while the capsule tank-treads along its (slowly changing)
// shape, the traction of the last solve re-interpolated at the moved vertices follows the
// traction of a solve at every step to within 3 %, with a few solves instead of 100 (the
// deformation of the start moves the surface itself); a
// checkpoint restart continues bit for bit; 2D refuses the key.
TEST(Simulation3D, ReinterpolatedTractionFollowsTheSolvedOne) {
  const std::vector<std::string> field = {"Ca_E=0.3", "sigma_r=1.75", "eps_r=3.5"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), field.begin(), field.end());
    return TinySphere().Build(extra);
  };
  Simulation every(with({"numerics.electric_every=1"}));
  const Scene lazy_scene =
      with({"numerics.electric_every=1000", "numerics.electric_move_tolerance=0.01",
            "numerics.electric_shape_tolerance=0.05"});
  Simulation lazy(lazy_scene);
  EXPECT_NE(lazy.Pipeline().find("re-interpolate"), std::string::npos) << lazy.Pipeline();
  int solves = 0;
  const std::string path = ::testing::TempDir() + "/ehd_checkpoint_3d_reinterpolate.bin";
  for (int i = 0; i < 100; ++i) {
    every.Step();
    lazy.Step();
    if (lazy.state().gmres_iterations > 0) ++solves;
    if (i == 49) lazy.Save(path);
  }
  const Eigen::Matrix3Xd& t_every = every.state().electric_force;  // traction per vertex
  const Eigen::Matrix3Xd& t_lazy = lazy.state().electric_force;
  const double scale = t_every.colwise().norm().maxCoeff();
  const double moved =
      (lazy.state().markers - Simulation(lazy_scene).state().markers).colwise().norm().maxCoeff();
  const double difference = (t_lazy - t_every).colwise().norm().maxCoeff();
  std::printf(
      "re-interpolated traction: %d solves in 100 steps, vertices moved up to %.3f h, "
      "difference %.2e of %.2e\n",
      solves, moved, difference, scale);
  EXPECT_GT(moved, 0.1);  // the vertices did move along the surface, by several tolerances
  EXPECT_LE(solves, 10);  // the start: the sphere deforms off its solved shape
  EXPECT_LT(difference, 0.03 * scale);
  Simulation restarted(lazy_scene);
  restarted.Restore(path);
  for (int i = 0; i < 50; ++i) restarted.Step();
  EXPECT_TRUE((restarted.state().markers.array() == lazy.state().markers.array()).all());
  EXPECT_TRUE(
      (restarted.state().electric_force.array() == lazy.state().electric_force.array()).all());
  std::remove(path.c_str());
  EXPECT_THROW(LoadScene("shear_field", {"numerics.electric_shape_tolerance=0.02"}), SceneError);
}

// The explicit step with Helfrich bending: below the estimated limit (membrane_stability.h, the
// planar-mode estimate with S = E_B, k up to pi / shortest edge) it runs and stays bounded; above
// it the scene is refused naming the term and the numerics.membrane_substeps that make it
// stable, which then runs.
TEST(Simulation3D, BendingStepLimitIsNamedAndRespected) {
  {
    // The 3D default integrator (Adams-Bashforth 2) has half forward Euler's limit. With the
    // roma3 kernel (pinned in TinySphere) the limit is 2.4 times stricter than with the cosine one:
    // it damps the mesh-scale modes less (its transform at k h = pi is larger).
    Simulation sim(TinySphere().Build({"E_b=1"}));  // estimated stable dt 1.31
    for (int i = 0; i < 1000; ++i) sim.Step();
    EXPECT_LT(sim.state().dxy, 0.05);  // stiff in bending: barely deformed
    EXPECT_LT(std::abs(sim.state().area_drift), 1e-2);
  }
  try {
    Simulation sim(TinySphere().Build({"E_b=2.5"}));  // estimated stable dt 0.524
    ADD_FAILURE() << "E_b = 2.5 accepted at membrane_substeps 1";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bending (E_b)"), std::string::npos) << what;
    EXPECT_NE(what.find("numerics.membrane_substeps >= 2"), std::string::npos) << what;
  }
  Simulation sim(TinySphere().Build({"E_b=2.5", "numerics.membrane_substeps=2"}));
  for (int i = 0; i < 1000; ++i) sim.Step();
  EXPECT_TRUE(sim.state().markers.allFinite());
  EXPECT_LT(sim.state().dxy, 0.05);
}

TEST(Simulation3D, SceneKeysAreValidatedForThreeDimensions) {
  auto refused = [](const std::vector<std::string>& overrides, const std::string& expect) {
    try {
      TinySphere().Build(overrides);
      ADD_FAILURE() << "accepted " << overrides[0];
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  };
  refused({"M=64"}, "mesh_subdivisions");
  refused({"V=2"}, "viscosity contrast is not built in 3D");
  refused({"Ca_E=0.1"}, "sigma_r");
  refused({"Ca_E=0.1", "sigma_r=2000", "eps_r=2"}, "accepted [0.0001, 1000]");
  refused({"membrane=drop"}, "surface tension only");
  refused({"geometry.shape=circle"}, "sphere | biconcave");
  refused({"law=skalak"}, "'C' missing");
  refused({"C=10"}, "only law: skalak");
  refused({"mesh_subdivisions=9"}, "out of range");
  refused({"numerics.relax_mesh_every=10"},
          "'numerics.relax_mesh_every' = '10' is not accepted here: needs dimension: 3 and "
          "membrane: drop");
  refused({"membrane=drop", "law=", "E_b=", "numerics.redistribute_markers=2"},
          "'numerics.redistribute_markers' = '2' is not accepted here: 2D drops only");
  // A mesh too coarse for the grid (edges > 2 h) is refused naming the subdivision needed.
  try {
    Simulation coarse(TinySphere().Build({"mesh_subdivisions=1", "N=48"}));
    ADD_FAILURE() << "a 42-vertex mesh on a = 8 cells accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh_subdivisions >= 3"), std::string::npos) << e.what();
  }
  // 2D scenes refuse the 3D keys.
  const test::TinyScene capsule_2d = test::TinyScene(2).Without("name");
  const auto refused_2d = [&](const std::string& key, const std::string& expect) {
    try {
      capsule_2d.Build({key});
      ADD_FAILURE() << "2D scene accepted " << key;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  };
  refused_2d("law=skalak", "only a 3D capsule has a finite-element law");
  refused_2d("numerics.mesh_filter_order=4",
             "'numerics.mesh_filter_order' = '4' is not accepted here: 3D only");
  refused_2d("numerics.volume_correction_every=100",
             "'numerics.volume_correction_every' = '100' is not accepted here: 3D only");
  {  // the 3D filter's order reaches the stage
    Simulation filtered(TinySphere().Build({"numerics.mesh_filter_order=4"}));
    EXPECT_NE(filtered.Pipeline().find("(order 4)"), std::string::npos) << filtered.Pipeline();
  }
  const Scene skalak = TinySphere().Build({"law=skalak", "C=15", "geometry.shape=biconcave"});
  EXPECT_EQ(skalak.law, SurfaceLawKind::kSkalak);
  EXPECT_EQ(skalak.M, 642);
  Simulation rbc(skalak);
  EXPECT_NE(rbc.Pipeline().find("Skalak"), std::string::npos);
}

// A live Ca change survives a checkpoint, restore and reset (support/same_state.h).
TEST(Simulation3D, LiveCaChangeSurvivesCheckpointRestoreAndReset) {
  const Scene scene = TinySphere().Build({"numerics.integrator=adams_bashforth2"});
  test::ExpectLiveChangeSurvivesCheckpointAndReset(scene, [](Simulation& sim) { sim.SetCa(0.1); });
}

// The same with a field (the tiny sphere of ElectricFieldActsOnTheMembrane, re-solved every 5
// steps: on both sides of the checkpoint) and Ca_E halved live.
TEST(Simulation3D, LiveCaEChangeSurvivesCheckpointRestoreAndReset) {
  const Scene scene =
      TinySphere().Build({"Ca_E=0.3", "sigma_r=1.75", "eps_r=3.5", "numerics.electric_every=5"});
  test::ExpectLiveChangeSurvivesCheckpointAndReset(scene,
                                                   [](Simulation& sim) { sim.SetCaE(0.15); });
}

// The coupled step gives the same bits on any thread count (docs/lbm.md: the LBM kernel's rows
// are independent, "1 thread == 2 threads bit-for-bit"; docs/electric_solver_3d.md: the IIM
// set-up's per-vertex fits and band rows are "laid out in order: the same bits on any thread
// count"; no stage has an OpenMP reduction). numerics.threads reaches only the LBM, and the LBM
// runs a thread per 8192 nodes at most, so the box is 32 x 24 x 32 (24576 nodes: 3 threads);
// the IIM set-up takes the OpenMP default, set here to the same count. With the field re-solved
// every 5 steps, 20 steps: the vertices and every CSV scalar are equal bit for bit between 1, 2
// and 3 threads (measured: equal).
TEST(Simulation3D, CoupledStepIsBitForBitOverThreadCounts) {
  const int default_threads = omp_get_max_threads();
  std::vector<SimulationState> states;
  for (const int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    Simulation sim(TinySphere().Build({"geometry.half_length=4", "Ca_E=0.3", "sigma_r=1.75",
                                       "eps_r=3.5", "numerics.electric_every=5",
                                       "numerics.threads=" + std::to_string(threads)}));
    for (int i = 0; i < 20; ++i) sim.Step();
    states.push_back(sim.state());
  }
  omp_set_num_threads(default_threads);
  EXPECT_GT(states[0].dxy, 0.0);
  for (std::size_t k = 1; k < states.size(); ++k) {
    SCOPED_TRACE(k + 1);
    ExpectSameState(states[0], states[k]);
  }
}

// The wall watchdog in 3D (simulation.h: a marker closer than 2 h to a wall stops the run; the
// check is MarkerStage::CheckInside; 2D: Simulation.WatchdogNamesStepAndQuantity). Walls at
// y = +-12 cells (L = 3 a, a = 4 cells), the margin at 10. Placed: center_y = 1.8 a puts the top
// of the capsule at 11.2 cells: the set-up refuses it (coupled_step.cpp, CheckInitialShape).
// Deformed: a capsule in shear near the wall does not get closer (measured at Ca = 1 from a top
// at 9.6 cells: the wall flattens it, 9.60 -> 8.30 cells by t = 4), so the deformation is an oblate
// drop's (Taylor's Case A, sigma_r = 1.75, eps_r = 3.5, Ca_E = 1, field along z: its equator widens
// towards the y walls). Its top starts 0.12 cells outside the margin (9.88 cells; near the wall the
// top rises by at most ~0.26 cells, measured from center_y = 1.4) and crosses it at t = 1.34 (step
// 130, a vertex at y = 10.0004, D = -0.079); the run stops naming the vertex and the wall, the
// points finite. Without the check the drop would run on to t = 3 and the test fail. 1.3 s.
TEST(Simulation3D, WallWatchdogStopsABodyNearingTheWall) {
  try {
    Simulation placed(TinySphere().Build({"geometry.center_y=1.8"}));
    ADD_FAILURE() << "a capsule 0.8 cells from the wall was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("within 2 h of the wall y = 3 a"), std::string::npos)
        << e.what();
  }
  Simulation drop(TinySphere()
                      .Name("oblate_drop_near_wall")
                      .Drop()
                      .AtRest(1)
                      .Field(1.0, 1.75, 3.5)
                      .Build({"geometry.center_y=1.47", "numerics.electric_every=50",
                              "numerics.electric_move_tolerance=0.02"}));
  ASSERT_NO_THROW(drop.Step()) << "0.12 cells outside the margin";
  try {
    while (drop.state().time < 3.0) drop.Step();
    ADD_FAILURE() << "the widening drop was not stopped at the wall";
  } catch (const SimulationError& e) {
    const std::string what = e.what();
    std::printf("oblate drop: stopped at t = %.3f, D along the field %.3f: %s\n", drop.state().time,
                drop.state().d_field, what.c_str());
    EXPECT_NE(what.find("vertex"), std::string::npos) << what;
    EXPECT_NE(what.find("within 2h of the wall y = 12"), std::string::npos) << what;
    EXPECT_LT(drop.state().d_field, 0.0);
    EXPECT_TRUE(drop.state().markers.allFinite());
  }
}

}  // namespace
}  // namespace ehd
