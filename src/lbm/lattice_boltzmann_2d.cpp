// LatticeBoltzmann2D: parameters, initial states, force/viscosity fields and outputs.
// The kernel is in stream_collide.cpp, the collision in lbm/mrt_collision.h.
//
// Initial state (Chapman-Enskog, song2019 eqs. (97)-(99)): f = f^eq(rho, u) + M^-1 m^neq with the
// only non-zero non-equilibrium moments (incompressible flow)
//   p_xx^neq = -(2/(3 s_nu)) (du_x/dx - du_y/dy),  p_xy^neq = -(1/(3 s_nu)) (du_x/dy + du_y/dx),
// f^eq_i = w_i [rho + 3 c_i.u + 9/2 (c_i.u)^2 - 3/2 |u|^2] (rho_0 = 1, whose moments are the m^eq
// of section 3.1.1); this pre-collision f is then collided (zero force) so that the stored buffer
// holds a post-collision f*, as after a Step.
#include "ehd_capsule/lbm/lattice_boltzmann_2d.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "ehd_capsule/lbm/d2q9.h"

namespace ehd {
namespace {

void CheckRate(const char* name, double s) {
  if (!(s > 0.0 && s < 2.0)) {
    std::ostringstream m;
    m << "LbmParameters." << name << " = " << s << " is outside the stable range (0, 2)";
    throw std::invalid_argument(m.str());
  }
}

void CheckViscosity(const char* name, double nu) {
  if (!(std::isfinite(nu) && nu > 0.0)) {
    std::ostringstream m;
    m << name << " = " << nu << " gives tau = 3 nu + 1/2 = " << 3.0 * nu + 0.5
      << "; the lattice Boltzmann relaxation time must satisfy tau > 0.5, i.e. viscosity > 0";
    throw std::invalid_argument(m.str());
  }
}

}  // namespace

LatticeBoltzmann2D::LatticeBoltzmann2D(const LbmParameters& p) : params_(p) {
  if (p.nx < 1 || p.ny < 1) {
    std::ostringstream m;
    m << "LbmParameters.nx = " << p.nx << ", ny = " << p.ny << ": both must be >= 1";
    throw std::invalid_argument(m.str());
  }
  CheckViscosity("LbmParameters.viscosity", p.viscosity);
  CheckRate("s_e", p.s_e);
  CheckRate("s_epsilon", p.s_epsilon);
  CheckRate("s_q", p.s_q);
  if (!std::isfinite(p.wall_velocity_bottom) || !std::isfinite(p.wall_velocity_top)) {
    throw std::invalid_argument("LbmParameters wall velocities must be finite");
  }
  if (p.threads < 0) {
    throw std::invalid_argument("LbmParameters.threads = " + std::to_string(p.threads) +
                                " must be >= 0 (0: OpenMP default)");
  }
  n_ = static_cast<std::size_t>(p.nx) * static_cast<std::size_t>(p.ny);
  buffers_[0].assign(d2q9::kQ * n_, 0.0);
  buffers_[1].assign(d2q9::kQ * n_, 0.0);
  force_x_.assign(n_, 0.0);
  force_y_.assign(n_, 0.0);
  rho_.assign(n_, 1.0);
  ux_.assign(n_, 0.0);
  uy_.assign(n_, 0.0);
  InitializeAtRest();
}

Grid2D LatticeBoltzmann2D::grid() const {
  return Grid2D{params_.nx, params_.ny, 1.0, -0.5 * params_.nx, -0.5 * params_.ny};
}

void LatticeBoltzmann2D::CheckNodeField(const std::vector<double>& v, const char* name) const {
  if (v.size() != n_) {
    std::ostringstream m;
    m << name << " has " << v.size() << " values; expected nx * ny = " << n_;
    throw std::invalid_argument(m.str());
  }
}

void LatticeBoltzmann2D::InitializeAtRest() {
  InitializeState(std::vector<double>(n_, 1.0), std::vector<double>(n_, 0.0),
                  std::vector<double>(n_, 0.0));
}

void LatticeBoltzmann2D::InitializeShear(double shear_rate) {
  const Grid2D g = grid();
  std::vector<double> ux(n_), uy(n_, 0.0);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) ux[g.index(i, j)] = shear_rate * g.y(j);
  }
  if (params_.boundary != FluidBoundary::kPeriodic) {
    SetWallVelocities(shear_rate * g.y0, shear_rate * g.y_max());
  }
  InitializeState(std::vector<double>(n_, 1.0), ux, uy);
}

void LatticeBoltzmann2D::InitializeVelocity(const std::vector<double>& ux,
                                            const std::vector<double>& uy) {
  InitializeState(std::vector<double>(n_, 1.0), ux, uy);
}

void LatticeBoltzmann2D::InitializeState(const std::vector<double>& rho,
                                         const std::vector<double>& ux,
                                         const std::vector<double>& uy) {
  using namespace d2q9;
  CheckNodeField(rho, "rho");
  CheckNodeField(ux, "ux");
  CheckNodeField(uy, "uy");
  const int nx = params_.nx, ny = params_.ny;
  const bool periodic_y = params_.boundary == FluidBoundary::kPeriodic;
  const bool periodic_x = params_.boundary != FluidBoundary::kClosedBox;
  // Central differences; periodic wrap or one-sided differences at walls.
  auto derivative = [&](const std::vector<double>& v, int i, int j, bool along_x) {
    const int n_dir = along_x ? nx : ny;
    const bool periodic = along_x ? periodic_x : periodic_y;
    const int k = along_x ? i : j;
    if (n_dir < 2) return 0.0;
    auto at = [&](int kk) {
      return along_x ? v[static_cast<std::size_t>(j) * nx + kk]
                     : v[static_cast<std::size_t>(kk) * nx + i];
    };
    if (periodic) return 0.5 * (at((k + 1) % n_dir) - at((k - 1 + n_dir) % n_dir));
    if (k == 0) return at(1) - at(0);
    if (k == n_dir - 1) return at(k) - at(k - 1);
    return 0.5 * (at(k + 1) - at(k - 1));
  };
  std::vector<double>& f = current();
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t node = static_cast<std::size_t>(j) * nx + i;
      const double u = ux[node], v = uy[node], r = rho[node];
      if (!std::isfinite(u) || !std::isfinite(v) || !std::isfinite(r)) {
        throw std::invalid_argument("initial rho/ux/uy must be finite");
      }
      const double s_nu =
          variable_viscosity_ ? s_nu_field_[node] : ShearRateFromViscosity(params_.viscosity);
      const double dudx = derivative(ux, i, j, true), dudy = derivative(ux, i, j, false);
      const double dvdx = derivative(uy, i, j, true), dvdy = derivative(uy, i, j, false);
      const double pxx_neq = -(2.0 / (3.0 * s_nu)) * (dudx - dvdy);
      const double pxy_neq = -(1.0 / (3.0 * s_nu)) * (dudy + dvdx);
      for (int q = 0; q < kQ; ++q) {
        const double cu = kCx[q] * u + kCy[q] * v;
        const double feq = kWeight[q] * (r + 3.0 * cu + 4.5 * cu * cu - 1.5 * (u * u + v * v));
        const double fneq =
            0.25 * (kMomentMatrix[kStressXX][q] * pxx_neq + kMomentMatrix[kStressXY][q] * pxy_neq);
        f[q * n_ + node] = feq + fneq;
      }
    }
  }
  CollideInPlaceWithoutForce();
  step_ = 0;
}

void LatticeBoltzmann2D::CollideInPlaceWithoutForce() {
  std::vector<double>& f = current();
  const MrtRates rates{params_.s_e, params_.s_epsilon, params_.s_q};
  const double s_nu_uniform = d2q9::ShearRateFromViscosity(params_.viscosity);
  for (std::size_t node = 0; node < n_; ++node) {
    double p[d2q9::kQ];
    for (int q = 0; q < d2q9::kQ; ++q) p[q] = f[q * n_ + node];
    const double s_nu = variable_viscosity_ ? s_nu_field_[node] : s_nu_uniform;
    auto kernel = params_.forcing == ForcingScheme::kGuo
                      ? &MrtCollideNode<ForcingScheme::kGuo>
                      : &MrtCollideNode<ForcingScheme::kSplitMomentum>;
    kernel(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], 0.0, 0.0, s_nu, rates, rho_[node],
           ux_[node], uy_[node]);
    for (int q = 0; q < d2q9::kQ; ++q) f[q * n_ + node] = p[q];
  }
}

void LatticeBoltzmann2D::ClearForce() {
  std::fill(force_x_.begin(), force_x_.end(), 0.0);
  std::fill(force_y_.begin(), force_y_.end(), 0.0);
}

void LatticeBoltzmann2D::SetViscosityField(const std::vector<double>& nu) {
  CheckNodeField(nu, "viscosity field");
  s_nu_field_.resize(n_);
  for (std::size_t node = 0; node < n_; ++node) SetNodeViscosity(nu, node);
  variable_viscosity_ = true;
}

void LatticeBoltzmann2D::UpdateViscosityField(const std::vector<double>& nu,
                                              const std::vector<std::size_t>& nodes) {
  if (!variable_viscosity_) {
    throw std::logic_error("UpdateViscosityField: call SetViscosityField first");
  }
  CheckNodeField(nu, "viscosity field");
  for (const std::size_t node : nodes) SetNodeViscosity(nu, node);
}

void LatticeBoltzmann2D::SetNodeViscosity(const std::vector<double>& nu, std::size_t node) {
  if (!(std::isfinite(nu[node]) && nu[node] > 0.0)) {
    CheckViscosity(("viscosity field[" + std::to_string(node) + "]").c_str(), nu[node]);
  }
  s_nu_field_[node] = d2q9::ShearRateFromViscosity(nu[node]);
}

void LatticeBoltzmann2D::ClearViscosityField() {
  variable_viscosity_ = false;
  s_nu_field_.clear();
}

void LatticeBoltzmann2D::SetWallVelocities(double bottom, double top) {
  if (!std::isfinite(bottom) || !std::isfinite(top)) {
    throw std::invalid_argument("SetWallVelocities: wall velocities must be finite");
  }
  params_.wall_velocity_bottom = bottom;
  params_.wall_velocity_top = top;
}

void LatticeBoltzmann2D::Step() {
  StreamCollide();
  current_index_ = 1 - current_index_;
  ++step_;
}

double LatticeBoltzmann2D::MaxSpeed() const {
  double max2 = 0.0;
  for (std::size_t k = 0; k < n_; ++k) max2 = std::max(max2, ux_[k] * ux_[k] + uy_[k] * uy_[k]);
  return std::sqrt(max2);
}

bool LatticeBoltzmann2D::AllFinite() const {
  for (double v : current()) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

void LatticeBoltzmann2D::SetPopulations(const std::vector<double>& f) {
  if (f.size() != d2q9::kQ * n_) {
    std::ostringstream m;
    m << "SetPopulations: " << f.size() << " values; expected 9 * nx * ny = " << d2q9::kQ * n_;
    throw std::invalid_argument(m.str());
  }
  current() = f;
  for (std::size_t node = 0; node < n_; ++node) {
    double r = 0.0, jx = 0.0, jy = 0.0;
    for (int q = 0; q < d2q9::kQ; ++q) {
      const double v = f[q * n_ + node];
      r += v;
      jx += d2q9::kCx[q] * v;
      jy += d2q9::kCy[q] * v;
    }
    rho_[node] = r;
    ux_[node] = jx - 0.5 * force_x_[node];
    uy_[node] = jy - 0.5 * force_y_[node];
  }
}

}  // namespace ehd
