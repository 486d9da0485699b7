// CSV time series of a simulation: one row per sample.
// Columns: step, t (units of 1/k with shear, else the scene's time unit), dxy (Taylor
// deformation), inclination (radians, (-pi/2, pi/2]), area (enclosed area / (pi a^2)),
// tt_phase (radians, unwrapped), area_drift, ca, ca_e, fe_x, fe_y (sum F_E dl / (T a), T = gamma
// or E_s), gmres_iterations, max_mach.
#pragma once

#include <fstream>
#include <string>

#include "ehd_capsule/coupling/simulation.h"

namespace ehd {

class TimeSeriesCsv {
 public:
  // Opens (truncates) the file and writes the header; with append = true (a restart) keeps the
  // existing rows and writes no header if the file is not empty. Throws std::runtime_error.
  TimeSeriesCsv(const std::string& path, const Simulation& sim, bool append = false);
  void Write(const Simulation& sim);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream out_;
};

// The header line (no newline). 3D simulations add fe_z (the electric force's z component),
// d_field (the deformation along the field axis z), surface_flow (the meridional surface
// flow about z, a per time unit, > 0 from the poles to the equator) and volume_corrected (the
// relative volume numerics.volume_correction_every has restored in total; 0 without it).
std::string TimeSeriesHeader(int dimension = 2);

}  // namespace ehd
