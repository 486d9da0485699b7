// Conversion of the simulator's state into ROS messages (no ROS logic, no state of its own).
//
// Messages carry the scene's dimensionless values, never bare lattice numbers: positions are in
// units of the capsule radius a about the domain centre, the electric force density in units of
// T/a (T = E_s for a capsule, gamma for a drop), time as SimulationState::time.
#pragma once

#include <geometry_msgs/PolygonStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>

#include "ehd_capsule/CapsuleState.h"
#include "ehd_capsule/SurfaceMesh.h"
#include "ehd_capsule/SurfaceState.h"
#include "ehd_capsule/coupling/simulation.h"

namespace ehd::ros_node {

// What the 3D surface's TRIANGLE_LIST is coloured by (~surface_colour): the normal electric
// traction (one colour without a field), the in-plane mean membrane tension, the vertex speed,
// or one colour.
enum class SurfaceColour { kTraction, kTension, kSpeed, kNone };
// "traction", "tension", "speed" or "none"; std::invalid_argument naming ~surface_colour else.
SurfaceColour ParseSurfaceColour(const std::string& name);

struct StateMessageSettings {
  std::string frame_id = "ehd";
  double force_arrow_scale = 1.0;  // arrow length (units of a) per unit dimensionless force
  bool velocity_arrows = false;
  int velocity_stride = 8;  // one velocity arrow every n grid cells
  SurfaceColour surface_colour = SurfaceColour::kTraction;
};

// Lattice length of the capsule radius a, and the lattice force-density scale T/a.
double LatticeRadius(const Simulation& sim);
double LatticeForceDensityScale(const Simulation& sim);

ehd_capsule::CapsuleState MakeCapsuleState(const Simulation& sim,
                                           const StateMessageSettings& settings,
                                           const ros::Time& stamp);
// 3D only (throw std::logic_error in 2D): the triangles of the membrane mesh, and the measures
// CapsuleState has no field for (msg/SurfaceState.msg).
ehd_capsule::SurfaceMesh MakeSurfaceMesh(const Simulation& sim,
                                         const StateMessageSettings& settings,
                                         const ros::Time& stamp);
ehd_capsule::SurfaceState MakeSurfaceState(const Simulation& sim,
                                           const StateMessageSettings& settings,
                                           const ros::Time& stamp);
geometry_msgs::PolygonStamped MakeShape(const Simulation& sim, const StateMessageSettings& settings,
                                        const ros::Time& stamp);
// Membrane line strip, electric force arrows (with heads), the walls, optional velocity arrows,
// and a two-line text overlay with step, t, D_xy, theta, Ca and Ca_E.
visualization_msgs::MarkerArray MakeMarkerArray(const Simulation& sim,
                                                const StateMessageSettings& settings,
                                                const ros::Time& stamp);

// The coloured grid layer under the shape: one flat square per (stride x stride) block of cells,
// coloured by the quantity over its range in this frame (dark blue = smallest, yellow = largest;
// the range is in the marker's text namespace "field_range"). Quantities: the flow speed |u| in
// units of the wall speed k L (or of its largest value without shear), the electric potential,
// or the field strength |E| = |grad phi| in units of |E_inf| (central differences).
enum class FieldLayer { kNone, kSpeed, kPotential, kFieldStrength };
// Parses "none" / "speed" / "potential" / "field"; throws std::invalid_argument naming
// ~field_layer and the accepted values, or for the electric layers on a scene without a field.
FieldLayer ParseFieldLayer(const std::string& text, const Simulation& sim);
visualization_msgs::MarkerArray MakeFieldLayer(const Simulation& sim, FieldLayer layer, int stride,
                                               const StateMessageSettings& settings,
                                               const ros::Time& stamp);

}  // namespace ehd::ros_node
