// The run controller's parts without a ROS master: the progress line, the summary and its
// stepping clock, the ranges dynamic_reconfigure shows, and the large-run warning.
#include "ehd_capsule/ros/run_controller.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ehd::ros_node {
namespace {

SimulationState State() {
  SimulationState s;
  s.step = 120;
  s.time = 0.3;
  s.dxy = 0.123456;
  s.inclination = 0.25 * M_PI;
  s.area_drift = 1e-5;
  return s;
}

TEST(RunController, ProgressLine) {
  EXPECT_EQ(FormatProgressLine(State(), ShownMeasures{}, "1/k", 499.6),
            "step 120  t = 0.3 1/k  D_xy = 0.12346  theta/pi = 0.2500  area drift = 1.00e-05  "
            "500 steps/s");
}

TEST(RunController, Summary) {
  EXPECT_EQ(FormatSummary("ran", State(), ShownMeasures{}, "1/k", 2.0, {120, 2.0, false}),
            "summary: ran after 120 steps, t = 0.3 1/k: D_xy = 0.12346, theta/pi = 0.2500, area "
            "drift = 1.00e-05; 2.0 s wall, 120 steps in 2.0 s of stepping (60 steps/s)");
  EXPECT_NE(FormatSummary("ran", State(), ShownMeasures{}, "1/k", 0.0, {}).find("(0 steps/s)"),
            std::string::npos);
  // Issue #44: 610 s wall, most of it paused, 120 steps since a reset stepped in 1.5 s: the rate
  // is theirs (it was 120 / 610 = 0 steps/s).
  EXPECT_NE(FormatSummary("ran", State(), ShownMeasures{}, "1/k", 610.0, {120, 1.5, true})
                .find("; 610.0 s wall, 120 steps in 1.5 s of stepping since the last reset (80 "
                      "steps/s)"),
            std::string::npos);
}

// Paused iterations do not count; the stepping ones (an ~advance while paused too) do, with the
// loop's own time; a restart (a reset) starts again.
TEST(RunController, SteppingClockCountsOnlySteppingIterations) {
  SteppingClock clock;
  clock.Restart(100.0);
  clock.Mark(100.0);
  clock.set_stepping(true);
  clock.Mark(101.0);  // 1 s stepping
  clock.set_stepping(true);
  clock.Mark(101.5);  // 0.5 s stepping
  clock.Mark(500.0);  // paused: not counted
  clock.Mark(600.0);
  clock.set_stepping(true);
  clock.Mark(600.25);
  EXPECT_DOUBLE_EQ(clock.seconds(), 1.75);
  clock.set_stepping(true);
  clock.Restart(700.0);  // a reset in the middle of an iteration
  clock.Mark(800.0);
  EXPECT_DOUBLE_EQ(clock.seconds(), 0.0);
}

// dynamic_reconfigure's sliders (issue #44: +-1e9 and the .cfg's defaults) are what the node
// accepts: each end taken, a hair beyond refused.
TEST(RunController, AcceptedLiveValuesAreSetCaAndSetCaEsRanges) {
  Simulation sim(LoadScene("shear_field", {"N=32", "M=32"}));
  const LiveValueRanges r = AcceptedLiveValues(sim);
  EXPECT_EQ(r.ca_e_min, 0.0);
  EXPECT_EQ(r.ca_e_max, sim.scene().electric.max_ca_e);
  EXPECT_NO_THROW(sim.SetCaE(r.ca_e_max));
  EXPECT_THROW(sim.SetCaE(r.ca_e_max * 1.001), std::invalid_argument);
  EXPECT_EQ(r.ca_min, 0.0);
  EXPECT_GT(r.ca_max, sim.state().ca);
  EXPECT_LE(r.ca_max, sim.scene().max_Ca);
  EXPECT_NO_THROW(sim.SetCa(r.ca_max));
  EXPECT_THROW(sim.SetCa(r.ca_max * 1.001), std::invalid_argument);
  // The largest max_Ca: the wall Mach number may bound Ca first.
  Simulation small(LoadScene("shear_field", {"N=32", "M=32", "max_Ca=10"}));
  const LiveValueRanges s = AcceptedLiveValues(small);
  EXPECT_LE(s.ca_max, 10.0);
  EXPECT_NO_THROW(small.SetCa(s.ca_max));
  EXPECT_THROW(small.SetCa(s.ca_max * 1.001), std::invalid_argument);
  // Without a field: Ca_E 0 only.
  Simulation plain(LoadScene("shear_field", {"N=32", "M=32", "Ca_E=0", "electric="}));
  EXPECT_EQ(AcceptedLiveValues(plain).ca_e_max, 0.0);
}

// 3D: D_z along the field where it means something, D_xy and theta only with shear, the volume's
// drift (electric_drop_3d printed D_xy = 0.00000 theta/pi = 0.5000 area drift = ...).
TEST(RunController, ThreeDimensionalMeasures) {
  Scene scene;
  EXPECT_TRUE(MeasuresOf(scene).shear_plane);  // 2D: as before
  EXPECT_FALSE(MeasuresOf(scene).field_axis);
  scene.dimension = 3;
  scene.flow = FlowKind::kNone;
  scene.electric_field = true;  // electric_drop_3d
  SimulationState s = State();
  s.d_field = 0.0123456;
  EXPECT_EQ(FormatProgressLine(s, MeasuresOf(scene), "mu a/gamma", 10.0),
            "step 120  t = 0.3 mu a/gamma  D_z = 0.01235  volume drift = 1.00e-05  10 steps/s");
  scene.flow = FlowKind::kShear;  // sphere_shear_field
  EXPECT_EQ(FormatSummary("ran", s, MeasuresOf(scene), "1/k", 2.0, {120, 2.0, false}),
            "summary: ran after 120 steps, t = 0.3 1/k: D_xy = 0.12346, theta/pi = 0.2500, D_z = "
            "0.01235, volume drift = 1.00e-05; 2.0 s wall, 120 steps in 2.0 s of stepping (60 "
            "steps/s)");
  scene.electric_field = false;  // sphere_shear
  EXPECT_EQ(FormatProgressLine(s, MeasuresOf(scene), "1/k", 10.0),
            "step 120  t = 0.3 1/k  D_xy = 0.12346  theta/pi = 0.2500  volume drift = 1.00e-05  "
            "10 steps/s");
}

TEST(RunController, LargeRunWarning) {
  Scene scene;
  LatticeUnits units;
  units.time_unit = "1/k";
  scene.N = 64;
  units.steps_per_time_unit = 1000;
  EXPECT_EQ(LargeRunWarning(scene, units), "");
  scene.N = 4096;  // 4 GB of fluid state
  const std::string warning = LargeRunWarning(scene, units);
  EXPECT_NE(warning.find("N = 4096"), std::string::npos) << warning;
  EXPECT_NE(warning.find("Lower N"), std::string::npos) << warning;
}

}  // namespace
}  // namespace ehd::ros_node
