// The same simulation state bit for bit, for the checkpoint, reset and thread-count tests of the
// coupled step in 2D and 3D: the points, the electric force and every scalar the CSV writes
// (io/time_series.h; the 3D columns are 0 in 2D).
#pragma once

#include <gtest/gtest.h>

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

}  // namespace test
}  // namespace ehd
