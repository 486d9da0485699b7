// MRT lattice Boltzmann fluid with body force (song2019 sections 3.1 and 3.2, eqs. (97)-(101),
// (107)-(108)), written once over a lattice descriptor (lattice_descriptors.h): D2Q9 on a
// Grid2D {nx, ny, h = 1, x0 = -nx/2, y0 = -ny/2}, D3Q19 on a Grid3D with z0 = -nz/2 as well.
//
// One Step() is a fused pull stream + collide:
//   f_i(x, t) = f*_i(x - c_i, t - 1)       (stream; boundaries replace links that leave the box)
//   f*(x, t)  = MRT collision of f(x, t) with the force F(x) in force(a)
// and writes rho(x, t), u(x, t) = j + F/2 (rho_0 = 1, incompressible equilibria of the reference)
// at the same time level. So after the n-th Step, populations() holds the post-collision f* of
// step n and velocity(a) the velocity of step n consistent with the force that was applied: the
// velocity an immersed-boundary coupling interpolates to move its markers (song2019 section 3.6).
// The stream-collide kernel is specialised per lattice (stream_collide.cpp for D2Q9,
// stream_collide_d3q19.cpp for D3Q19); everything around it is common.
//
// Boundaries: x (and z in 3D) are periodic unless kClosedBox. In y:
//   kPeriodic   periodic;
//   kShearWalls half-way bounce-back walls on the faces y = -ny/2 (bottom) and y = +ny/2 (top)
//               moving in x:  f_i(x) = f*_opp(i)(x) + 6 w_i rho_0 c_i.u_wall  (= f_opp - 2 w rho
//               c_opp.u_w / c_s^2);
//   kClosedBox  the same walls at y = +-ny/2 and resting walls on the other faces (a closed box;
//               the y walls still move if wall velocities are set, e.g. a lid-driven cavity).
#pragma once

#include <array>
#include <vector>

#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/lbm/lattice_descriptors.h"
#include "ehd_capsule/lbm/mrt_collision.h"

namespace ehd {

enum class FluidBoundary { kPeriodic, kShearWalls, kClosedBox };

// How the kernel writes the new populations: through the cache, or with non-temporal (streaming)
// stores that skip the read-for-ownership of lines that will not be reused before they leave the
// cache (large grids). kAuto currently means kCached (streaming was not measurably faster here).
// D2Q9 only (D3Q19 writes through the cache).
enum class PopulationStores { kAuto, kCached, kStreaming };

// How the populations stream: two arrays (read one, write the other), or in place on one array
// (the AA pattern: half the population memory, no write-allocate traffic). kAuto: in place for
// both lattices (measured faster, docs/lbm.md), except D2Q9 with PopulationStores::kStreaming,
// which streams with two arrays (kInPlace with kStreaming is refused). Results are identical
// either way.
enum class StreamingPattern { kAuto, kTwoLattice, kInPlace };

struct LbmParameters {
  int nx = 0, ny = 0;
  int nz = 1;                    // D3Q19 only (D2Q9 requires 1)
  double viscosity = 1.0 / 6.0;  // lattice kinematic viscosity nu (tau = 3 nu + 1/2 > 1/2)
  FluidBoundary boundary = FluidBoundary::kShearWalls;
  double wall_velocity_bottom = 0, wall_velocity_top = 0;  // x-velocity of the y walls
  // Non-hydrodynamic relaxation rates, each in (0, 2). Reference numbering (song2019 3.1.1):
  double s_e = 1.64;        // s_1, energy e (bulk viscosity); not given in the reference, value of
                            // Lallemand & Luo (2000)
  double s_epsilon = 1.54;  // s_2, energy square epsilon (reference value)
  double s_q = 1.9;         // s_4 = s_6, heat fluxes q_x, q_y (reference value)
  double s_pi = 1.8;        // D3Q19 only: 3pi_xx, pi_ww (reference sec. 3.1.2: 1.8)
  double s_m = 1.8;         // D3Q19 only: m_x, m_y, m_z (reference sec. 3.1.2: 1.8)
  ForcingScheme forcing = ForcingScheme::kSplitMomentum;  // reference eqs. (107)-(108)
  int threads = 0;  // 0: OpenMP default; capped so that each thread gets >= 8192 nodes
  PopulationStores stores = PopulationStores::kAuto;   // a speed choice; results identical
  StreamingPattern pattern = StreamingPattern::kAuto;  // a speed choice; results identical
};

template <class L>
class LatticeBoltzmann {
 public:
  static constexpr int kDimension = L::kDimension;
  static constexpr int kQ = L::kQ;
  using Lattice = L;
  using GridType = Grid<L::kDimension>;
  using VelocityField = std::array<std::vector<double>, L::kDimension>;

  // Validates the parameters (throws std::invalid_argument naming parameter, value and range).
  explicit LatticeBoltzmann(const LbmParameters& p);

  GridType grid() const;
  const LbmParameters& parameters() const { return params_; }
  std::size_t nodes() const { return n_; }

  // All initialisers set step() = 0 and store the post-collision state (zero force) of a node
  // distribution f = f^eq + f^neq whose non-equilibrium stress matches the velocity gradient
  // (Chapman-Enskog: Pi^neq = -(rho/(3 s_nu)) (grad u + grad u^T), projected on the lattice's
  // stress moments), so a smooth flow starts without an initial layer.
  void InitializeAtRest();  // rho = 1, u = 0
  // u = (k y, 0[, 0]), rho = 1; with kShearWalls or kClosedBox also sets the wall velocities to
  // -k ny/2 (bottom) and +k ny/2 (top) so that the shear is held.
  void InitializeShear(double shear_rate);
  void InitializeVelocity(const VelocityField& u);
  void InitializeState(const std::vector<double>& rho, const VelocityField& u);

  // Body-force density per node (lattice units); the caller fills them before Step. Step does
  // not clear them.
  std::vector<double>& force(int axis) { return force_[axis]; }
  const std::vector<double>& force(int axis) const { return force_[axis]; }
  std::vector<double>& force_x() { return force_[0]; }
  std::vector<double>& force_y() { return force_[1]; }
  const std::vector<double>& force_x() const { return force_[0]; }
  const std::vector<double>& force_y() const { return force_[1]; }
  void ClearForce();

  // Per-node kinematic viscosity (viscosity contrast); each value finite and > 0 (tau > 1/2).
  void SetViscosityField(const std::vector<double>& nu);
  // Re-reads nu only at the listed nodes (a moving interface changes a band of the field); needs
  // a field set before. Same validation as SetViscosityField.
  void UpdateViscosityField(const std::vector<double>& nu, const std::vector<std::size_t>& nodes);
  void ClearViscosityField();  // back to the uniform parameters().viscosity
  bool has_viscosity_field() const { return variable_viscosity_; }

  void SetWallVelocities(double bottom, double top);  // takes effect at the next Step

  void Step();  // stream + collide (with forcing) + boundaries; updates rho and u

  const std::vector<double>& rho() const { return rho_; }
  const std::vector<double>& velocity(int axis) const { return u_[axis]; }
  const std::vector<double>& ux() const { return u_[0]; }
  const std::vector<double>& uy() const { return u_[1]; }
  double MaxSpeed() const;  // max |u|
  bool AllFinite() const;   // every population finite

  // Checkpoint/restart: the post-collision populations, layout f[q * nodes + node]
  // (q = velocity index of the descriptor, node = grid index). SetPopulations recomputes rho and
  // u = j* - F/2 (j* = j + F of the stored f*) with the current force arrays; Step continues
  // bit-for-bit. SetStep restores the step counter.
  const std::vector<double>& populations() const;
  bool in_place() const { return in_place_; }
  void SetPopulations(const std::vector<double>& f);
  void SetStep(long step) { step_ = step; }
  long step() const { return step_; }

  // Which axes wrap (from the boundary kind).
  bool periodic(int axis) const;

 private:
  void SetNodeViscosity(const std::vector<double>& nu, std::size_t node);
  void CheckNodeField(const std::vector<double>& v, const char* name) const;
  void CollideInPlaceWithoutForce();
  void StreamCollide();  // the lattice's own kernel
  // In-place streaming: the stored layout after an even step (each node's f*_i in its slot
  // opp(i)) from canonical post-collision populations in current(), and back.
  void StoreCanonicalInPlace();

  LbmParameters params_;
  std::size_t n_ = 0;
  std::size_t stride_ = 0;  // of the population streams in buffers_ (n_ padded)
  // Two population buffers; the index (not a pointer) keeps the class copyable and movable.
  std::vector<double>& current() { return buffers_[current_index_]; }
  const std::vector<double>& current() const { return buffers_[current_index_]; }
  std::vector<double>& next() { return buffers_[1 - current_index_]; }

  std::vector<double> buffers_[2];
  int current_index_ = 0;  // buffers_[current_index_] holds the post-collision f* of the last step
  std::array<std::vector<double>, L::kDimension> force_;
  std::vector<double> s_nu_field_;  // per-node shear rate, used when variable_viscosity_
  bool variable_viscosity_ = false;
  std::vector<double> rho_;
  std::array<std::vector<double>, L::kDimension> u_;
  std::vector<double> stream_scratch_;  // per-thread blocks for streaming stores (made once)
  long step_ = 0;
  bool in_place_ = false;
  bool next_odd_ = true;  // in place: the next step is an odd one (the last was even, or a start)
  mutable std::vector<double> canonical_;  // populations() without the padding, on demand
};

extern template class LatticeBoltzmann<D2Q9>;
extern template class LatticeBoltzmann<D3Q19>;
using LatticeBoltzmann2D = LatticeBoltzmann<D2Q9>;
using LatticeBoltzmann3D = LatticeBoltzmann<D3Q19>;

}  // namespace ehd
