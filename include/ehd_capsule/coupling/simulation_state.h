// What a simulation publishes after each step, the same type in 2D and 3D: the node, the CSV and
// VTK writers and the CLI read only this (and Simulation's field accessors).
//
// Points are 3-vectors in both dimensions: in 2D the membrane markers lie in the plane z = 0 (the
// shear plane x-y), in 3D they are the surface vertices. Lattice units, centred on the domain.
#pragma once

#include <Eigen/Core>

namespace ehd {

struct SimulationState {
  int dimension = 2;
  long step = 0;
  double time = 0;                                // units of 1/k with shear (sum of k dt)
  Eigen::Matrix3Xd markers;                       // membrane points (2D: z = 0)
  Eigen::Matrix3Xd electric_force;                // per unit length (2D) or area (3D) per point;
                                                  // empty without field
  Eigen::Vector3d electric_force_total{0, 0, 0};  // sum F_E dl (2D) or F_E dA (3D)
  double dxy = 0, inclination = 0;  // Taylor deformation, inclination in the shear plane
  double area = 0;                  // enclosed area (2D); 3D: the enclosed volume
  double area_drift = 0;            // area / initial area - 1
  // Membrane length (2D) or surface area (3D) / its initial value - 1.
  double surface_drift = 0;
  // 3D only: deformation along z, the axis of the field (ShapeDiagnostics3D::dz).
  double d_field = 0;
  // 3D only: amplitude of the meridional surface flow about the field axis z, in a per time unit
  // (MeasureMeridionalFlow; > 0 from the poles to the equator).
  double surface_flow = 0;
  // 3D only: the enclosed volume the volume correction has restored in total, relative to the
  // initial volume (numerics.volume_correction_every; 0 without it): the immersed boundary's
  // leak is area_drift - volume_corrected.
  double volume_corrected = 0;
  double tt_phase = 0;  // unwrapped angle of material point 0 about the centroid (rad)
  // With shear: the xy component of the body's stresslet (particle stress dipole)
  // S = -sum_k sym((x_k - x_c) F_k) over the forces F_k the membrane spreads into the fluid,
  // over mu k a^3 (3D) or mu k a^2 per unit depth (2D); a rigid sphere in unbounded shear has
  // 10 pi / 3, a rigid cylinder 2 pi (Batchelor 1970; the immersed boundary's effective radius
  // shows in it as (a_eff / a)^D). 0 without shear.
  double stresslet_xy = 0;
  double ca = 0, ca_e = 0;
  int gmres_iterations = 0;
  double gmres_residual = 0;
  double max_mach = 0;
};

}  // namespace ehd
