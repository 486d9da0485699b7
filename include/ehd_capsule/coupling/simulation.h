// The coupled electrohydrodynamic time step (song2019 sec. 3.6) of one capsule or drop.
//
// One Step at t^n, in lattice units (h = dt = 1):
//   1. electric potential by the fast IIM (warm-started), interfacial force
//      F_E = [M_E] . n at the markers (eq. (148)); solved every `electric_every` steps or when a
//      marker moved more than `electric_move_tolerance` since the last solve, else reused;
//   2. membrane force density (tension for a drop; Hookean + Kelvin-Voigt + bending, eqs.
//      (110)-(115), for a capsule);
//   3. spread (f_membrane + F_E) dl to the grid (eq. (106)); with V != 1 the viscosity field
//      mu(x) = mu_c + (mu_a - mu_c) H(d(x)) (eqs. (117)-(118)) is refreshed from the markers;
//   4. one LBM step (eqs. (97), (107)-(108));
//   5. interpolate u^{n+1} to the markers (eq. (104)) and move them (eq. (105), or AB2).
// Only what the scene needs is built: no electric solver nor its buffers without a field, no
// bending term with E_b = 0, no viscosity field with V = 1.
// Watchdogs after each step throw SimulationError naming the step and the quantity: a non-finite
// value, lattice Mach above numerics.max_mach, GMRES not converged, |A/A0 - 1| above
// numerics.area_drift_limit, a marker closer than 2h to a wall.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

struct SimulationError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SimulationState {
  long step = 0;
  double time = 0;                             // units of 1/k with shear (sum of k dt)
  Eigen::Matrix2Xd markers;                    // lattice units, centred on the domain
  Eigen::Matrix2Xd electric_force;             // per unit length per marker; empty w/o field
  Eigen::Vector2d electric_force_total{0, 0};  // sum F_E dl
  double dxy = 0, inclination = 0, area = 0, area_drift = 0, tt_phase = 0;
  double ca = 0, ca_e = 0;
  int gmres_iterations = 0;
  double gmres_residual = 0;
  double max_mach = 0;
};

class Simulation {
 public:
  // Builds only what the scene needs; throws SceneError for unusable lattice values (tau, Mach,
  // membrane explicit limit).
  explicit Simulation(const Scene& scene);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  void Step();  // one EHD step; throws SimulationError

  // Queue a change applied at the next Step. SetCaE throws std::invalid_argument outside
  // [0, electric.max_Ca_E], or for Ca_E > 0 on a scene built without the field. SetCa throws
  // outside (0, max_Ca] (Ca = 0 would freeze the time, counted in units of 1/k) or on a scene
  // without shear; it changes the wall speed, not the membrane.
  void SetCaE(double ca_e);
  void SetCa(double ca);

  bool has_electric_field() const;
  bool has_bending() const;
  bool has_viscosity_contrast() const;

  const SimulationState& state() const { return state_; }
  const Scene& scene() const { return scene_; }
  const LatticeUnits& units() const { return units_; }
  const Grid2D& grid() const { return grid_; }
  const std::vector<double>& ux() const;
  const std::vector<double>& uy() const;
  // Electric potential on the grid (empty without field).
  const std::vector<double>& potential() const;
  std::string Pipeline() const;  // the assembled modules, one per line
  // How often a drop's markers were re-spaced (numerics.redistribute_markers) since construction.
  long marker_redistributions() const;
  void Reset();  // back to the initial state (pending changes dropped)

  // Checkpoint/restart: a binary file with a version tag and the scene text; Restore requires a
  // Simulation built from the same scene and continues bit-for-bit.
  void Save(const std::string& path) const;
  void Restore(const std::string& path);

 private:
  void RedistributeBunchedMarkers();  // numerics.redistribute_markers (drops)

  struct Impl;
  std::unique_ptr<Impl> impl_;
  Scene scene_;
  LatticeUnits units_;
  Grid2D grid_;
  SimulationState state_;
};

}  // namespace ehd
