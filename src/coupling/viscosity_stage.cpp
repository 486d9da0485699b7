// The viscosity-contrast stage (coupling/stages/viscosity_stage.h).
#include "ehd_capsule/coupling/stages/viscosity_stage.h"

#include <sstream>

namespace ehd {

template <int D>
ViscosityStage<D>::ViscosityStage(const Scene& scene, const LatticeUnits& units,
                                  const Grid<D>& grid, StepData<D>& data, FluidOf<D>& fluid)
    : scene_(scene), units_(units), grid_(grid), data_(data), fluid_(fluid) {
  if (data.bodies.size() != 1) {
    throw SceneError("scene " + scene.name + ": the viscosity contrast takes one body (" +
                     std::to_string(data.bodies.size()) + " in the scene)");
  }
}

template <int D>
std::string ViscosityStage<D>::Describe() const {
  std::ostringstream out;
  out << "smoothed Heaviside (eq. 117), nu_in = " << units_.viscosity_inner
      << ", nu_out = " << units_.viscosity << " (V = " << scene_.V << ")";
  return out.str();
}

template <int D>
void ViscosityStage<D>::Reset() {
  // A fresh indicator, so a reset run is the same as a newly built one.
  indicator_ = std::make_unique<ViscosityIndicator>(grid_, scene_.has_shear(), false,
                                                    units_.viscosity_inner, units_.viscosity);
  indicator_->Update(data_.bodies.front().shape.curve);
  fluid_.SetViscosityField(indicator_->viscosity());
}

template <int D>
void ViscosityStage<D>::Run(long) {
  // The fluid's field was last set from this indicator (build, reset, restore), so passing only
  // the band the indicator rewrote keeps them equal at O(band) cost per step.
  indicator_->Update(data_.bodies.front().shape.curve);
  if (indicator_->last_update_was_full()) {
    fluid_.SetViscosityField(indicator_->viscosity());
  } else {
    fluid_.UpdateViscosityField(indicator_->viscosity(), indicator_->updated_nodes());
  }
}

template <int D>
void ViscosityStage<D>::Restore(CheckpointReader&) {
  indicator_->Update(data_.bodies.front().shape.curve);
  fluid_.SetViscosityField(indicator_->viscosity());
}

template class ViscosityStage<2>;

}  // namespace ehd
