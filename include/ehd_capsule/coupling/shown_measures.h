// The measures that mean something for a scene, for the progress lines and summaries of the node
// and of ehd_sim run: D_xy and theta in the shear plane (2D; 3D with shear), D_z along the field
// axis z (3D with a field, or without shear: electric_drop_3d's D_xy is 0 and its theta 0.5
// whatever its shape), and the drift of the enclosed area (2D) or volume (3D).
#pragma once

#include <string>

#include "ehd_capsule/coupling/simulation_state.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd {

struct ShownMeasures {
  bool shear_plane = true;
  bool field_axis = false;
  bool volume = false;
};
ShownMeasures MeasuresOf(const Scene& scene);

// "D_xy = 0.12346", "theta/pi = 0.2500", "D_z = 0.01234", "area drift = 1.00e-05" (3D: "volume
// drift"), those of m, joined by separator.
std::string FormatMeasures(const SimulationState& s, const ShownMeasures& m, const char* separator);

}  // namespace ehd
