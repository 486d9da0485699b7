// Transverse shear tension of a membrane with bending stiffness, song2019 eq. (115):
//   m = E_B (kappa - kappa_0)   (bending moment),   q = dm/dl = E_B d(kappa - kappa_0)/dl,
// with kappa the spline curvature at the markers (eq. (116)) and kappa_0 the curvature of the
// reference (initial) shape at the same marker, so the initial shape carries no bending moment.
// The normal force needs dq/dl = E_B d2(kappa - kappa_0)/dl2, taken with the 5-point second
// derivative stencil (not d/dl twice: the centred first difference applied twice cannot see the
// alternating mode kappa_k ~ (-1)^k, so a marker zig-zag would feel no bending stiffness).
#pragma once

#include <vector>

#include "ehd_capsule/membrane/arc_length_stencil.h"

namespace ehd {

struct BendingTension {
  double bending_modulus = 0.0;  // E_B
  // excess_curvature[k] = kappa_k - kappa_0,k; writes q and dq/dl at every marker, with l along
  // the counter-clockwise tangent (orientation = +1 if the markers run counter-clockwise, else
  // -1: first derivatives along the marker order change sign, second derivatives do not).
  void Compute(const ArcLengthStencil& stencil, const std::vector<double>& excess_curvature,
               int orientation, std::vector<double>& q, std::vector<double>& dq_dl) const {
    for (int k = 0; k < stencil.size(); ++k) {
      q[k] = orientation * bending_modulus * stencil.MarkerFirst(excess_curvature, k);
      dq_dl[k] = bending_modulus * stencil.MarkerSecond(excess_curvature, k);
    }
  }
};

}  // namespace ehd
