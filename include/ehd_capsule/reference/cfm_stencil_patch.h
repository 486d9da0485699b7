// Integration region Omega_Sigma^ij of the correction function method, song2019 sec. 2.3.2
// (Marques, Nave & Petitpas 2011, sec. 3.3), and the interface quadrature on Sigma cap patch.
//
// For the 5-point stencil centred at x_ij whose arms cross Sigma:
//  1. Sigma_ij = the piece of Sigma inside the stencil's diamond |x - x_i| + |y - y_j| <= h
//     (the "dashed square box connecting the four neighbours"), found from a crossing of an arm.
//  2. theta_Sigma = angle of the tangent at the middle of Sigma_ij; the (p, q) frame is the
//     (x, y) frame rotated by theta_r = theta_Sigma - pi/4, so Sigma runs along the patch diagonal.
//  3. The patch is the smallest (p, q)-aligned rectangle holding Sigma_ij and every node where D
//     is needed (Fig. 4a-c).
// Departure from the text (a safeguard it does not state): each half side is at least a quarter
// of the longer one, so that a stencil barely clipped by Sigma does not give a sliver patch on
// which the Cauchy continuation is ill-conditioned.
// The interface quadrature then covers the whole of Sigma cap patch (which may be longer than
// Sigma_ij), with 4-point Gauss-Legendre rules on equal sub-intervals of the curve parameter.
#pragma once

#include <Eigen/Core>

#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/reference/cfm_local_cauchy.h"

namespace ehd {

struct CfmStencilPatch {
  CfmPatch patch;
  double s_begin = 0.0;  // curve parameters bounding Sigma cap patch (s_end > s_begin, may
  double s_end = 0.0;    // exceed the period; At() wraps)
  double s_hint = 0.0;   // a parameter on the piece, for local closest-point searches
};

// Parameter of the point of `curve` closest to p by Newton's method from s_hint (local search:
// p must be within a few marker spacings of X(s_hint)).
double CfmLocalClosestParameter(const ClosedCurve& curve, const Eigen::Vector2d& p, double s_hint);

// Builds the patch for the stencil centred at `center` (grid spacing h). far_nodes are the
// n_far (1..4) neighbours on the other side of Sigma, where D is needed; s_hint is a curve
// parameter near the stencil (e.g. ClosestParameter(center)). Returns false if no crossing of
// Sigma is found along the arms (inconsistent side flags).
bool BuildCfmStencilPatch(const ClosedCurve& curve, const Eigen::Vector2d& center, double h,
                          const Eigen::Vector2d* far_nodes, int n_far, double s_hint,
                          CfmStencilPatch* out);

// Gauss quadrature of Sigma cap patch: n_sub sub-intervals x 4 points (n_sub * 4 <=
// CfmLocalCauchy::kMaxInterfaceSamples). Fills positions, normals and arc-length weights only;
// the caller sets the jump data. Returns the number of samples written.
int CfmInterfaceQuadrature(const ClosedCurve& curve, const CfmStencilPatch& stencil_patch,
                           int n_sub, CfmInterfaceSample* samples, double* sample_parameters);

}  // namespace ehd
