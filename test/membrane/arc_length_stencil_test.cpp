// Non-uniform arc-length stencils (song2019 sec. 3.3): exact on polynomials up to their degree,
// and the staggered stencil sees the alternating segment mode.
#include "ehd_capsule/membrane/arc_length_stencil.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ehd {
namespace {

TEST(FiniteDifferenceWeights, ExactOnPolynomials) {
  // Lagrange weights on n nodes differentiate polynomials of degree < n exactly.
  const double x[5] = {-1.3, -0.4, 0.0, 0.7, 1.9};
  double w[15];
  FiniteDifferenceWeights(0.0, x, 5, 2, w);
  for (int p = 0; p < 5; ++p) {
    double v = 0, d1 = 0, d2 = 0;
    for (int j = 0; j < 5; ++j) {
      const double f = std::pow(x[j], p);
      v += w[j] * f;
      d1 += w[5 + j] * f;
      d2 += w[10 + j] * f;
    }
    EXPECT_NEAR(v, p == 0 ? 1.0 : 0.0, 1e-13);
    EXPECT_NEAR(d1, p == 1 ? 1.0 : 0.0, 1e-12);
    EXPECT_NEAR(d2, p == 2 ? 2.0 : 0.0, 1e-12);
  }
  // Uniform spacing reproduces the classical (1, -8, 0, 8, -1)/12 and (-1, 16, -30, 16, -1)/12.
  const double u[5] = {-2, -1, 0, 1, 2};
  FiniteDifferenceWeights(0.0, u, 5, 2, w);
  const double c1[5] = {1, -8, 0, 8, -1}, c2[5] = {-1, 16, -30, 16, -1};
  for (int j = 0; j < 5; ++j) {
    EXPECT_NEAR(w[5 + j], c1[j] / 12.0, 1e-14);
    EXPECT_NEAR(w[10 + j], c2[j] / 12.0, 1e-14);
  }
}

TEST(ArcLengthStencil, PeriodicFunctionAndOrders) {
  // g(l) = sin(2 pi l / L) on randomly spaced markers: marker d/dl error O(dl^4), d2/dl2 O(dl^3);
  // segment-average tension interpolated/differentiated at markers, O(dl^2) from the midpoint
  // value vs. segment mean (here the segment value is the midpoint value, so O(dl^4)/O(dl^3)).
  double prev1 = 0.0, prev2 = 0.0, prev3 = 0.0;
  for (int m : {40, 80, 160}) {
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> u(0.7, 1.3);
    std::vector<double> seg(m);
    double total = 0.0;
    for (double& s : seg) total += (s = u(gen));
    const double k = 2.0 * M_PI / total;
    std::vector<double> g(m), mid(m), pos(m);
    double l = 0.0;
    for (int i = 0; i < m; ++i) {
      pos[i] = l;
      g[i] = std::sin(k * l);
      mid[i] = std::sin(k * (l + 0.5 * seg[i]));
      l += seg[i];
    }
    ArcLengthStencil st;
    st.Build(seg);
    double e1 = 0, e2 = 0, e3 = 0;
    for (int i = 0; i < m; ++i) {
      e1 = std::max(e1, std::abs(st.MarkerFirst(g, i) - k * std::cos(k * pos[i])));
      e2 = std::max(e2, std::abs(st.MarkerSecond(g, i) + k * k * std::sin(k * pos[i])));
      e3 = std::max(e3, std::abs(st.SegmentDerivativeAtMarker(mid, i) - k * std::cos(k * pos[i])));
    }
    if (prev1 > 0) {
      EXPECT_GT(std::log2(prev1 / e1), 3.7) << m;
      EXPECT_GT(std::log2(prev2 / e2), 2.7) << m;
      EXPECT_GT(std::log2(prev3 / e3), 2.7) << m;
    }
    prev1 = e1;
    prev2 = e2;
    prev3 = e3;
  }
  // The alternating segment mode tau_k = (-1)^k has a nonzero marker derivative (uniform spacing:
  // (1 + 27 + 27 + 1)/24 = 7/3), so a zig-zag stretch is resisted.
  std::vector<double> seg(8, 1.0), alt(8);
  for (int i = 0; i < 8; ++i) alt[i] = (i % 2 == 0) ? 1.0 : -1.0;
  ArcLengthStencil st;
  st.Build(seg);
  EXPECT_NEAR(std::abs(st.SegmentDerivativeAtMarker(alt, 3)), 56.0 / 24.0, 1e-12);
}

}  // namespace
}  // namespace ehd
