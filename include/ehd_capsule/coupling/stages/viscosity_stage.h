// The viscosity-contrast stage: the fluid's viscosity field mu(x) = mu_c + (mu_a - mu_c) H(d(x))
// from the markers (song2019 eqs. (117)-(118), ib/viscosity_indicator.h); built only with V != 1.
// 2D only: the scene refuses V != 1 in 3D (there is no 3D indicator yet), so only
// ViscosityStage<2> exists.
#pragma once

#include <memory>
#include <string>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/dimension_traits.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/ib/viscosity_indicator.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

template <int D>
class ViscosityStage : public StepStage {
  static_assert(D == 2, "the viscosity contrast is built in 2D only (scene: V != 1 in 3D)");

 public:
  ViscosityStage(const Scene& scene, const LatticeUnits& units, const Grid<D>& grid,
                 StepData<D>& data, FluidOf<D>& fluid);
  const char* name() const override { return "viscosity"; }
  std::string Describe() const override;
  void Reset() override;  // after the fluid's: sets its field from the initial shape
  void Run(long step) override;
  void Save(CheckpointWriter&) const override {}  // a function of the markers
  void Restore(CheckpointReader&) override;

 private:
  const Scene& scene_;
  const LatticeUnits& units_;
  Grid<D> grid_;
  StepData<D>& data_;
  FluidOf<D>& fluid_;
  std::unique_ptr<ViscosityIndicator> indicator_;
};

extern template class ViscosityStage<2>;

}  // namespace ehd
