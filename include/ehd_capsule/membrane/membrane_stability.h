// Explicit time-step limits of the membrane forces in the immersed boundary coupling.
//
// Estimate (quasi-static Stokes response, both sides viscosity mu): a force density
// F e^{i k l} along a straight membrane moves it with velocity F / (4 mu k) (normal and
// tangential alike; it gives the classical capillary relaxation rate gamma k / (4 mu)). The IB
// spreads and interpolates with a kernel (here the cosine one; the roma3 kernel's transform is
// ib/delta_kernel.h's Roma3DeltaTransform), which multiplies that response by
// phi_hat(k h)^2 along the membrane, phi_hat(xi) = sin(2 xi) / (2 xi) / (1 - 4 xi^2 / pi^2)
// (Fourier transform of song2019 eq. (103)). A membrane term of stiffness S k^p (p = 2: tension
// gamma and in-plane elasticity E_s; p = 4: bending E_B) then relaxes mode k at the rate
//   sigma(k) = S k^(p-1) phi_hat(k h)^2 / (4 mu),   k in (0, pi / dl_min],
// with dl_min the smallest marker spacing. Forward Euler is stable for dt sigma < 2 and AB2 for
// dt sigma < 1, so the returned limit is dt_max = 1 / max_k sigma(k) (AB2-safe, factor 2 for
// Euler). The Kelvin-Voigt term, explicit with the stretch history, gives an amplification
// independent of dt: with the one-sided second-order dlambda/dt the mode is stable only while
//   V = mu_s max_k k phi_hat(k h)^2 / (4 mu) < 1/2          (first-order difference: < 1).
// LBM's finite fluid inertia per step makes the real response smaller than the Stokes one, so V
// is a warning indicator, and all limits are estimates to fail early or sub-step, not guarantees.
#pragma once

#include <functional>
#include <limits>

namespace ehd {

struct MembraneStabilityLimits {
  double tension_dt = std::numeric_limits<double>::infinity();  // gamma
  double elastic_dt = std::numeric_limits<double>::infinity();  // E_s (+ prestress tau)
  double bending_dt = std::numeric_limits<double>::infinity();  // E_B
  double viscous_number = 0.0;                                  // V above
  double min_dt() const;
};

// Fourier transform of the cosine kernel phi (unit h) at xi = k h; 1 at xi = 0.
double CosineDeltaTransform(double xi);

// A kernel's Fourier transform phi_hat(xi), xi = k h (the coupling passes the one in use,
// numerics.ib_kernel; the cosine kernel's by default).
using KernelTransform = std::function<double(double)>;

// Limits for stiffnesses gamma, elastic (E_s + max(tau_e, 0)), E_B, mu_s, fluid dynamic viscosity
// mu > 0, grid spacing h > 0 and smallest marker spacing dl_min > 0.
MembraneStabilityLimits EstimateMembraneStability(
    double gamma, double elastic_stiffness, double bending_modulus, double membrane_viscosity,
    double fluid_viscosity, double grid_spacing, double min_marker_spacing,
    const KernelTransform& kernel_transform = CosineDeltaTransform);

}  // namespace ehd
