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
#pragma once

#include <cmath>
#include <string>

#include "ehd_capsule/ib/cosine_delta.h"

namespace ehd {

enum class DeltaKernel { kCosine4, kRoma3 };

// "cosine" | "roma3" (the scene key numerics.ib_kernel); throws std::invalid_argument otherwise.
DeltaKernel ParseDeltaKernel(const std::string& name);

// phi(r) for r = distance / h.
double DeltaKernelValue(DeltaKernel kernel, double r_over_h);

// Fourier transform of the roma3 phi at xi = k h, int phi(r) cos(xi r) dr (1 at xi = 0): its
// damping of a membrane mode k, for the membrane's explicit stability limit
// (membrane/membrane_stability.h, where the cosine kernel's closed form is).
double Roma3DeltaTransform(double xi);

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

}  // namespace ehd
