// A 2D membrane (capsule, red blood cell) or drop interface: the enabled force terms, their
// reference state, and the force density they exert on the fluid at each marker.
//
// song2019 sec. 3.3, eqs. (110)-(116): tau = gamma + E_s (lambda - 1) + mu_s lambda_dot / lambda
// per segment, q = E_B d(kappa - kappa_0)/dl per marker, f = d(tau t + q n)/dl (membrane_force.h
// for the sign). A term with a zero coefficient is not built at all (a scene with E_B = 0 has no
// bending term). Reference state, from the shape passed to the constructor: segment lengths l_0
// (spline arc length between markers, eq. (112)) and the marker curvatures kappa_0 (sec. 3.3:
// "kappa_0 is set equal to the initial curvature"), so the reference shape is force-free.
//
// ComputeForce advances the stretch history used by the Kelvin-Voigt term: call it once per time
// step with that step's dt (constant dt assumed). dlambda/dt is the one-sided second-order
// difference (3 lambda^n - 4 lambda^{n-1} + lambda^{n-2}) / (2 dt) (sec. 3.3 below eq. (114)),
// first-order on the first step, whose previous stretch is the reference (lambda = 1).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/membrane/arc_length_stencil.h"
#include "ehd_capsule/membrane/bending_tension.h"
#include "ehd_capsule/membrane/membrane_force.h"
#include "ehd_capsule/membrane/membrane_stability.h"
#include "ehd_capsule/membrane/tension_laws.h"

namespace ehd {

struct MembraneParameters {
  double tension = 0.0;             // gamma (interfacial tension of a drop)
  double shear_modulus = 0.0;       // E_s, eq. (113)
  double membrane_viscosity = 0.0;  // mu_s, eq. (114)
  double bending_modulus = 0.0;     // E_B, eq. (115)
};

class MembraneModel {
 public:
  // Throws std::invalid_argument for a negative coefficient or fewer than 5 markers.
  MembraneModel(const MembraneParameters& p, const ClosedCurve& reference_shape);

  // force_density (2 x M, resized if needed): force per unit length the membrane exerts on the
  // fluid at each marker. dt > 0 is required when the membrane viscosity term is enabled.
  void ComputeForce(const ClosedCurve& curve, double dt, Eigen::Matrix2Xd& force_density);

  // e.g. "Hookean(E_s=0.01) + bending(E_B=0.0005)"; "none" if no term is enabled.
  std::string Describe() const;

  // Explicit stability limit (membrane_stability.h) for the curve's smallest marker spacing,
  // the fluid's dynamic viscosity mu (rho nu; nu in lattice units when rho = 1) and grid spacing
  // h (1 in lattice units). Covers gamma, E_s (plus the current elastic prestress) and E_B.
  double StableTimeStep(const ClosedCurve& curve, double fluid_viscosity,
                        double grid_spacing = 1.0) const;
  MembraneStabilityLimits Stability(
      const ClosedCurve& curve, double fluid_viscosity, double grid_spacing = 1.0,
      const KernelTransform& kernel_transform = CosineDeltaTransform) const;

  // Total tau at each marker from the last ComputeForce (for output).
  const std::vector<double>& tension() const { return tau_marker_; }
  // Per-segment tension and stretch of the last ComputeForce.
  const std::vector<double>& segment_tension() const { return tau_segment_; }
  const std::vector<double>& stretch() const { return stretch_; }
  // Spline arc length of each segment of the last ComputeForce (reuse for the arc elements
  // dl_k = (l_{k-1} + l_k)/2 instead of recomputing them).
  const std::vector<double>& segment_length() const { return segment_length_; }
  const std::vector<double>& reference_segment_length() const { return reference_length_; }
  const std::vector<double>& reference_curvature() const { return reference_curvature_; }
  const MembraneParameters& parameters() const { return params_; }
  int size() const { return static_cast<int>(reference_length_.size()); }

 private:
  MembraneParameters params_;
  std::optional<InterfacialTension> interfacial_;
  std::optional<HookeanTension> hookean_;
  std::optional<KelvinVoigtTension> kelvin_voigt_;
  std::optional<BendingTension> bending_;

  std::vector<double> reference_length_, reference_curvature_;
  std::vector<double> stretch_prev1_, stretch_prev2_;  // lambda^{n-1}, lambda^{n-2}
  int history_ = 1;                                    // stored previous stretches (1 or 2)

  // Work buffers, sized once.
  CurveSegments segments_;
  ArcLengthStencil stencil_;
  MarkerFrames frames_;
  std::vector<double> segment_length_, stretch_, stretch_rate_, tau_segment_, tau_marker_;
  std::vector<double> excess_curvature_, q_, dq_dl_;
};

}  // namespace ehd
