// Stage 3 of the coupled step: the immersed-boundary spreading of the marker forces (song2019
// eq. (106)), and with V != 1 the viscosity field mu(x) = mu_c + (mu_a - mu_c) H(d(x)) from the
// markers (eqs. (117)-(118)).
#include <sstream>

#include "ehd_capsule/coupling/capsule_stages_2d.h"

namespace ehd {

SpreadStage2D::SpreadStage2D(const Scene& scene, const ImmersedBoundary& ib,
                             MembraneMarkers2D& body, LatticeBoltzmann2D& fluid)
    : scene_(scene), ib_(ib), body_(body), fluid_(fluid) {}

std::string SpreadStage2D::Describe() const {
  return std::string("cosine delta (eq. 103), spread (f_membrane") +
         (body_.electric_density.size() > 0 ? " + F_E" : "") + ") dl" +
         (scene_.has_shear() ? ", periodic in x" : "");
}

void SpreadStage2D::Run(long) {
  MarkerArcElements(body_.curve, body_.dl);
  const int markers = static_cast<int>(body_.X.cols());
  const bool electric = body_.electric_density.cols() == markers;
  for (int k = 0; k < markers; ++k) {
    if (electric) {
      body_.marker_force.col(k) =
          (body_.membrane_density.col(k) + body_.electric_density.col(k)) * body_.dl[k];
    } else {
      body_.marker_force.col(k) = body_.membrane_density.col(k) * body_.dl[k];
    }
  }
  fluid_.ClearForce();
  ib_.Spread(body_.X, body_.marker_force, fluid_.force_x(), fluid_.force_y());
}

void SpreadStage2D::Restore(CheckpointReader&) { MarkerArcElements(body_.curve, body_.dl); }

ViscosityContrastStage2D::ViscosityContrastStage2D(const Scene& scene, const LatticeUnits& units,
                                                   const Grid2D& grid, MembraneMarkers2D& body,
                                                   LatticeBoltzmann2D& fluid)
    : scene_(scene), units_(units), grid_(grid), body_(body), fluid_(fluid) {}

std::string ViscosityContrastStage2D::Describe() const {
  std::ostringstream out;
  out << "smoothed Heaviside (eq. 117), nu_in = " << units_.viscosity_inner
      << ", nu_out = " << units_.viscosity << " (V = " << scene_.V << ")";
  return out.str();
}

void ViscosityContrastStage2D::Reset() {
  // A fresh indicator, so a reset run is the same as a newly built one.
  indicator_ = std::make_unique<ViscosityIndicator>(grid_, scene_.has_shear(), false,
                                                    units_.viscosity_inner, units_.viscosity);
  indicator_->Update(body_.curve);
  fluid_.SetViscosityField(indicator_->viscosity());
}

void ViscosityContrastStage2D::Run(long) {
  // The fluid's field was last set from this indicator (build, reset, restore), so passing only
  // the band the indicator rewrote keeps them equal at O(band) cost per step.
  indicator_->Update(body_.curve);
  if (indicator_->last_update_was_full()) {
    fluid_.SetViscosityField(indicator_->viscosity());
  } else {
    fluid_.UpdateViscosityField(indicator_->viscosity(), indicator_->updated_nodes());
  }
}

void ViscosityContrastStage2D::Restore(CheckpointReader&) {
  indicator_->Update(body_.curve);
  fluid_.SetViscosityField(indicator_->viscosity());
}

}  // namespace ehd
