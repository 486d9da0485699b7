// LatticeBoltzmann<L>: parameters, initial states, force/viscosity fields and outputs, written
// once over the lattice descriptor. The kernels are in stream_collide.cpp (D2Q9) and
// stream_collide_d3q19.cpp (D3Q19).
//
// Initial state (Chapman-Enskog, song2019 eqs. (97)-(101)): f = f^eq(rho, u) + M^-1 m^neq with
// the only non-zero non-equilibrium moments the stress moments of the lattice (incompressible
// flow), from Pi^neq = -(1/(3 s_nu)) (grad u + grad u^T):
//   D2Q9   p_xx^neq = -(2/(3 s_nu)) (du_x/dx - du_y/dy),  p_xy^neq = -(1/(3 s_nu)) (du_x/dy +
//          du_y/dx);
//   D3Q19  3p_xx^neq = -(2/(3 s_nu)) (2 du_x/dx - du_y/dy - du_z/dz), p_ww^neq = -(2/(3 s_nu))
//          (du_y/dy - du_z/dz), p_ab^neq = -(1/(3 s_nu)) (du_a/db + du_b/da) for xy, yz, xz;
// f^eq_i = w_i [rho + 3 c_i.u + 9/2 (c_i.u)^2 - 3/2 |u|^2] (rho_0 = 1, whose moments are the m^eq
// of section 3.1); this pre-collision f is then collided (zero force) so that the stored buffer
// holds a post-collision f*, as after a Step.
#include "ehd_capsule/lbm/lattice_boltzmann.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>

#include "stream_collide.h"

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

// Kinematic viscosity <-> shear relaxation rate (song2019 eqs. (99), (101)).
double ShearRate(double nu) { return 1.0 / (3.0 * nu + 0.5); }

// The non-equilibrium stress moments of a velocity gradient grad[a][b] = du_b/dx_a (see the file
// comment); same arithmetic as the original D2Q9 code.
void NonEquilibriumStress(const double grad[2][2], double s_nu, double out[2]) {
  out[0] = -(2.0 / (3.0 * s_nu)) * (grad[0][0] - grad[1][1]);
  out[1] = -(1.0 / (3.0 * s_nu)) * (grad[1][0] + grad[0][1]);
}
void NonEquilibriumStress(const double grad[3][3], double s_nu, double out[5]) {
  const double two = -(2.0 / (3.0 * s_nu)), one = -(1.0 / (3.0 * s_nu));
  out[0] = two * (2.0 * grad[0][0] - grad[1][1] - grad[2][2]);
  out[1] = two * (grad[1][1] - grad[2][2]);
  out[2] = one * (grad[1][0] + grad[0][1]);
  out[3] = one * (grad[2][1] + grad[1][2]);
  out[4] = one * (grad[2][0] + grad[0][2]);
}

template <class L>
void CollideNode(double* f, const double* force, double s_nu, const MrtRates& rates,
                 ForcingScheme forcing, double& rho, double* u) {
  if constexpr (L::kDimension == 2) {
    lbm_kernels::CollideNodeD2Q9(f, force, s_nu, rates, forcing, rho, u);
  } else {
    lbm_kernels::CollideNodeD3Q19(f, force, s_nu, rates, forcing, rho, u);
  }
}

}  // namespace

template <class L>
LatticeBoltzmann<L>::LatticeBoltzmann(const LbmParameters& p) : params_(p) {
  constexpr int D = L::kDimension;
  if (p.nx < 1 || p.ny < 1 || p.nz < 1) {
    std::ostringstream m;
    m << "LbmParameters.nx = " << p.nx << ", ny = " << p.ny << ", nz = " << p.nz
      << ": each must be >= 1";
    throw std::invalid_argument(m.str());
  }
  if (D == 2) {
    if (p.nz != 1) {
      throw std::invalid_argument("LbmParameters.nz = " + std::to_string(p.nz) +
                                  ": a D2Q9 lattice has nz = 1");
    }
    const LbmParameters defaults;
    if (p.s_pi != defaults.s_pi || p.s_m != defaults.s_m) {
      throw std::invalid_argument(
          "LbmParameters.s_pi / s_m set for a D2Q9 lattice, which has no pi or m moments "
          "(D3Q19 only)");
    }
    // kAuto streams in place (1.5-2x the two-lattice kernel at 129^2..1281^2, docs/lbm.md)
    // unless streaming stores are asked for: they belong to the two-lattice kernel.
    if (p.pattern == StreamingPattern::kInPlace && p.stores == PopulationStores::kStreaming) {
      throw std::invalid_argument(
          "LbmParameters.stores = kStreaming needs pattern = kTwoLattice or kAuto for D2Q9 (the "
          "in-place kernel writes through the cache)");
    }
    in_place_ = p.pattern == StreamingPattern::kInPlace ||
                (p.pattern == StreamingPattern::kAuto && p.stores != PopulationStores::kStreaming);
  } else {
    CheckRate("s_pi", p.s_pi);
    CheckRate("s_m", p.s_m);
    in_place_ = p.pattern != StreamingPattern::kTwoLattice;
    if (p.stores == PopulationStores::kStreaming) {
      throw std::invalid_argument(
          "LbmParameters.stores = kStreaming is implemented for D2Q9 only (D3Q19 writes through "
          "the cache)");
    }
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
  n_ = static_cast<std::size_t>(p.nx) * static_cast<std::size_t>(p.ny) *
       static_cast<std::size_t>(p.nz);
  // The streams f[q * stride_ + node] start 40 doubles (5 cache lines) apart modulo a 4 KiB
  // page: with a stride of a multiple of 4 KiB (64^3, 128^3 nodes) the 19 streams of one node
  // would fall into the same L1 sets and alias the loads with the stores of the opposite slot.
  constexpr std::size_t kPage = 512, kOffset = 40;  // doubles
  stride_ = n_ + (kOffset + kPage - n_ % kPage) % kPage;
  buffers_[0].assign(L::kQ * stride_, 0.0);
  if (!in_place_) buffers_[1].assign(L::kQ * stride_, 0.0);
  for (auto& f : force_) f.assign(n_, 0.0);
  rho_.assign(n_, 1.0);
  for (auto& u : u_) u.assign(n_, 0.0);
  InitializeAtRest();
}

template <class L>
typename LatticeBoltzmann<L>::GridType LatticeBoltzmann<L>::grid() const {
  if constexpr (L::kDimension == 2) {
    return Grid2D{params_.nx, params_.ny, 1.0, -0.5 * params_.nx, -0.5 * params_.ny};
  } else {
    return Grid3D{params_.nx,        params_.ny,        params_.nz,       1.0,
                  -0.5 * params_.nx, -0.5 * params_.ny, -0.5 * params_.nz};
  }
}

template <class L>
bool LatticeBoltzmann<L>::periodic(int axis) const {
  if (axis == 1) return params_.boundary == FluidBoundary::kPeriodic;
  return params_.boundary != FluidBoundary::kClosedBox;
}

template <class L>
void LatticeBoltzmann<L>::CheckNodeField(const std::vector<double>& v, const char* name) const {
  if (v.size() != n_) {
    std::ostringstream m;
    m << name << " has " << v.size() << " values; expected " << n_ << " (one per node)";
    throw std::invalid_argument(m.str());
  }
}

template <class L>
void LatticeBoltzmann<L>::InitializeAtRest() {
  VelocityField u;
  for (auto& c : u) c.assign(n_, 0.0);
  InitializeState(std::vector<double>(n_, 1.0), u);
}

template <class L>
void LatticeBoltzmann<L>::InitializeShear(double shear_rate) {
  const GridType g = grid();
  VelocityField u;
  for (auto& c : u) c.assign(n_, 0.0);
  const std::size_t row = static_cast<std::size_t>(g.nx);
  for (std::size_t node = 0; node < n_; ++node) {
    u[0][node] = shear_rate * g.y(static_cast<int>((node / row) % g.ny));
  }
  if (params_.boundary != FluidBoundary::kPeriodic) {
    SetWallVelocities(shear_rate * g.y0, shear_rate * g.y_max());
  }
  InitializeState(std::vector<double>(n_, 1.0), u);
}

template <class L>
void LatticeBoltzmann<L>::InitializeVelocity(const VelocityField& u) {
  InitializeState(std::vector<double>(n_, 1.0), u);
}

template <class L>
void LatticeBoltzmann<L>::InitializeState(const std::vector<double>& rho, const VelocityField& u) {
  constexpr int D = L::kDimension, Q = L::kQ;
  CheckNodeField(rho, "rho");
  for (int a = 0; a < D; ++a) CheckNodeField(u[a], "initial velocity component");
  const int extent[3] = {params_.nx, params_.ny, params_.nz};
  const std::size_t stride[3] = {1, static_cast<std::size_t>(params_.nx),
                                 static_cast<std::size_t>(params_.nx) * params_.ny};
  // Central differences; periodic wrap or one-sided differences at walls.
  auto derivative = [&](const std::vector<double>& v, std::size_t node, const int* coord,
                        int axis) {
    const int n_dir = extent[axis];
    const int k = coord[axis];
    if (n_dir < 2) return 0.0;
    const std::size_t base = node - static_cast<std::size_t>(k) * stride[axis];
    auto at = [&](int kk) { return v[base + static_cast<std::size_t>(kk) * stride[axis]]; };
    if (periodic(axis)) return 0.5 * (at((k + 1) % n_dir) - at((k - 1 + n_dir) % n_dir));
    if (k == 0) return at(1) - at(0);
    if (k == n_dir - 1) return at(k) - at(k - 1);
    return 0.5 * (at(k + 1) - at(k - 1));
  };
  const double s_nu_uniform = ShearRate(params_.viscosity);
  std::vector<double>& f = current();
  for (std::size_t node = 0; node < n_; ++node) {
    const int coord[3] = {static_cast<int>(node % extent[0]),
                          static_cast<int>((node / stride[1]) % extent[1]),
                          static_cast<int>(node / stride[2])};
    double v[D], u2 = 0.0;
    const double r = rho[node];
    bool finite = std::isfinite(r);
    for (int a = 0; a < D; ++a) {
      v[a] = u[a][node];
      finite = finite && std::isfinite(v[a]);
    }
    if (!finite) throw std::invalid_argument("initial rho and velocity must be finite");
    for (int a = 0; a < D; ++a) u2 += v[a] * v[a];
    const double s_nu = variable_viscosity_ ? s_nu_field_[node] : s_nu_uniform;
    double grad[D][D];  // grad[a][b] = du_b / dx_a
    for (int a = 0; a < D; ++a)
      for (int b = 0; b < D; ++b) grad[a][b] = derivative(u[b], node, coord, a);
    double stress[L::kStressCount];
    NonEquilibriumStress(grad, s_nu, stress);
    for (int q = 0; q < Q; ++q) {
      double cu = 0.0;
      for (int a = 0; a < D; ++a) cu += L::kC[q][a] * v[a];
      const double feq = L::kWeight[q] * (r + 3.0 * cu + 4.5 * cu * cu - 1.5 * u2);
      double fneq = 0.0;
      for (int s = 0; s < L::kStressCount; ++s) {
        const int k = L::kStressMoment[s];
        fneq += L::kMomentMatrix[k][q] * stress[s] / L::kMomentNorm[k];
      }
      f[q * stride_ + node] = feq + fneq;
    }
  }
  CollideInPlaceWithoutForce();
  if (in_place_) StoreCanonicalInPlace();
  step_ = 0;
}

template <class L>
void LatticeBoltzmann<L>::StoreCanonicalInPlace() {
  // Slot opp(i) of each node takes f*_i: swap the pairs (i, opp(i)).
  std::vector<double>& f = current();
  for (int q = 0; q < L::kQ; ++q) {
    const int o = L::kOpposite[q];
    if (o <= q) continue;
    for (std::size_t node = 0; node < n_; ++node) {
      std::swap(f[q * stride_ + node], f[o * stride_ + node]);
    }
  }
  next_odd_ = true;
}

template <class L>
const std::vector<double>& LatticeBoltzmann<L>::populations() const {
  const std::vector<double>& f = current();
  canonical_.resize(L::kQ * n_);
  if (!in_place_ || next_odd_) {
    // Two lattices: f*_i(x) in slot i of x; in place after an even step (or a start): in slot
    // opp(i) of x. Either way one stream per direction, without the padding.
    for (int q = 0; q < L::kQ; ++q) {
      const std::size_t from = static_cast<std::size_t>(in_place_ ? L::kOpposite[q] : q) * stride_;
      std::copy(f.begin() + from, f.begin() + from + n_, canonical_.begin() + q * n_);
    }
    return canonical_;
  }
  // After an odd step: f*_i(x) is in slot i of x + c_i, or in slot opp(i) of x where x + c_i
  // lies beyond a wall.
  const int extent[3] = {params_.nx, params_.ny, params_.nz};
  const std::size_t stride[3] = {1, static_cast<std::size_t>(params_.nx),
                                 static_cast<std::size_t>(params_.nx) * params_.ny};
  for (std::size_t node = 0; node < n_; ++node) {
    const int coord[3] = {static_cast<int>(node % extent[0]),
                          static_cast<int>((node / stride[1]) % extent[1]),
                          static_cast<int>(node / stride[2])};
    for (int q = 0; q < L::kQ; ++q) {
      std::size_t to = 0;
      bool wall = false;
      for (int a = 0; a < L::kDimension && !wall; ++a) {
        int c = coord[a] + L::kC[q][a];
        if (c < 0 || c >= extent[a]) {
          if (!periodic(a)) {
            wall = true;
            break;
          }
          c = (c + extent[a]) % extent[a];
        }
        to += static_cast<std::size_t>(c) * stride[a];
      }
      canonical_[q * n_ + node] =
          wall ? f[static_cast<std::size_t>(L::kOpposite[q]) * stride_ + node]
               : f[q * stride_ + to];
    }
  }
  return canonical_;
}

template <class L>
void LatticeBoltzmann<L>::CollideInPlaceWithoutForce() {
  constexpr int D = L::kDimension, Q = L::kQ;
  std::vector<double>& f = current();
  const MrtRates rates{params_.s_e, params_.s_epsilon, params_.s_q, params_.s_pi, params_.s_m};
  const double s_nu_uniform = ShearRate(params_.viscosity);
  const double zero_force[D] = {};
  for (std::size_t node = 0; node < n_; ++node) {
    double p[Q];
    for (int q = 0; q < Q; ++q) p[q] = f[q * stride_ + node];
    const double s_nu = variable_viscosity_ ? s_nu_field_[node] : s_nu_uniform;
    double u[D];
    CollideNode<L>(p, zero_force, s_nu, rates, params_.forcing, rho_[node], u);
    for (int a = 0; a < D; ++a) u_[a][node] = u[a];
    for (int q = 0; q < Q; ++q) f[q * stride_ + node] = p[q];
  }
}

template <class L>
void LatticeBoltzmann<L>::ClearForce() {
  for (auto& f : force_) std::fill(f.begin(), f.end(), 0.0);
}

template <class L>
void LatticeBoltzmann<L>::SetViscosityField(const std::vector<double>& nu) {
  CheckNodeField(nu, "viscosity field");
  s_nu_field_.resize(n_);
  for (std::size_t node = 0; node < n_; ++node) SetNodeViscosity(nu, node);
  variable_viscosity_ = true;
}

template <class L>
void LatticeBoltzmann<L>::UpdateViscosityField(const std::vector<double>& nu,
                                               const std::vector<std::size_t>& nodes) {
  if (!variable_viscosity_) {
    throw std::logic_error("UpdateViscosityField: call SetViscosityField first");
  }
  CheckNodeField(nu, "viscosity field");
  for (const std::size_t node : nodes) SetNodeViscosity(nu, node);
}

template <class L>
void LatticeBoltzmann<L>::SetNodeViscosity(const std::vector<double>& nu, std::size_t node) {
  if (!(std::isfinite(nu[node]) && nu[node] > 0.0)) {
    CheckViscosity(("viscosity field[" + std::to_string(node) + "]").c_str(), nu[node]);
  }
  s_nu_field_[node] = ShearRate(nu[node]);
}

template <class L>
void LatticeBoltzmann<L>::ClearViscosityField() {
  variable_viscosity_ = false;
  s_nu_field_.clear();
}

template <class L>
void LatticeBoltzmann<L>::SetWallVelocities(double bottom, double top) {
  if (!std::isfinite(bottom) || !std::isfinite(top)) {
    throw std::invalid_argument("SetWallVelocities: wall velocities must be finite");
  }
  params_.wall_velocity_bottom = bottom;
  params_.wall_velocity_top = top;
}

template <class L>
void LatticeBoltzmann<L>::Step() {
  StreamCollide();
  if (in_place_) {
    next_odd_ = !next_odd_;
  } else {
    current_index_ = 1 - current_index_;
  }
  ++step_;
}

template <class L>
void LatticeBoltzmann<L>::StreamCollide() {
  lbm_kernels::StreamCollideArgs a;
  a.src = current().data();
  a.dst = in_place_ ? current().data() : next().data();
  a.nx = params_.nx;
  a.ny = params_.ny;
  a.nz = params_.nz;
  a.stream_stride = stride_;
  for (int d = 0; d < L::kDimension; ++d) {
    a.force[d] = force_[d].data();
    a.u[d] = u_[d].data();
  }
  a.s_nu_field = variable_viscosity_ ? s_nu_field_.data() : nullptr;
  a.s_nu_uniform = ShearRate(params_.viscosity);
  a.rates = MrtRates{params_.s_e, params_.s_epsilon, params_.s_q, params_.s_pi, params_.s_m};
  a.periodic_y = params_.boundary == FluidBoundary::kPeriodic;
  a.side_walls = params_.boundary == FluidBoundary::kClosedBox;
  a.wall_u_bottom = params_.wall_velocity_bottom;
  a.wall_u_top = params_.wall_velocity_top;
  a.rho = rho_.data();
  a.forcing = params_.forcing;
  // Small grids run on one thread: on a shared, oversubscribed machine the fork/join of a
  // parallel region costs more than the work below ~128^2 nodes.
  constexpr std::size_t kMinNodesPerThread = 8192;
  int threads = params_.threads > 0 ? params_.threads : omp_get_max_threads();
  threads = std::max(1, std::min<int>(threads, static_cast<int>(n_ / kMinNodesPerThread)));
  a.threads = threads;
  if constexpr (L::kDimension == 2) {
    // Streaming stores are opt-in: on the 2-core development machine (shared, loaded) they did
    // not measurably beat cached stores even at 1281^2 (docs/lbm.md), so kAuto keeps cached.
    if (params_.stores == PopulationStores::kStreaming && !in_place_) {
      const std::size_t per_thread = lbm_kernels::kD2Q9ScratchDoublesPerThread;
      const std::size_t needed = per_thread * static_cast<std::size_t>(threads) + 8;
      if (stream_scratch_.size() < needed) stream_scratch_.assign(needed, 0.0);  // first step
      const std::uintptr_t base = reinterpret_cast<std::uintptr_t>(stream_scratch_.data());
      a.scratch = stream_scratch_.data() + ((64 - base % 64) % 64) / sizeof(double);
    }
    if (in_place_) {
      lbm_kernels::StreamCollideD2Q9InPlace(a, next_odd_);
    } else {
      lbm_kernels::StreamCollideD2Q9(a);
    }
  } else if (in_place_) {
    lbm_kernels::StreamCollideD3Q19InPlace(a, next_odd_);
  } else {
    lbm_kernels::StreamCollideD3Q19(a);
  }
}

template <class L>
double LatticeBoltzmann<L>::MaxSpeed() const {
  double max2 = 0.0;
  for (std::size_t k = 0; k < n_; ++k) {
    double s2 = 0.0;
    for (int a = 0; a < L::kDimension; ++a) s2 += u_[a][k] * u_[a][k];
    max2 = std::max(max2, s2);
  }
  return std::sqrt(max2);
}

template <class L>
bool LatticeBoltzmann<L>::AllFinite() const {
  for (double v : current()) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

template <class L>
void LatticeBoltzmann<L>::SetPopulations(const std::vector<double>& f) {
  constexpr int D = L::kDimension, Q = L::kQ;
  if (f.size() != Q * n_) {
    std::ostringstream m;
    m << "SetPopulations: " << f.size() << " values; expected " << Q << " * " << n_ << " = "
      << Q * n_;
    throw std::invalid_argument(m.str());
  }
  std::vector<double>& stored = current();
  for (int q = 0; q < Q; ++q) {
    std::copy(f.begin() + q * n_, f.begin() + (q + 1) * n_, stored.begin() + q * stride_);
  }
  if (in_place_) StoreCanonicalInPlace();
  for (std::size_t node = 0; node < n_; ++node) {
    double r = 0.0, j[D] = {};
    for (int q = 0; q < Q; ++q) {
      const double v = f[q * n_ + node];
      r += v;
      for (int a = 0; a < D; ++a) j[a] += L::kC[q][a] * v;
    }
    rho_[node] = r;
    for (int a = 0; a < D; ++a) u_[a][node] = j[a] - 0.5 * force_[a][node];
  }
}

template class LatticeBoltzmann<D2Q9>;
template class LatticeBoltzmann<D3Q19>;

}  // namespace ehd
