// The coupled electrohydrodynamic time step (song2019 sec. 3.6) of a scene, in 2D or 3D.
//
// One Step at t^n, in lattice units (h = dt = 1), applies the queued changes (Ca, Ca_E), runs the
// stages built from the scene (coupled_step.h; one class template per stage over the dimension,
// coupling/stages/), in this order:
//   1. electric: potential by the fast IIM (warm-started), the Maxwell-stress force source
//      [M_E] . n at the points (eq. (148)); solved every `electric_every` steps or when a point
//      moved more than `electric_move_tolerance` since the last solve, else reused;
//   2. membrane: the membrane's force sources (2D: tension for a drop; Hookean + Kelvin-Voigt +
//      bending, eqs. (110)-(115), for a capsule; 3D: finite-element elasticity + Helfrich
//      bending, or a drop's tension);
//   3. spread: each body's sources summed (Body::SumLoads) and spread to the grid (eq. (106));
//      with V != 1 (2D) the viscosity field mu(x) = mu_c + (mu_a - mu_c) H(d(x)) (eqs.
//      (117)-(118)) is refreshed from the markers;
//   4. fluid: one LBM step (eqs. (97), (107)-(108));
//   5. markers: interpolate u^{n+1} (eq. (104)) and move them (eq. (105), or AB2);
//   6. diagnostics: shape, tank-treading phase, the public state;
// then advances the clock. Only what the scene needs is built: no electric stage nor its buffers
// without a field, no bending term with E_b = 0, no viscosity stage with V = 1. The printed
// pipeline and the checkpoint are assembled from the stages that were built.
// Watchdogs throw SimulationError naming the step and the quantity: a non-finite value, lattice
// Mach above numerics.max_mach, GMRES not converged, |A/A0 - 1| above numerics.area_drift_limit,
// a marker closer than 2h to a wall.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation_state.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

class CoupledStep;

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
  int dimension() const { return scene_.dimension; }
  // The fluid grid: grid() in 2D, grid3d() in 3D (each throws std::logic_error in the other).
  const Grid2D& grid() const;
  const Grid3D& grid3d() const;
  const std::vector<double>& ux() const;
  const std::vector<double>& uy() const;
  const std::vector<double>& uz() const;  // 3D only (throws std::logic_error in 2D)
  // 3D only (each throws std::logic_error in 2D), per vertex of state().markers: the in-plane
  // mean principal tension (tau_1 + tau_2) / 2 in units of the scene's modulus (G_s; a drop:
  // gamma, 1 everywhere), and the velocity of the last marker step in a per time unit (zero
  // before the first step and after a reset).
  std::vector<double> VertexTension() const;
  Eigen::Matrix3Xd VertexVelocity() const;
  // 3D: the membrane's triangles (vertex indices into state().markers); empty in 2D.
  const std::vector<std::array<int, 3>>& triangles() const;
  // Electric potential on the grid (empty without field).
  const std::vector<double>& potential() const;
  std::string Pipeline() const;  // the stages built, one per line, and those left out
  // How often a drop's markers were re-spaced (numerics.redistribute_markers) since the last
  // Reset (construction included).
  long marker_redistributions() const;
  void Reset();  // back to the initial state (pending changes dropped)

  // Wall time spent in each built stage since construction (or ResetStageTimes), in run order:
  // where a step's time goes (steady_clock around each stage's Run, ~0.3 % overhead).
  struct StageTime {
    std::string name;
    double seconds = 0;
  };
  std::vector<StageTime> StageTimes() const;
  void ResetStageTimes();

  // Checkpoint/restart: a binary file with a version tag, the scene text, the clock, the markers
  // and one section per stage; Restore requires a Simulation built from the same scene and
  // continues bit-for-bit.
  void Save(const std::string& path) const;
  void Restore(const std::string& path);

 private:
  Scene scene_;
  LatticeUnits units_;
  SimulationState state_;
  std::unique_ptr<CoupledStep> coupled_;  // after the members above: its stages refer to them
  // Changes queued by SetCa / SetCaE for the next Step (-1: none).
  double pending_ca_ = -1.0, pending_ca_e_ = -1.0;
};

}  // namespace ehd
