// The fluid stage: one lattice Boltzmann step with the spread force (D2Q9 MRT in 2D, song2019
// eqs. (97), (107)-(108); D3Q19 MRT in 3D, sec. 3.1.2), then the fluid watchdogs (non-finite
// velocity, lattice Mach). It owns the lattice; the spread and viscosity stages act on it.
#pragma once

#include <memory>
#include <string>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/dimension_traits.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

template <int D>
class FluidStage : public StepStage {
 public:
  FluidStage(const Scene& scene, const LatticeUnits& units, StepData<D>& data);
  const char* name() const override { return "fluid"; }
  std::string Describe() const override;
  void Reset() override;  // first of all stages: uniform viscosity, shear or rest
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

  FluidOf<D>& lattice() { return *lattice_; }
  const FluidOf<D>& lattice() const { return *lattice_; }
  void ApplyShearRate();  // wall velocities -+k L from the controls (at the next step)

 private:
  const Scene& scene_;
  const LatticeUnits& units_;
  StepData<D>& data_;
  std::unique_ptr<FluidOf<D>> lattice_;
};

extern template class FluidStage<2>;
extern template class FluidStage<3>;

}  // namespace ehd
