// The per-lattice stream-collide kernels behind LatticeBoltzmann<L> (internal to the lbm
// library): one fused pull stream + MRT collide over plain arrays of one layout
// (f[q * stream_stride + node], node = grid index x-fastest), two buffers (read src, write dst).
#pragma once

#include <cstddef>

#include "ehd_capsule/lbm/mrt_collision.h"

namespace ehd::lbm_kernels {

// v mod period for v in [-period, 2 period): the neighbour coordinates of a link (both kernels).
inline int WrapOnce(int v, int period) {
  return v < 0 ? v + period : (v >= period ? v - period : v);
}

struct StreamCollideArgs {
  const double* src = nullptr;
  double* dst = nullptr;
  int nx = 1, ny = 1, nz = 1;
  // Distance between the population streams, f[q * stream_stride + node]: at least the node
  // count, padded so the streams do not start at the same offset within a 4 KiB page.
  std::size_t stream_stride = 0;
  const double* force[3] = {nullptr, nullptr, nullptr};
  const double* s_nu_field = nullptr;  // per node, or nullptr: s_nu_uniform
  double s_nu_uniform = 1.0;
  MrtRates rates{1.64, 1.54, 1.9};
  bool periodic_y = false;
  bool side_walls = false;  // resting walls on the x (and z) faces
  double wall_u_bottom = 0, wall_u_top = 0;
  double* rho = nullptr;
  double* u[3] = {nullptr, nullptr, nullptr};
  double* scratch = nullptr;  // D2Q9 streaming stores: kScratchDoubles per thread, or nullptr
  ForcingScheme forcing = ForcingScheme::kSplitMomentum;
  int threads = 1;
};

// D2Q9 (stream_collide.cpp): two lattices (src -> dst), or in place on one array (dst; the AA
// pattern, `odd` alternates as for D3Q19). Streaming-store scratch (two lattices only): this many
// doubles per thread.
extern const std::size_t kD2Q9ScratchDoublesPerThread;
void StreamCollideD2Q9(const StreamCollideArgs& a);
void StreamCollideD2Q9InPlace(const StreamCollideArgs& a, bool odd);
// One node's collision with the fast kernel (f: 9 populations in place, force: 2 components).
void CollideNodeD2Q9(double* f, const double* force, double s_nu, const MrtRates& rates,
                     ForcingScheme forcing, double& rho, double* u);

// D3Q19 (stream_collide_d3q19.cpp): two lattices (src -> dst), or in place on one array (dst;
// the AA pattern: `odd` alternates, see the kernel).
void StreamCollideD3Q19(const StreamCollideArgs& a);
void StreamCollideD3Q19InPlace(const StreamCollideArgs& a, bool odd);
void CollideNodeD3Q19(double* f, const double* force, double s_nu, const MrtRates& rates,
                      ForcingScheme forcing, double& rho, double* u);

}  // namespace ehd::lbm_kernels
