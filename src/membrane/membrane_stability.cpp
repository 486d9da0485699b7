// Explicit stability estimates of the membrane terms; see membrane_stability.h.
#include "ehd_capsule/membrane/membrane_stability.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {

double MembraneStabilityLimits::min_dt() const {
  return std::min({tension_dt, elastic_dt, bending_dt, compression_dt});
}

double CosineDeltaTransform(double xi) {
  constexpr double kPi = 3.141592653589793;
  xi = std::abs(xi);
  if (xi < 1e-8) return 1.0;
  const double sinc = std::sin(2.0 * xi) / (2.0 * xi);
  const double denom = 1.0 - 4.0 * xi * xi / (kPi * kPi);
  if (std::abs(denom) < 1e-8) return 0.5;  // removable singularity at xi = pi / 2
  return sinc / denom;
}

MembraneStabilityLimits EstimateMembraneStability(double gamma, double elastic_stiffness,
                                                  double bending_modulus, double membrane_viscosity,
                                                  double fluid_viscosity, double grid_spacing,
                                                  double min_marker_spacing,
                                                  const KernelTransform& kernel_transform) {
  if (!(fluid_viscosity > 0.0) || !(grid_spacing > 0.0) || !(min_marker_spacing > 0.0)) {
    throw std::invalid_argument(
        "EstimateMembraneStability: fluid_viscosity, grid_spacing and marker spacing must be > 0 "
        "(got " +
        std::to_string(fluid_viscosity) + ", " + std::to_string(grid_spacing) + ", " +
        std::to_string(min_marker_spacing) + ")");
  }
  constexpr double kPi = 3.141592653589793;
  const double k_max = kPi / min_marker_spacing;
  // max over k of k^(p-1) phi_hat(k h)^2, sampled finely (the function is smooth).
  double g1 = 0.0, g3 = 0.0;
  const int samples = 2000;
  for (int i = 1; i <= samples; ++i) {
    const double k = k_max * i / samples;
    const double p2 = std::pow(kernel_transform(k * grid_spacing), 2);
    g1 = std::max(g1, k * p2);
    g3 = std::max(g3, k * k * k * p2);
  }
  const double four_mu = 4.0 * fluid_viscosity;
  MembraneStabilityLimits lim;
  if (gamma > 0.0) lim.tension_dt = four_mu / (gamma * g1);
  if (elastic_stiffness > 0.0) lim.elastic_dt = four_mu / (elastic_stiffness * g1);
  if (bending_modulus > 0.0) lim.bending_dt = four_mu / (bending_modulus * g3);
  lim.viscous_number = std::max(membrane_viscosity, 0.0) * g1 / four_mu;
  return lim;
}

double GridNyquistTransmission(const KernelTransform& kernel_transform) {
  constexpr double kPi = 3.141592653589793;
  // The series of phi_hat at the odd multiples of pi, to 23 pi (a C^1 kernel's phi_hat decays as
  // xi^-3: the tail is ~1e-4 of roma3's 1/3; Roma3DeltaTransform's quadrature holds to there).
  double sum = 0.0;
  for (int p = 0; p < 12; ++p) sum += kernel_transform((2 * p + 1) * kPi);
  const double t = std::abs(2.0 * sum);
  return t < 1e-6 ? 0.0 : t;
}

double LatticeCompressionStep(double elastic_stiffness, double tau, double grid_spacing,
                              double min_marker_spacing, const KernelTransform& kernel_transform) {
  if (!(elastic_stiffness > 0.0)) return std::numeric_limits<double>::infinity();
  if (!(tau > 0.5) || !(grid_spacing > 0.0) || !(min_marker_spacing > 0.0)) {
    throw std::invalid_argument("LatticeCompressionStep: tau must be > 1/2 and the spacings > 0");
  }
  const double t_pi = GridNyquistTransmission(kernel_transform);
  if (t_pi == 0.0) return std::numeric_limits<double>::infinity();
  // Forward Euler's measured threshold; AB2 measured half of it (0.577 against 1.15 S / mu).
  constexpr double kC = 0.0261;  // 0.235 / 9: roma3's S_c = 0.235 (dl / h) at tau = 1
  const double critical =
      kC * (min_marker_spacing / grid_spacing) * std::cbrt(2.0 * (tau - 0.5)) / (t_pi * t_pi);
  return critical / (2.0 * elastic_stiffness);
}

}  // namespace ehd
