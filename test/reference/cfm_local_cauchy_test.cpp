// Checks of the CFM local Cauchy least-squares problem (song2019 sec. 2.3.2-2.3.3) on every
// irregular 5-point stencil of a grid cut by a circle or an ellipse: the fitted correction
// function D is compared with a known D whose Laplacian and Cauchy data are given exactly.
#include "ehd_capsule/reference/cfm_local_cauchy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/reference/cfm_stencil_patch.h"

namespace ehd {
namespace {

struct KnownD {
  std::function<double(double, double)> value;
  std::function<Eigen::Vector2d(double, double)> gradient;
  std::function<double(double, double)> laplacian;
};

// A full cubic: every monomial of degree <= 3 (lies in the bicubic space in any rotated frame).
KnownD Cubic() {
  return {[](double x, double y) {
            return 1.0 + 2.0 * x - y + x * x - 3.0 * x * y + 0.5 * y * y + x * x * x -
                   2.0 * x * x * y + x * y * y + 0.7 * y * y * y;
          },
          [](double x, double y) {
            return Eigen::Vector2d(2.0 + 2.0 * x - 3.0 * y + 3.0 * x * x - 4.0 * x * y + y * y,
                                   -1.0 - 3.0 * x + y - 2.0 * x * x + 2.0 * x * y + 2.1 * y * y);
          },
          [](double x, double y) { return 2.0 + 1.0 + 6.0 * x - 4.0 * y + 2.0 * x + 4.2 * y; }};
}

// Linear plus c |x|^2: lies in the modified bilinear space (bilinear + N_5) in any frame.
KnownD LinearPlusRadial() {
  return {[](double x, double y) { return 0.5 - x + 2.0 * y + 1.5 * (x * x + y * y); },
          [](double x, double y) { return Eigen::Vector2d(-1.0 + 3.0 * x, 2.0 + 3.0 * y); },
          [](double, double) { return 6.0; }};
}

// Smooth, not polynomial: D = exp(x) sin(2y) + cos(3x) y.
KnownD Smooth() {
  return {
      [](double x, double y) { return std::exp(x) * std::sin(2.0 * y) + std::cos(3.0 * x) * y; },
      [](double x, double y) {
        return Eigen::Vector2d(std::exp(x) * std::sin(2.0 * y) - 3.0 * std::sin(3.0 * x) * y,
                               2.0 * std::exp(x) * std::cos(2.0 * y) + std::cos(3.0 * x));
      },
      [](double x, double y) {
        return -3.0 * std::exp(x) * std::sin(2.0 * y) - 9.0 * std::cos(3.0 * x) * y;
      }};
}

Eigen::Matrix2Xd Ellipse(int m, double a, double b) {
  Eigen::Matrix2Xd x(2, m);
  for (int k = 0; k < m; ++k) {
    const double t = 2.0 * M_PI * k / m;
    x(0, k) = 0.02 + a * std::cos(t);
    x(1, k) = -0.03 + b * std::sin(t);
  }
  return x;
}

struct StencilStats {
  double max_error = 0.0;  // max |D_fit - D| over all far nodes of all irregular stencils
  double max_scale = 0.0;  // max |D| there
  int stencils = 0;
  int failures = 0;
};

// Solves the local Cauchy problem at every irregular stencil of an n x n grid on [-1, 1]^2.
StencilStats SweepStencils(const ClosedCurve& curve, int n, const KnownD& d, CfmBasis basis,
                           int n_sub) {
  const Grid2D grid{n, n, 2.0 / n, -1.0, -1.0};
  std::vector<char> inside(grid.size());
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) inside[grid.index(i, j)] = curve.Contains({grid.x(i), grid.y(j)});
  }
  CfmLocalCauchy cauchy(basis);
  StencilStats stats;
  constexpr int kDi[4] = {1, -1, 0, 0}, kDj[4] = {0, 0, 1, -1};
  for (int j = 1; j < n - 1; ++j) {
    for (int i = 1; i < n - 1; ++i) {
      Eigen::Vector2d far[4];
      int n_far = 0;
      for (int k = 0; k < 4; ++k) {
        if (inside[grid.index(i + kDi[k], j + kDj[k])] != inside[grid.index(i, j)]) {
          far[n_far++] = {grid.x(i + kDi[k]), grid.y(j + kDj[k])};
        }
      }
      if (n_far == 0) continue;
      const Eigen::Vector2d center(grid.x(i), grid.y(j));
      CfmStencilPatch sp;
      ++stats.stencils;
      if (!BuildCfmStencilPatch(curve, center, grid.h, far, n_far, curve.ClosestParameter(center),
                                &sp)) {
        ++stats.failures;
        continue;
      }
      // Every node where D is needed lies in the patch (song2019 Fig. 4b).
      for (int k = 0; k < n_far; ++k) {
        const Eigen::Vector2d local = sp.patch.Local(far[k]);
        EXPECT_LE(std::abs(local.x()), 1.0 + 1e-9);
        EXPECT_LE(std::abs(local.y()), 1.0 + 1e-9);
      }
      CfmInterfaceSample samples[CfmLocalCauchy::kMaxInterfaceSamples];
      double params[CfmLocalCauchy::kMaxInterfaceSamples];
      const int ns = CfmInterfaceQuadrature(curve, sp, n_sub, samples, params);
      for (int m = 0; m < ns; ++m) {
        const Eigen::Vector2d x = samples[m].position;
        samples[m].jump_value = d.value(x.x(), x.y());
        samples[m].jump_normal = d.gradient(x.x(), x.y()).dot(samples[m].normal);
      }
      const auto area = CfmLocalCauchy::AreaPoints(sp.patch);
      double f_jump[CfmLocalCauchy::kAreaPoints];
      for (int q = 0; q < CfmLocalCauchy::kAreaPoints; ++q) {
        f_jump[q] = d.laplacian(area[q].x(), area[q].y());
      }
      if (!cauchy.Solve(sp.patch, f_jump, samples, ns)) {
        ++stats.failures;
        continue;
      }
      for (int k = 0; k < n_far; ++k) {
        const double exact = d.value(far[k].x(), far[k].y());
        stats.max_error = std::max(stats.max_error, std::abs(cauchy.Value(far[k]) - exact));
        stats.max_scale = std::max(stats.max_scale, std::abs(exact));
      }
    }
  }
  return stats;
}

// A bicubic-space D has J_p = 0 at D itself, and the minimiser is unique (a harmonic function
// with zero Cauchy data on an arc vanishes), so the fit must reproduce D to round-off.
TEST(CfmLocalCauchy, BicubicReproducesCubicExactly) {
  for (const int n : {24, 64}) {
    const ClosedCurve ellipse(Ellipse(120, 0.6, 0.35));
    const StencilStats stats = SweepStencils(ellipse, n, Cubic(), CfmBasis::kBicubic, 3);
    EXPECT_GT(stats.stencils, 20);
    EXPECT_EQ(stats.failures, 0);
    EXPECT_LT(stats.max_error, 1e-9 * stats.max_scale) << "n = " << n;
  }
}

// Same argument for the modified bilinear space of song2019 sec. 2.3.4 (N_5 gives Laplace = c).
TEST(CfmLocalCauchy, ModifiedBilinearReproducesLinearPlusRadial) {
  const ClosedCurve ellipse(Ellipse(120, 0.6, 0.35));
  const StencilStats stats =
      SweepStencils(ellipse, 40, LinearPlusRadial(), CfmBasis::kModifiedBilinear, 1);
  EXPECT_EQ(stats.failures, 0);
  EXPECT_LT(stats.max_error, 1e-10 * stats.max_scale);
}

// A smooth D is approximated by a bicubic to O(h^4) on a patch of size O(h) (Taylor remainder of
// degree 4); the least-squares fit inherits that order, so halving h divides the error by ~16.
TEST(CfmLocalCauchy, BicubicIsFourthOrderOnSmoothD) {
  const ClosedCurve ellipse(Ellipse(240, 0.6, 0.35));
  double error[3];
  const int sizes[3] = {32, 64, 128};
  for (int r = 0; r < 3; ++r) {
    const StencilStats stats = SweepStencils(ellipse, sizes[r], Smooth(), CfmBasis::kBicubic, 3);
    EXPECT_EQ(stats.failures, 0);
    error[r] = stats.max_error;
  }
  const double order_1 = std::log2(error[0] / error[1]);
  const double order_2 = std::log2(error[1] / error[2]);
  std::printf("bicubic D errors at the far nodes: %.3e %.3e %.3e, orders %.2f %.2f\n", error[0],
              error[1], error[2], order_1, order_2);
  EXPECT_GT(order_2, 3.5) << "errors " << error[0] << " " << error[1] << " " << error[2]
                          << " orders " << order_1 << " " << order_2;
}

TEST(CfmLocalCauchy, RejectsBadInput) {
  EXPECT_THROW(CfmLocalCauchy(CfmBasis::kBicubic, 0.0), std::invalid_argument);
  CfmLocalCauchy cauchy;
  CfmPatch patch;
  patch.half_p = patch.half_q = 1.0;
  double f[CfmLocalCauchy::kAreaPoints] = {};
  CfmInterfaceSample sample;
  EXPECT_THROW(cauchy.Solve(patch, f, &sample, 0), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
