// Sawtooth filter (ib/sawtooth_filter.h): the gain on each Fourier mode is the analytic
// 1 - ((1 - cos theta)/2)^p, the zigzag is removed exactly, smooth shapes are kept to
// (theta/2)^(2p), and the order-2 filter is Longuet-Higgins & Cokelet's five-point formula.
#include "ehd_capsule/ib/sawtooth_filter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ehd {
namespace {

Eigen::Matrix2Xd Mode(int m, int wavenumber, double amplitude) {
  Eigen::Matrix2Xd x(2, m);
  for (int k = 0; k < m; ++k) {
    const double t = 2.0 * M_PI * k / m;
    x(0, k) = amplitude * std::cos(wavenumber * t);
    x(1, k) = amplitude * std::sin(wavenumber * t);
  }
  return x;
}

TEST(SawtoothFilter, GainOnEachFourierModeMatchesTheFormula) {
  // A Fourier mode is an eigenvector of the circulant filter; its eigenvalue is H(theta).
  for (int p : {1, 2, 3, 4}) {
    SawtoothFilter filter(p);
    const int m = 48;
    for (int n : {1, 2, 5, 12, 20, 23}) {
      Eigen::Matrix2Xd x = Mode(m, n, 1.0);
      const Eigen::Matrix2Xd before = x;
      filter.Apply(x);
      const double expected = filter.Gain(2.0 * M_PI * n / m);
      EXPECT_NEAR((x - expected * before).cwiseAbs().maxCoeff(), 0.0, 1e-13)
          << "p = " << p << ", n = " << n;
    }
  }
}

TEST(SawtoothFilter, RemovesTheZigzagExactly) {
  SawtoothFilter filter;
  const int m = 64;
  Eigen::Matrix2Xd x = Mode(m, 1, 8.0);
  for (int k = 0; k < m; ++k) x.col(k) *= 1.0 + 0.05 * (k % 2 == 0 ? 1.0 : -1.0);
  filter.Apply(x);
  // The modulation 0.05 (-1)^k of a circle of radius 8 is the mode of wavenumber M/2 + 1
  // (theta = pi + 2 pi / M) with amplitude 0.4; it keeps the gain
  // 1 - ((1 + cos(2 pi / 64)) / 2)^8 = 0.0191 (default p = 8). The circle keeps 1 - 1e-21.
  const Eigen::Matrix2Xd circle = Mode(m, 1, 8.0);
  EXPECT_LT((x - circle).cwiseAbs().maxCoeff(), 0.4 * 0.0192);
}

TEST(SawtoothFilter, KeepsSmoothShapes) {
  // theta = 2 pi / 64: a circle loses (theta / 2)^(2p) per application, 3.3e-11 for p = 4 (seen
  // after 1000 applications) and 1e-21 for the default p = 8 (round-off only).
  SawtoothFilter order4(4), order8;
  Eigen::Matrix2Xd x4 = Mode(64, 1, 8.0), x8 = x4;
  const Eigen::Matrix2Xd before = x4;
  for (int i = 0; i < 1000; ++i) {
    order4.Apply(x4);
    order8.Apply(x8);
  }
  EXPECT_LT((x4 - before).cwiseAbs().maxCoeff(), 8.0 * 1000 * 3.4e-11);
  EXPECT_GT((x4 - before).cwiseAbs().maxCoeff(), 8.0 * 1000 * 3.0e-11);
  EXPECT_LT((x8 - before).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(order8.order(), 8);
}

TEST(SawtoothFilter, OrderTwoIsLonguetHigginsCokelet) {
  SawtoothFilter filter(2);
  Eigen::Matrix2Xd x(2, 7);
  x << 0, 1, 5, 2, -3, 4, 1, 2, 0, -1, 3, 6, 1, 0;
  Eigen::Matrix2Xd expected(2, 7);
  for (int k = 0; k < 7; ++k) {
    expected.col(k) = (-x.col((k + 5) % 7) + 4.0 * x.col((k + 6) % 7) + 10.0 * x.col(k) +
                       4.0 * x.col((k + 1) % 7) - x.col((k + 2) % 7)) /
                      16.0;
  }
  filter.Apply(x);
  EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(SawtoothFilter, RejectsTooFewMarkersAndBadOrder) {
  EXPECT_THROW(SawtoothFilter(0), std::invalid_argument);
  SawtoothFilter filter(8);
  Eigen::Matrix2Xd x = Mode(16, 1, 1.0);
  EXPECT_THROW(filter.Apply(x), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
