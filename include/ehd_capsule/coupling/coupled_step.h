// The coupled step (song2019 sec. 3.6) assembled from the scene: the bodies, the stages that act
// on them in run order, and the stages the scene did not need. One class template over the
// dimension (CoupledStepOf<D>, coupled_step.cpp) behind one dimension-free interface
// (CoupledStep), which is what Simulation holds; BuildCoupledStep is the one function that
// chooses the dimension and assembles the stage list.
//
// Run order (each stage built only when the scene needs it; docs/architecture.md):
//   electric     fast IIM potential, Maxwell-stress force source (with a field)
//   membrane     the membrane's force sources (elastic, bending, tension)
//   spread       the sources summed per body (Body::SumLoads), spread to the grid
//   viscosity    mu(x) from the markers (2D, V != 1)
//   fluid        one LBM step, fluid watchdogs
//   markers      interpolate, move, filter, wrap, wall checks
//   diagnostics  shape measures, drift watchdogs, tank-treading, the public state
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/checkpoint_io.h"
#include "ehd_capsule/coupling/simulation_state.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

class CoupledStep {
 public:
  virtual ~CoupledStep() = default;

  // Runs stage by stage the step `step` that reaches `time` (StepData::step, time), timing each.
  void Run(long step, double time);
  // The built stages, one per line, and those left out.
  std::string Pipeline() const;
  const std::vector<StepStage*>& stages() const { return stages_; }
  const std::vector<double>& stage_seconds() const { return stage_seconds_; }
  void ResetStageTimes() { stage_seconds_.assign(stages_.size(), 0.0); }

  virtual int dimension() const = 0;
  virtual StepControls& controls() = 0;
  // The bodies to their initial shapes, the fluid first (the stages that configure it, the
  // viscosity contrast, reset after it), then every other stage in run order.
  virtual void Reset() = 0;
  virtual void ApplyShearRate() = 0;  // wall velocities from controls().shear_rate
  // The first body's positions, for the checkpoint's "markers positions" section.
  virtual void SavePositions(CheckpointWriter& w) const = 0;
  virtual void RestorePositions(CheckpointReader& r) = 0;

  virtual bool has_electric_field() const = 0;
  virtual bool has_viscosity_contrast() const = 0;
  // The grid of the dimension; nullptr for the other one.
  virtual const Grid2D* grid2() const = 0;
  virtual const Grid3D* grid3() const = 0;
  // Fluid velocity component `axis` (< dimension; std::logic_error otherwise).
  virtual const std::vector<double>& velocity(int axis) const = 0;
  virtual const std::vector<double>& potential() const = 0;              // empty without a field
  virtual const std::vector<std::array<int, 3>>& triangles() const = 0;  // empty in 2D
  // 3D only (std::logic_error in 2D): per vertex of the first body, the mean principal tension
  // in units of the modulus and the velocity of the last marker step in a per time unit.
  virtual std::vector<double> VertexTension() const = 0;
  virtual Eigen::Matrix3Xd VertexVelocity() const = 0;
  virtual long marker_redistributions() const = 0;

 protected:
  virtual void SetClock(long step, double time) = 0;  // StepData::step and time
  std::vector<StepStage*> stages_;                    // run order, only what was built
  std::vector<double> stage_seconds_;
  std::vector<std::string> not_built_;  // "electric (why)", for the pipeline text
};

// Builds the step the scene describes (dimension 2 or 3); throws SceneError for unusable lattice
// values (tau, Mach, membrane explicit limit, a mesh too coarse for the grid). The stages report
// to `state`.
std::unique_ptr<CoupledStep> BuildCoupledStep(const Scene& scene, const LatticeUnits& units,
                                              SimulationState& state);

}  // namespace ehd
