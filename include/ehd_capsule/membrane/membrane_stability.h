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
//
// Measured (bench/ib_membrane_modes_bench: a flat periodic membrane in a periodic D2Q9 box, the
// coupling's classes and stage order; docs/validation_3d.md, "The kernel"). The smallest
// S dt / (mu h) at which a mode grows with forward Euler, dl = 0.79 h, tau = 1:
//   cosine  39 tangential, 44 normal (the estimate above: 13.8, 2.8 times too strict);
//   roma3   1.15 tangential, 29 normal (the estimate: 10.4).
// roma3's tangential mode grows at k h = pi along the membrane: a force alternating cell by cell.
// The incompressible Stokes response has no such mode. Its threshold in lattice units hardly
// follows the viscosity (S_c = 0.11 ... 0.23 for tau = 0.6 ... 1.5). It is D2Q9's undamped momentum
// mode at k = (pi, 0): j_x alternating along x with q_x = -j_x, every non-conserved moment at its
// equilibrium, so no relaxation rate (s_e, s_eps, s_q) damps it; near it the damping is nu k_y^2
// across and grows with the bulk viscosity along x (docs/validation_3d.md, "Damping the
// grid-Nyquist mode"). The cosine, trapezoid3 and roma3_even_odd kernels do not couple to it (sum_j
// (-1)^j phi(r - j) = 0 at every r); roma3 couples with T_pi = 1/3. LatticeCompressionStep is the
// empirical fit, within -7.5 % ... +2.5 % of eight measured points (dl 0.75 ... 1.29 h, tau 0.6
// ... 1.5):
//   S_c = 0.235 (dl / h) (2 (tau - 1/2))^(1/3) / (9 T_pi^2)  (forward Euler; AB2: half).
// Only the 2D stage applies it. D3Q19's bulk rate follows tau, and 3D is not measured.
// It catches roma3's fast instability. A slower growth of the curved roma3 capsule below S_c
// remains: the tiny capsule stops at t = 25 with 2 substeps and at t = 43 with 3. With
// roma3_even_odd (roma3 across each component's axis, trapezoid3 along it) the stage skips this
// limit: the tiny capsule runs at one substep with a flat Mach number.
#pragma once

#include <functional>
#include <limits>

namespace ehd {

struct MembraneStabilityLimits {
  double tension_dt = std::numeric_limits<double>::infinity();  // gamma
  double elastic_dt = std::numeric_limits<double>::infinity();  // E_s (+ prestress tau)
  double bending_dt = std::numeric_limits<double>::infinity();  // E_B
  double viscous_number = 0.0;                                  // V above
  // The tangential grid-Nyquist limit of E_s (LatticeCompressionStep; 2D, D2Q9 only).
  double compression_dt = std::numeric_limits<double>::infinity();
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

// T_pi = sum_j (-1)^j phi(j) = 2 sum_{p >= 0} phi_hat((2 p + 1) pi) (Poisson summation): how
// much of a force alternating cell by cell a marker on a node spreads (and of such a velocity it
// interpolates); the largest over the marker's offset in the cell. 0 for the cosine kernel
// (sum_even phi = sum_odd phi = 1/2 at every offset), 1/3 for roma3.
double GridNyquistTransmission(const KernelTransform& kernel_transform);

// The tangential grid-Nyquist limit (2D, D2Q9 MRT with the coupling's rates, lattice units rho =
// h = dt = 1; measured with bench/ib_membrane_modes_bench, see the header comment): the stable
// step for the in-plane stiffness E_s of a membrane with marker spacing dl_min and LBM relaxation
// time tau, in the AB2 convention of EstimateMembraneStability (forward Euler: twice it),
//   dt_max = S_c / (2 E_s),  S_c = c (dl_min / h) (2 (tau - 1/2))^(1/3) / T_pi^2,  c = 0.0261.
// Infinite when the kernel's T_pi vanishes (cosine) or E_s <= 0.
double LatticeCompressionStep(double elastic_stiffness, double tau, double grid_spacing,
                              double min_marker_spacing, const KernelTransform& kernel_transform);

}  // namespace ehd
