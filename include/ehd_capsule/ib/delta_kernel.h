// The discrete delta kernels of the immersed boundary method, and the choice between them.
//
// cosine (song2019 eq. (103), cosine_delta.h): phi(r) = (1/4) [1 + cos(pi r / 2)], |r| <= 2,
//   4 nodes per axis. The reference's kernel.
// roma3 (Roma, Peskin & Berger, J. Comput. Phys. 153 (1999) 509, eq. (A.1); not in song2019):
//   phi(r) = (1 + sqrt(1 - 3 r^2)) / 3                       |r| <= 1/2
//          = (5 - 3 |r| - sqrt(1 - 3 (1 - |r|)^2)) / 6      1/2 <= |r| <= 3/2,
//   3 nodes per axis. It satisfies sum_j phi(r - j) = 1, sum_j (r - j) phi(r - j) = 0 (linear
//   fields interpolated exactly, which the cosine kernel does not) and sum_j phi(r - j)^2 = 1/2
//   for every r. Its support is 3 h wide in place of 4 h, so a membrane's force and velocity are
//   smeared over less of the fluid: a capsule thinned by large strain is less stiff on a coarse
//   grid (docs/validation_3d.md, "The kernel"), and a step costs 27 in place of 64 nodes per
//   point in 3D.
// trapezoid3 (the 3-node kernel with the even-odd condition; docs/validation_3d.md, "Damping the
//   grid-Nyquist mode"):
//   phi(r) = 1/2                   |r| <= 1/2
//          = 3/4 - |r| / 2         1/2 <= |r| <= 3/2,
//   3 nodes per axis, the box of width h convolved with the box of width 2 h. It keeps roma3's
//   sum_j phi(r - j) = 1 and sum_j (r - j) phi(r - j) = 0 and replaces sum_j phi^2 = 1/2 by
//   Peskin's even-odd condition sum_{j even} phi(r - j) = sum_{j odd} phi(r - j) = 1/2 (the
//   only 3-node kernel with all three): a force or velocity alternating node by node has no
//   part in it (T_pi = 0, as cosine), so it does not drive the lattice's undamped k h = pi
//   momentum mode that roma3 does. phi_hat(xi) = sinc(xi / 2) sinc(xi).
// roma3_even_odd: per velocity (and force) component d, trapezoid3 along axis d and roma3 along
//   the other axes. The lattice's undamped mode at the grid's Nyquist is longitudinal (u_d
//   alternating along axis d); this kernel does not couple to it, and keeps roma3 across a
//   membrane for the tangential components, whose kink the narrow kernel resolves.
#pragma once

#include <cmath>
#include <string>

#include "ehd_capsule/ib/cosine_delta.h"

namespace ehd {

enum class DeltaKernel { kCosine4, kRoma3, kTrapezoid3, kRoma3EvenOdd };

// "cosine" | "roma3" | "trapezoid3" | "roma3_even_odd" (the scene key numerics.ib_kernel);
// throws std::invalid_argument otherwise.
DeltaKernel ParseDeltaKernel(const std::string& name);

// phi(r) for r = distance / h (roma3_even_odd: roma3's, its kernel across each component's axis).
double DeltaKernelValue(DeltaKernel kernel, double r_over_h);

// Fourier transform of the roma3 phi at xi = k h, int phi(r) cos(xi r) dr (1 at xi = 0): its
// damping of a membrane mode k, for the membrane's explicit stability limit
// (membrane/membrane_stability.h, where the cosine kernel's closed form is).
double Roma3DeltaTransform(double xi);

// Fourier transform of the trapezoid3 phi at xi = k h: sinc(xi / 2) sinc(xi), sinc(x) = sin x / x.
double Trapezoid3DeltaTransform(double xi);

// Weights of the three nodes in the roma3 support of a point at fractional node coordinate xi
// (node i at xi = i): nodes n - 1, n, n + 1 with n the nearest node, d = xi - n in [-1/2, 1/2],
//   w(n) = (1 + s) / 3,  w(n -+ 1) = (2 -+ 3 d - s) / 6,  s = sqrt(1 - 3 d^2)
// (one square root per axis). weight[3] stays 0.
inline DeltaStencil Roma3DeltaStencil(double xi) {
  const double nearest = std::floor(xi + 0.5);
  const double d = xi - nearest;
  const double s = std::sqrt(1.0 - 3.0 * d * d);
  DeltaStencil st;
  st.first = static_cast<int>(nearest) - 1;
  st.weight[0] = (2.0 - 3.0 * d - s) / 6.0;
  st.weight[1] = (1.0 + s) / 3.0;
  st.weight[2] = (2.0 + 3.0 * d - s) / 6.0;
  return st;
}

// Weights of the three nodes in the trapezoid3 support (nodes n - 1, n, n + 1, n the nearest
// node, d = xi - n in [-1/2, 1/2]): w(n) = 1/2, w(n -+ 1) = 1/4 -+ d / 2.
inline DeltaStencil Trapezoid3DeltaStencil(double xi) {
  const double nearest = std::floor(xi + 0.5);
  const double d = xi - nearest;
  DeltaStencil st;
  st.first = static_cast<int>(nearest) - 1;
  st.weight[0] = 0.25 - 0.5 * d;
  st.weight[1] = 0.5;
  st.weight[2] = 0.25 + 0.5 * d;
  return st;
}

}  // namespace ehd
