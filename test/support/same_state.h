// The same simulation state bit for bit, for the checkpoint, reset and thread-count tests of the
// coupled step in 2D and 3D: the points, the electric force and every scalar the CSV writes
// (io/time_series.h; the 3D columns are 0 in 2D); and the live-change check built on it.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <string>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/coupling/simulation_state.h"

namespace ehd {
namespace test {

inline void ExpectSameState(const SimulationState& a, const SimulationState& b) {
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.time, b.time);
  EXPECT_TRUE((a.markers.array() == b.markers.array()).all());
  EXPECT_TRUE((a.electric_force.array() == b.electric_force.array()).all());
  EXPECT_EQ(a.electric_force_total, b.electric_force_total);
  EXPECT_EQ(a.dxy, b.dxy);
  EXPECT_EQ(a.inclination, b.inclination);
  EXPECT_EQ(a.area, b.area);
  EXPECT_EQ(a.area_drift, b.area_drift);
  EXPECT_EQ(a.surface_drift, b.surface_drift);
  EXPECT_EQ(a.d_field, b.d_field);
  EXPECT_EQ(a.surface_flow, b.surface_flow);
  EXPECT_EQ(a.volume_corrected, b.volume_corrected);
  EXPECT_EQ(a.tt_phase, b.tt_phase);
  EXPECT_EQ(a.stresslet_xy, b.stresslet_xy);
  EXPECT_EQ(a.ca, b.ca);
  EXPECT_EQ(a.ca_e, b.ca_e);
  EXPECT_EQ(a.gmres_iterations, b.gmres_iterations);
  EXPECT_EQ(a.gmres_residual, b.gmres_residual);
  EXPECT_EQ(a.max_mach, b.max_mach);
}

// Save after `before` steps and take `after` more; restore the file into a new Simulation of the
// scene and take the same steps: the same state and fluid, bit for bit. Returns the file's path
// (left in place for further checks; the caller removes it).
inline std::string ExpectCheckpointRestartIsBitForBit(const Scene& scene, int before, int after) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string path = ::testing::TempDir() + "/ehd_checkpoint_" + info->name() + ".bin";
  Simulation a(scene);
  for (int i = 0; i < before; ++i) a.Step();
  a.Save(path);
  for (int i = 0; i < after; ++i) a.Step();
  Simulation b(scene);
  b.Restore(path);
  EXPECT_EQ(b.state().step, before);
  for (int i = 0; i < after; ++i) b.Step();
  ExpectSameState(a.state(), b.state());
  EXPECT_EQ(a.ux(), b.ux());
  EXPECT_EQ(a.uy(), b.uy());
  return path;
}

// A live change (the node's dynamic reconfigure, Simulation::SetCa / SetCaE) is part of what a
// checkpoint holds and what a reset undoes (docs/architecture.md, "The stage contract" 2 and 4;
// simulation.h: Save/Restore "continues bit-for-bit", Reset "back to the initial state"). SetCa
// changes the wall speed (the time per step scales with Ca), SetCaE the field of the next solve.
// Run A is changed after 3 steps, saved at step 6 and continues 5 steps; B restores the file into
// a new Simulation of the scene and takes the same 5 steps: the same bits, the live Ca and Ca_E
// included. A reset returns the live values to the scene's (a change still queued is dropped) and
// the next 5 steps equal a fresh run's. The change is checked to matter (A differs from a run
// without it), so a checkpoint that dropped it would fail.
inline void ExpectLiveChangeSurvivesCheckpointAndReset(
    const Scene& scene, const std::function<void(Simulation&)>& change) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string path = ::testing::TempDir() + "/ehd_live_change_" + info->name() + ".bin";
  Simulation a(scene), unchanged(scene);
  for (int i = 0; i < 3; ++i) a.Step(), unchanged.Step();
  change(a);
  for (int i = 0; i < 3; ++i) a.Step(), unchanged.Step();
  const double ca = a.state().ca, ca_e = a.state().ca_e;
  EXPECT_TRUE(ca != unchanged.state().ca || ca_e != unchanged.state().ca_e);
  a.Save(path);
  for (int i = 0; i < 5; ++i) a.Step(), unchanged.Step();
  EXPECT_FALSE((a.state().markers.array() == unchanged.state().markers.array()).all());

  Simulation b(scene);
  b.Restore(path);
  std::remove(path.c_str());
  EXPECT_EQ(b.state().step, 6);
  EXPECT_EQ(b.state().ca, ca);
  EXPECT_EQ(b.state().ca_e, ca_e);
  for (int i = 0; i < 5; ++i) b.Step();
  ExpectSameState(a.state(), b.state());
  EXPECT_EQ(a.ux(), b.ux());

  change(b);  // queued, then dropped by the reset
  b.Reset();
  Simulation fresh(scene);
  EXPECT_EQ(b.state().ca, fresh.state().ca);
  EXPECT_EQ(b.state().ca_e, fresh.state().ca_e);
  for (int i = 0; i < 5; ++i) fresh.Step(), b.Step();
  ExpectSameState(fresh.state(), b.state());
  EXPECT_EQ(fresh.ux(), b.ux());
}

}  // namespace test
}  // namespace ehd
