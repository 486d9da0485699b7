// The stages of the 2D coupled step (song2019 sec. 3.6) of one capsule or drop, and the marker
// data they share. See step_stage.h for the stage contract and simulation.h for the step.
//
// Run order (Simulation builds only the stages the scene needs):
//   electric   fast IIM potential and F_E = [M_E].n at the markers (only with a field)
//   membrane   membrane force density (drop tension, or Hookean + Kelvin-Voigt + bending)
//   spread     arc elements dl, (f_membrane + F_E) dl spread to the grid (eq. (106))
//   viscosity  mu(x) from the markers (eqs. (117)-(118); only with V != 1)
//   fluid      one D2Q9 MRT LBM step (eqs. (97), (107)-(108))
//   markers    interpolate u (eq. (104)), advance (eq. (105) or AB2), filter, wrap, re-space
//   diagnostics  watchdogs, D_xy, inclination, tank-treading phase, the public state
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation_state.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/diagnostics/shape_diagnostics.h"
#include "ehd_capsule/diagnostics/tank_treading.h"
#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/ib/immersed_boundary.h"
#include "ehd_capsule/ib/marker_update.h"
#include "ehd_capsule/ib/sawtooth_filter.h"
#include "ehd_capsule/ib/viscosity_indicator.h"
#include "ehd_capsule/lbm/lattice_boltzmann.h"
#include "ehd_capsule/membrane/membrane_model.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

class LeakyDielectricSolver;

// The Lagrangian markers of the membrane and what the stages exchange on them in one step.
struct MembraneMarkers2D {
  Eigen::Matrix2Xd initial;  // the scene's initial shape
  Eigen::Matrix2Xd X;        // positions, lattice units, stored unwrapped (marker_update.h)
  ClosedCurve curve;         // through X; updated whenever X changes
  std::vector<double> dl;    // arc elements at the start of the step (spread)
  Eigen::Matrix2Xd U;        // velocity interpolated this step
  Eigen::Matrix2Xd membrane_density, electric_density, marker_force;
  double initial_area = 0;
  // Controls in effect (Simulation applies queued changes before the stages run).
  double shear_rate = 0;             // k (lattice units); 0 without shear
  double field = 0;                  // |E_inf| (lattice units)
  SimulationState* state = nullptr;  // what the stages report to

  void ResetTo(const Eigen::Matrix2Xd& positions);  // X, curve, zero U and densities
};

class ElectricStage2D : public StepStage {
 public:
  ElectricStage2D(const Scene& scene, const LatticeUnits& units, const Grid2D& grid,
                  MembraneMarkers2D& body);
  ~ElectricStage2D() override;
  const char* name() const override { return "electric"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

  const std::vector<double>& potential() const;
  // After the markers were re-spaced: resample the warm start G along the curve with `resample`
  // (values at the old markers -> values at the new ones) and solve again at the next step.
  void Respaced(const std::function<void(std::vector<double>&)>& resample);

 private:
  const Scene& scene_;
  MembraneMarkers2D& body_;
  std::unique_ptr<LeakyDielectricSolver> solver_;
  Eigen::Matrix2Xd markers_at_last_solve_;
  long last_solve_step_ = -1;
  double solved_field_ = -1.0;  // |E| of the last solve
};

class MembraneStage2D : public StepStage {
 public:
  // Throws SceneError if the explicit membrane step is unstable at the initial shape (names the
  // term and the numerics.membrane_substeps needed).
  MembraneStage2D(const Scene& scene, const LatticeUnits& units, MembraneMarkers2D& body);
  const char* name() const override { return "membrane"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

 private:
  const Scene& scene_;
  MembraneMarkers2D& body_;
  MembraneParameters parameters_;
  std::unique_ptr<MembraneModel> model_;  // rebuilt by Reset and Restore
  double viscous_number_ = 0;             // Kelvin-Voigt stability indicator
  // Markers at the last two force evaluations: replayed on Restore to rebuild the model's
  // stretch history (Kelvin-Voigt) bit-for-bit.
  Eigen::Matrix2Xd previous1_, previous2_;
  int history_ = 0;
};

class SpreadStage2D : public StepStage {
 public:
  SpreadStage2D(const Scene& scene, const ImmersedBoundary& ib, MembraneMarkers2D& body,
                LatticeBoltzmann2D& fluid);
  const char* name() const override { return "spread"; }
  std::string Describe() const override;
  void Reset() override {}
  void Run(long step) override;
  void Save(CheckpointWriter&) const override {}  // the grid force is the fluid's
  void Restore(CheckpointReader&) override;

 private:
  const Scene& scene_;
  const ImmersedBoundary& ib_;
  MembraneMarkers2D& body_;
  LatticeBoltzmann2D& fluid_;
};

class ViscosityContrastStage2D : public StepStage {
 public:
  ViscosityContrastStage2D(const Scene& scene, const LatticeUnits& units, const Grid2D& grid,
                           MembraneMarkers2D& body, LatticeBoltzmann2D& fluid);
  const char* name() const override { return "viscosity"; }
  std::string Describe() const override;
  void Reset() override;  // after the fluid's: sets its field from the initial shape
  void Run(long step) override;
  void Save(CheckpointWriter&) const override {}  // a function of the markers
  void Restore(CheckpointReader&) override;

 private:
  const Scene& scene_;
  const LatticeUnits& units_;
  Grid2D grid_;
  MembraneMarkers2D& body_;
  LatticeBoltzmann2D& fluid_;
  std::unique_ptr<ViscosityIndicator> indicator_;
};

class FluidStage2D : public StepStage {
 public:
  FluidStage2D(const Scene& scene, const LatticeUnits& units, MembraneMarkers2D& body);
  const char* name() const override { return "fluid"; }
  std::string Describe() const override;
  void Reset() override;  // first of all stages: uniform viscosity, shear or rest
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

  LatticeBoltzmann2D& lattice() { return *lattice_; }
  const LatticeBoltzmann2D& lattice() const { return *lattice_; }
  void ApplyShearRate();  // wall velocities -+k L from body.shear_rate (at the next step)

 private:
  const Scene& scene_;
  const LatticeUnits& units_;
  MembraneMarkers2D& body_;
  std::unique_ptr<LatticeBoltzmann2D> lattice_;
};

class MarkerStage2D : public StepStage {
 public:
  // electric may be null (no field); it is told when drop markers are re-spaced.
  MarkerStage2D(const Scene& scene, const Grid2D& grid, const ImmersedBoundary& ib,
                MembraneMarkers2D& body, const LatticeBoltzmann2D& fluid,
                ElectricStage2D* electric);
  const char* name() const override { return "markers"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

  long redistributions() const { return redistributions_; }

 private:
  void RedistributeBunchedMarkers();  // numerics.redistribute_markers (drops)

  const Scene& scene_;
  Grid2D grid_;
  const ImmersedBoundary& ib_;
  MembraneMarkers2D& body_;
  const LatticeBoltzmann2D& fluid_;
  ElectricStage2D* electric_;
  MarkerAdvector advector_;
  // numerics.marker_filter_every; order 8, lower for fewer than 17 markers (it needs 2p + 1).
  SawtoothFilter sawtooth_;
  long redistributions_ = 0;
};

class DiagnosticsStage2D : public StepStage {
 public:
  DiagnosticsStage2D(const Scene& scene, const LatticeUnits& units, MembraneMarkers2D& body,
                     const LatticeBoltzmann2D& fluid, bool electric);
  const char* name() const override { return "diagnostics"; }
  std::string Describe() const override;
  void Reset() override;  // the public state of the initial shape
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

 private:
  // The public state's shape, area drift, tank-treading phase and F_E from the body.
  void MeasureInto(const ShapeDiagnostics& d, SimulationState& s) const;

  const Scene& scene_;
  const LatticeUnits& units_;
  MembraneMarkers2D& body_;
  const LatticeBoltzmann2D& fluid_;
  bool electric_;
  TankTreadingTracker tracker_;
  double initial_length_ = 0;  // membrane length of the initial shape
};

}  // namespace ehd
