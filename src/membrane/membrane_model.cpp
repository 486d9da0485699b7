// Composition of the membrane terms of song2019 sec. 3.3 (eqs. (110)-(116)); see
// membrane_model.h.
#include "ehd_capsule/membrane/membrane_model.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace ehd {
namespace {

void CheckNonNegative(double v, const char* name) {
  if (!(v >= 0.0)) {
    std::ostringstream os;
    os << "MembraneParameters: " << name << " must be >= 0, got " << v;
    throw std::invalid_argument(os.str());
  }
}

}  // namespace

MembraneModel::MembraneModel(const MembraneParameters& p, const ClosedCurve& reference_shape)
    : params_(p) {
  CheckNonNegative(p.tension, "tension (gamma)");
  CheckNonNegative(p.shear_modulus, "shear_modulus (E_s)");
  CheckNonNegative(p.membrane_viscosity, "membrane_viscosity (mu_s)");
  CheckNonNegative(p.bending_modulus, "bending_modulus (E_B)");
  const int m = reference_shape.size();
  if (m < 5) {
    throw std::invalid_argument("MembraneModel: need at least 5 markers, got " + std::to_string(m));
  }
  if (p.tension > 0.0) interfacial_ = InterfacialTension{p.tension};
  if (p.shear_modulus > 0.0) hookean_ = HookeanTension{p.shear_modulus};
  if (p.membrane_viscosity > 0.0) kelvin_voigt_ = KelvinVoigtTension{p.membrane_viscosity};
  if (p.bending_modulus > 0.0) bending_ = BendingTension{p.bending_modulus};

  reference_length_.resize(m);
  reference_curvature_.resize(m);
  // Same evaluation path as ComputeForce, so the reference shape gives exactly zero force.
  segments_.Update(reference_shape);
  for (int k = 0; k < m; ++k) {
    reference_length_[k] = segments_.SegmentArcLength(k);
    reference_curvature_[k] = segments_.AtMarker(k).curvature;
  }
  stretch_prev1_.assign(m, 1.0);
  stretch_prev2_.assign(m, 1.0);
  for (auto* v : {&segment_length_, &stretch_, &stretch_rate_, &tau_segment_, &tau_marker_,
                  &excess_curvature_, &q_, &dq_dl_}) {
    v->assign(m, 0.0);
  }
}

void MembraneModel::ComputeForce(const ClosedCurve& curve, double dt,
                                 Eigen::Matrix2Xd& force_density) {
  const int m = size();
  if (curve.size() != m) {
    throw std::invalid_argument("MembraneModel::ComputeForce: curve has " +
                                std::to_string(curve.size()) + " markers, reference has " +
                                std::to_string(m));
  }
  if (kelvin_voigt_ && !(dt > 0.0)) {
    throw std::invalid_argument(
        "MembraneModel::ComputeForce: dt must be > 0 with membrane viscosity, got " +
        std::to_string(dt));
  }
  segments_.Update(curve);
  for (int k = 0; k < m; ++k) {
    segment_length_[k] = segments_.SegmentArcLength(k);
    stretch_[k] = segment_length_[k] / reference_length_[k];
  }
  stencil_.Build(segment_length_);
  frames_.Update(segments_);

  std::fill(tau_segment_.begin(), tau_segment_.end(), 0.0);
  if (interfacial_) interfacial_->Add(tau_segment_);
  if (hookean_) hookean_->Add(stretch_, tau_segment_);
  if (kelvin_voigt_) {
    for (int k = 0; k < m; ++k) {
      stretch_rate_[k] =
          history_ >= 2
              ? (3.0 * stretch_[k] - 4.0 * stretch_prev1_[k] + stretch_prev2_[k]) / (2.0 * dt)
              : (stretch_[k] - stretch_prev1_[k]) / dt;
    }
    kelvin_voigt_->Add(stretch_, stretch_rate_, tau_segment_);
  }
  if (bending_) {
    for (int k = 0; k < m; ++k)
      excess_curvature_[k] = frames_.curvature[k] - reference_curvature_[k];
    bending_->Compute(stencil_, excess_curvature_, frames_.orientation, q_, dq_dl_);
    MembraneForceDensity(frames_, stencil_, tau_segment_, &q_, &dq_dl_, tau_marker_, force_density);
  } else {
    MembraneForceDensity(frames_, stencil_, tau_segment_, nullptr, nullptr, tau_marker_,
                         force_density);
  }
  // Advance the stretch history (swap: no allocation).
  stretch_prev2_.swap(stretch_prev1_);
  stretch_prev1_ = stretch_;
  history_ = std::min(history_ + 1, 2);
}

std::string MembraneModel::Describe() const {
  std::ostringstream os;
  os.precision(6);
  const char* sep = "";
  if (interfacial_) {
    os << "interfacial tension(gamma=" << interfacial_->gamma << ")";
    sep = " + ";
  }
  if (hookean_) {
    os << sep << "Hookean(E_s=" << hookean_->shear_modulus << ")";
    sep = " + ";
  }
  if (kelvin_voigt_) {
    os << sep << "Kelvin-Voigt(mu_s=" << kelvin_voigt_->membrane_viscosity << ")";
    sep = " + ";
  }
  if (bending_) {
    os << sep << "bending(E_B=" << bending_->bending_modulus << ")";
    sep = " + ";
  }
  const std::string s = os.str();
  return s.empty() ? "none" : s;
}

MembraneStabilityLimits MembraneModel::Stability(const ClosedCurve& curve, double fluid_viscosity,
                                                 double grid_spacing,
                                                 const KernelTransform& kernel_transform) const {
  double min_spacing = curve.SegmentArcLength(0);
  double max_stretch = 1.0;
  for (int k = 0; k < curve.size(); ++k) {
    const double l = curve.SegmentArcLength(k);
    min_spacing = std::min(min_spacing, l);
    if (k < size()) max_stretch = std::max(max_stretch, l / reference_length_[k]);
  }
  // In-plane stiffness d tau / d lambda = E_s, plus the normal stiffness of the elastic
  // prestress E_s (lambda - 1) when stretched.
  const double elastic = params_.shear_modulus * max_stretch;
  return EstimateMembraneStability(params_.tension, elastic, params_.bending_modulus,
                                   params_.membrane_viscosity, fluid_viscosity, grid_spacing,
                                   min_spacing, kernel_transform);
}

double MembraneModel::StableTimeStep(const ClosedCurve& curve, double fluid_viscosity,
                                     double grid_spacing) const {
  return Stability(curve, fluid_viscosity, grid_spacing).min_dt();
}

}  // namespace ehd
