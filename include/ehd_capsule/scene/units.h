// Dimensionless scene numbers -> lattice values (the one place where units are converted).
//
// Lattice units: h = 1, dt = 1, rho = 1. The domain [-L, L]^2 has N cells, so L = N/2 and the
// radius is a = N / (2 L/a). The outer fluid has nu = (tau - 1/2)/(3 n) with n =
// numerics.membrane_substeps (time-step refinement at fixed h), mu = rho nu (song2019
// eq. (99) with c = dx/dt = 1), the inner fluid nu_in = V nu. With T the membrane tension scale
// (gamma for a drop, E_s for a capsule):
//   shear:     k = Re nu / a^2                  (Re = rho k a^2 / mu, sec. 4.1)
//              T = mu k a / Ca                  (eq. (119); sec. 4.2.2 for a drop)
//              time unit 1/k steps
//   no shear:  T = mu^2 / (rho a Oh^2)          (Oh = mu / sqrt(rho a T), sec. 4.2.2)
//              time unit mu a / T steps (viscous-capillary time)
//   E_B = E_b a^2 T    (song2019 eq. (120) prints E_B/(a E_s); in 2D E_B has units of
//                       tension x length^2, so the dimensionless form is E_B/(a^2 E_s))
//   mu_s = eta a mu    (eq. (121))
//   eps+ = 1, eps- = eps_r, sigma+ = 1, sigma- = sigma_r, |E_inf| = sqrt(Ca_E T / (eps+ a))
//   (Ca_E = eps+ a E^2 / T, sec. 4.2.2 and 5.1).
// The wall speed is k L; the lattice Mach number k L / c_s (c_s = 1/sqrt 3) must stay small.
#pragma once

#include <string>

#include "ehd_capsule/scene/scene.h"

namespace ehd {

struct LatticeUnits {
  double radius = 0;      // a in cells
  double half_width = 0;  // L in cells
  // Grid cells per axis: N along y (and x in 2D); in 3D round(N L_x / L) along x and z
  // (geometry.half_length), N for a cube.
  int nx = 0, ny = 0, nz = 0;
  double tau = 0;        // outer fluid
  double viscosity = 0;  // nu outer (kinematic; rho = 1 so also mu)
  double tau_inner = 0;
  double viscosity_inner = 0;
  double shear_rate = 0;          // k per step (0 without shear)
  double wall_speed = 0;          // k L
  double wall_mach = 0;           // k L / c_s
  double tension = 0;             // gamma (drop) or E_s (capsule)
  double bending_modulus = 0;     // E_B
  double membrane_viscosity = 0;  // mu_s
  double field = 0;               // |E_inf|
  double eps_plus = 1, eps_minus = 1, sigma_plus = 1, sigma_minus = 1;
  double steps_per_time_unit = 0;  // 1/k or mu a / T
  double dt = 0;                   // one step in the scene's time unit
  std::string time_unit;           // "1/k" or "mu a/gamma" ...
};

constexpr double kLatticeSoundSpeed = 0.57735026918962576;  // 1/sqrt(3)

// Throws SceneError when the lattice values are unusable (tau <= 1/2 inside or outside, wall
// Mach number above scene.numerics.max_mach).
LatticeUnits DeriveLatticeUnits(const Scene& scene);

// Field strength for a given Ca_E, shear rate for a given Ca (membrane tension unchanged).
double FieldForCaE(const LatticeUnits& units, double ca_e);
double ShearRateForCa(const LatticeUnits& units, double ca);

// Multi-line table of the lattice values with the time step in the scene's time unit.
std::string DescribeUnits(const Scene& scene, const LatticeUnits& units);

}  // namespace ehd
