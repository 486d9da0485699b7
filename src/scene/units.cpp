// Dimensionless numbers -> lattice values; the formulas are listed in units.h.
#include "ehd_capsule/scene/units.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace ehd {

LatticeUnits DeriveLatticeUnits(const Scene& s) {
  LatticeUnits u;
  u.half_width = 0.5 * s.N;
  u.ny = s.N;
  u.nx = s.N;
  if (s.dimension == 3 && s.geometry.half_length > 0) {  // N itself is checked by the scene
    u.nx = static_cast<int>(std::lround(s.N * s.geometry.half_length / s.geometry.half_width));
    if (u.nx < 16 || u.nx > 4096) {
      throw SceneError(
          "scene " + s.name + ": geometry.half_length = " + std::to_string(s.geometry.half_length) +
          " gives " + std::to_string(u.nx) + " cells along x and z at N = " + std::to_string(s.N) +
          " (half_width = " + std::to_string(s.geometry.half_width) +
          "); the grid needs 16 to 4096");
    }
  }
  u.nz = s.dimension == 3 ? u.nx : 1;
  u.radius = u.half_width / s.geometry.half_width;
  // membrane_substeps n refines the time step at fixed h: nu -> nu / n (and k -> k / n through
  // k = Re nu / a^2), i.e. tau -> 1/2 + (tau - 1/2) / n.
  u.tau = 0.5 + (s.numerics.tau - 0.5) / s.numerics.membrane_substeps;
  u.viscosity = (u.tau - 0.5) / 3.0;
  u.viscosity_inner = s.V * u.viscosity;
  u.tau_inner = 3.0 * u.viscosity_inner + 0.5;
  if (!(u.tau > 0.5) || !(u.tau_inner > 0.5)) {
    throw SceneError("scene " + s.name + ": relaxation time tau = " + std::to_string(u.tau) +
                     " (inner " + std::to_string(u.tau_inner) +
                     ") must exceed 1/2 (numerics.tau in (0.5, 20])");
  }
  const double mu = u.viscosity;  // rho = 1
  const double a = u.radius;
  if (s.has_shear()) {
    u.shear_rate = s.Re * u.viscosity / (a * a);
    u.tension = mu * u.shear_rate * a / s.Ca;
    u.steps_per_time_unit = 1.0 / u.shear_rate;
    u.time_unit = "1/k";
  } else {
    u.tension = mu * mu / (a * s.Oh * s.Oh);
    u.steps_per_time_unit = mu * a / u.tension;
    u.time_unit = s.membrane == MembraneKind::kDrop ? "mu a/gamma" : "mu a/E_s";
  }
  u.dt = 1.0 / u.steps_per_time_unit;
  u.wall_speed = u.shear_rate * u.half_width;
  u.wall_mach = u.wall_speed / kLatticeSoundSpeed;
  u.bending_modulus = s.membrane == MembraneKind::kCapsule ? s.E_b * a * a * u.tension : 0.0;
  u.membrane_viscosity = s.membrane == MembraneKind::kCapsule ? s.eta * a * mu : 0.0;
  u.eps_plus = 1.0;
  u.eps_minus = s.eps_r;
  u.sigma_plus = 1.0;
  u.sigma_minus = s.sigma_r;
  u.field = FieldForCaE(u, s.Ca_E);
  if (u.wall_mach > s.numerics.max_mach) {
    std::ostringstream m;
    // k L = (Re nu / a^2) (N / 2) with a = N / (2 L/a): 2 Re nu (L/a)^2 / N, nu = (tau - 1/2) / 3n.
    m << "scene " << s.name << ": wall speed k L = 2 Re nu (L/a)^2 / N = " << u.wall_speed
      << " is lattice Mach " << u.wall_mach << " > " << s.numerics.max_mach
      << " (numerics.max_mach), set by geometry.half_width = " << s.geometry.half_width
      << " (squared), Re = " << s.Re << ", numerics.tau = " << s.numerics.tau << " and N = " << s.N
      << ": lower geometry.half_width, Re or numerics.tau, or raise N or "
      << "numerics.membrane_substeps (now " << s.numerics.membrane_substeps << ")";
    throw SceneError(m.str());
  }
  return u;
}

double FieldForCaE(const LatticeUnits& u, double ca_e) {
  return std::sqrt(ca_e * u.tension / (u.eps_plus * u.radius));
}

double ShearRateForCa(const LatticeUnits& u, double ca) {
  return ca * u.tension / (u.viscosity * u.radius);
}

std::string DescribeUnits(const Scene& s, const LatticeUnits& u) {
  std::ostringstream out;
  out << std::setprecision(5);
  const char* t = s.membrane == MembraneKind::kDrop ? "gamma" : s.dimension == 3 ? "G_s" : "E_s";
  out << "lattice values (h = dt = rho = 1):\n"
      << "  grid " << u.nx << " x " << u.ny
      << (s.dimension == 3 ? " x " + std::to_string(u.nz) : "") << ", L = " << u.half_width;
  if (u.nx != u.ny) out << " (L_x = L_z = " << 0.5 * u.nx << ")";
  out << ", a = " << u.radius << " cells, " << s.M
      << (s.dimension == 3 ? " vertices (mean edge ~" : " markers (spacing ")
      << (s.dimension == 3 ? u.radius * std::sqrt(8.0 * M_PI / (std::sqrt(3.0) * (s.M - 2)))
                           : 2.0 * M_PI * u.radius / s.M)
      << " h)\n"
      << "  tau = " << u.tau << " (nu = " << u.viscosity << ")";
  if (s.V != 1.0) out << ", inner tau = " << u.tau_inner << " (nu = " << u.viscosity_inner << ")";
  out << '\n';
  if (s.has_shear()) {
    out << "  shear rate k = " << u.shear_rate << ", wall speed +-" << u.wall_speed << " (Mach "
        << u.wall_mach << ")\n";
  }
  out << "  " << t << " = " << u.tension;
  if (s.has_bending()) out << ", E_B = " << u.bending_modulus;
  if (s.has_membrane_viscosity()) out << ", mu_s = " << u.membrane_viscosity;
  out << '\n';
  if (s.electric_field) {
    out << "  |E_inf| = " << u.field << " (Ca_E = " << s.Ca_E
        << "), eps+ = 1, eps- = " << u.eps_minus << ", sigma+ = 1, sigma- = " << u.sigma_minus
        << '\n';
  }
  out << "  time unit " << u.time_unit << " = " << u.steps_per_time_unit << " steps; dt = " << u.dt
      << " " << u.time_unit << '\n';
  return out.str();
}

}  // namespace ehd
