// Finite differences along the arc length of a closed marker curve with non-uniform spacing.
//
// song2019 sec. 3.3 (after eq. (110)): "first and second derivatives with respect to arc length
// are computed by five-point centred difference methods for arbitrarily spaced stencil". The
// weights are those of the Lagrange interpolant through the stencil nodes, computed by
// Fornberg's recursion (Math. Comp. 51 (1988) 699):
//   marker data g_k (curvature, q) -> marker derivatives, nodes l_{k-2..k+2}:
//     dg/dl: 4th order, d2g/dl2: 3rd order (4th on uniform spacing);
//   segment data tau_{k+1/2} (tension, constant on a segment) -> marker values and derivatives,
//   nodes at the four nearest segment midpoints (staggered, 4th / 3rd order).
// Departure from the text: tensions live on segments (one stretch per segment, eq. (112)), and
// averaging them to markers before a centred 5-point difference would hide the alternating
// ("zig-zag") segment-stretch mode from the force; the staggered stencil sees it.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace ehd {

// Weights w[d * n + j] of the d-th derivative (d = 0..max_order) at z from values at nodes
// x[0..n-1] (distinct). Fornberg's algorithm.
void FiniteDifferenceWeights(double z, const double* x, int n, int max_order, double* w);

// Stencils for one curve, rebuilt (without allocation once sized) from its segment lengths.
class ArcLengthStencil {
 public:
  // segment_length[k] = arc length from marker k to marker k+1 (periodic). At least 5 segments.
  void Build(const std::vector<double>& segment_length);
  int size() const { return size_; }

  // Centred 5-point derivatives of marker values g (size M).
  double MarkerFirst(const std::vector<double>& g, int k) const;
  double MarkerSecond(const std::vector<double>& g, int k) const;
  // Marker value and derivative of segment values s (size M; s[k] on segment k -> k+1).
  double SegmentToMarker(const std::vector<double>& s, int k) const;
  double SegmentDerivativeAtMarker(const std::vector<double>& s, int k) const;

 private:
  int size_ = 0;
  // 5 weights per marker for d/dl and d2/dl2; 4 for staggered value and d/dl.
  std::vector<double> d1_, d2_, s0_, s1_;
};

}  // namespace ehd
