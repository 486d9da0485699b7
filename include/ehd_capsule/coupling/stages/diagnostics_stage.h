// The diagnostics stage, last in the step: each body's shape measures (2D: the equivalent
// ellipse's D_xy and inclination, the enclosed area; 3D: the equivalent ellipsoid's D_xy and
// inclination in the shear plane, D along the field axis z, the enclosed volume, the meridional
// surface flow), the watchdogs (area or volume drift; 3D: the mesh degenerating), the
// tank-treading phase of one material point, and the public state (SimulationState, of the
// first body). The clock is the step's (StepData::step, time), not this stage's.
#pragma once

#include <string>
#include <vector>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/dimension_traits.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/diagnostics/shape_diagnostics.h"
#include "ehd_capsule/diagnostics/shape_diagnostics_3d.h"
#include "ehd_capsule/diagnostics/tank_treading.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

template <int D>
class DiagnosticsStage : public StepStage {
 public:
  using Shape = std::conditional_t<D == 2, ShapeDiagnostics, ShapeDiagnostics3D>;
  DiagnosticsStage(const Scene& scene, const LatticeUnits& units, StepData<D>& data,
                   const FluidOf<D>& fluid);
  const char* name() const override { return "diagnostics"; }
  std::string Describe() const override;
  void Reset() override;  // the public state of the initial shape
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

 private:
  struct Tracked {
    TankTreadingTracker tracker{0};
    double initial_length = 0;     // 2D: membrane length of the initial shape
    double initial_min_angle = 0;  // 3D: of the initial mesh, for the degeneration watchdog
  };
  // Throws SimulationError (via FailStep) when the body's area or volume drifted beyond
  // numerics.area_drift_limit or (3D) its mesh degenerates.
  void Watch(long step, const Body<D>& body, const Tracked& tracked, const Shape& d) const;
  // The public state's shape, drifts, tank-treading phase and electric force from body 0.
  void MeasureInto(const Shape& d, SimulationState& s) const;

  const Scene& scene_;
  const LatticeUnits& units_;
  StepData<D>& data_;
  const FluidOf<D>& fluid_;
  std::vector<const ForceSource<D>*> electric_;  // per body; null without a field
  std::vector<Tracked> tracked_;                 // per body
};

extern template class DiagnosticsStage<2>;
extern template class DiagnosticsStage<3>;

}  // namespace ehd
