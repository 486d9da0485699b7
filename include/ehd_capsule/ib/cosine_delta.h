// The 4-point cosine discrete delta of the immersed boundary method.
//
// song2019 eq. (103) (typo "pi x pi / 2h" in the text corrected to "pi x / 2h"):
//   delta_h(x) = (1 / 4h) [1 + cos(pi x / 2h)]  for |x| <= 2h,   0 otherwise,
// and in 2D the tensor product delta_h(x) delta_h(y), eq. (102). With r = x / h the kernel is
//   phi(r) = (1/4) [1 + cos(pi r / 2)],   delta_h(x) = phi(x / h) / h.
// Discrete moments over the integer nodes j (any offset r):
//   sum_j phi(r - j) = 1 and sum_{j even} = sum_{j odd} = 1/2   (exact),
//   sum_j phi(r - j)^2 = 3/8                                      (exact, shift-invariant norm),
//   sum_j (r - j) phi(r - j) = d - 1/2 + (cos(pi d/2) - sin(pi d/2)) / 2,  d = frac(r),
// i.e. the first moment is NOT zero (|.| <= 0.0211 h, zero only for d = 0 or 1/2): unlike
// Peskin's 4-point kernel, the cosine kernel does not interpolate linear fields exactly.
#pragma once

#include <cmath>

namespace ehd {

// phi(r) for r = distance / h; the 1D delta is CosineDelta(x / h) / h.
double CosineDelta(double r_over_h);

// Weights of the four nodes in the support of a point at fractional node coordinate xi
// (xi = (x - x_node0) / h, so node i sits at xi = i). Nodes first .. first + 3; the node at
// distance exactly 2h has weight 0 and is left out. One sin and one cos per call:
// with d = xi - floor(xi), the four cosines are -sin, cos, sin, -cos of (pi d / 2).
struct DeltaStencil {
  int first = 0;
  double weight[4] = {0.0, 0.0, 0.0, 0.0};
};

inline DeltaStencil CosineDeltaStencil(double xi) {
  constexpr double kHalfPi = 1.5707963267948966;
  const double base = std::floor(xi);
  const double d = xi - base;
  const double c = std::cos(kHalfPi * d);
  const double s = std::sin(kHalfPi * d);
  DeltaStencil st;
  st.first = static_cast<int>(base) - 1;
  st.weight[0] = 0.25 * (1.0 - s);  // r = d + 1
  st.weight[1] = 0.25 * (1.0 + c);  // r = d
  st.weight[2] = 0.25 * (1.0 + s);  // r = d - 1
  st.weight[3] = 0.25 * (1.0 - c);  // r = d - 2
  return st;
}

}  // namespace ehd
