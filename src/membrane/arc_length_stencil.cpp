// Non-uniform 5-point (marker) and 4-point staggered (segment) arc-length stencils,
// song2019 sec. 3.3; see arc_length_stencil.h.
#include "ehd_capsule/membrane/arc_length_stencil.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ehd {

void FiniteDifferenceWeights(double z, const double* x, int n, int max_order, double* w) {
  // Fornberg (1988), in-place form: w[d * n + j].
  const int m = max_order;
  std::fill(w, w + (m + 1) * n, 0.0);
  double c1 = 1.0;
  double c4 = x[0] - z;
  w[0] = 1.0;
  for (int i = 1; i < n; ++i) {
    const int mn = std::min(i, m);
    double c2 = 1.0;
    const double c5 = c4;
    c4 = x[i] - z;
    for (int j = 0; j < i; ++j) {
      const double c3 = x[i] - x[j];
      c2 *= c3;
      if (j == i - 1) {
        for (int d = mn; d >= 1; --d) {
          w[d * n + i] = c1 * (d * w[(d - 1) * n + i - 1] - c5 * w[d * n + i - 1]) / c2;
        }
        w[i] = -c1 * c5 * w[i - 1] / c2;
      }
      for (int d = mn; d >= 1; --d) {
        w[d * n + j] = (c4 * w[d * n + j] - d * w[(d - 1) * n + j]) / c3;
      }
      w[j] = c4 * w[j] / c3;
    }
    c1 = c2;
  }
}

void ArcLengthStencil::Build(const std::vector<double>& seg) {
  const int m = static_cast<int>(seg.size());
  if (m < 5) {
    throw std::invalid_argument("ArcLengthStencil: need at least 5 segments, got " +
                                std::to_string(m));
  }
  if (size_ != m) {
    size_ = m;
    d1_.resize(5 * m);
    d2_.resize(5 * m);
    s0_.resize(4 * m);
    s1_.resize(4 * m);
  }
  auto at = [&](int k) { return seg[((k % m) + m) % m]; };
  double w[15];
  for (int k = 0; k < m; ++k) {
    // Marker offsets l_{k+j} - l_k, j = -2..2.
    const double nodes[5] = {-at(k - 1) - at(k - 2), -at(k - 1), 0.0, at(k), at(k) + at(k + 1)};
    FiniteDifferenceWeights(0.0, nodes, 5, 2, w);
    for (int j = 0; j < 5; ++j) {
      d1_[5 * k + j] = w[5 + j];
      d2_[5 * k + j] = w[10 + j];
    }
    // Midpoints of segments k-2, k-1, k, k+1 relative to marker k.
    const double mids[4] = {-at(k - 1) - 0.5 * at(k - 2), -0.5 * at(k - 1), 0.5 * at(k),
                            at(k) + 0.5 * at(k + 1)};
    FiniteDifferenceWeights(0.0, mids, 4, 1, w);
    for (int j = 0; j < 4; ++j) {
      s0_[4 * k + j] = w[j];
      s1_[4 * k + j] = w[4 + j];
    }
  }
}

namespace {
inline int Wrap(int k, int m) { return k < 0 ? k + m : (k >= m ? k - m : k); }
}  // namespace

double ArcLengthStencil::MarkerFirst(const std::vector<double>& g, int k) const {
  double r = 0.0;
  for (int j = 0; j < 5; ++j) r += d1_[5 * k + j] * g[Wrap(k + j - 2, size_)];
  return r;
}

double ArcLengthStencil::MarkerSecond(const std::vector<double>& g, int k) const {
  double r = 0.0;
  for (int j = 0; j < 5; ++j) r += d2_[5 * k + j] * g[Wrap(k + j - 2, size_)];
  return r;
}

double ArcLengthStencil::SegmentToMarker(const std::vector<double>& s, int k) const {
  double r = 0.0;
  for (int j = 0; j < 4; ++j) r += s0_[4 * k + j] * s[Wrap(k + j - 2, size_)];
  return r;
}

double ArcLengthStencil::SegmentDerivativeAtMarker(const std::vector<double>& s, int k) const {
  double r = 0.0;
  for (int j = 0; j < 4; ++j) r += s1_[4 * k + j] * s[Wrap(k + j - 2, size_)];
  return r;
}

}  // namespace ehd
