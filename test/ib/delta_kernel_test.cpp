// The roma3 kernel (ib/delta_kernel.h; Roma, Peskin & Berger 1999) against its defining
// identities, and the transfer with it in 2D and 3D: the values at the nodes and the joins,
// the discrete moments for any offset (sum 1, first moment 0, sum of squares 1/2), the Fourier
// transform against a brute-force integral, and the transfer's adjointness, force conservation,
// product structure and exact interpolation of linear fields (which the cosine kernel lacks).
#include "ehd_capsule/ib/delta_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "ehd_capsule/ib/immersed_boundary.h"
#include "support/ib_contract.h"

namespace ehd {
namespace {

constexpr DeltaKernel kRoma = DeltaKernel::kRoma3;

TEST(Roma3Delta, ValuesAtTheNodesAndTheJoins) {
  // phi(0) = 2/3, phi(1/2) = 1/2 from both pieces, phi(1) = 1/6, phi(3/2) = 0, even.
  EXPECT_NEAR(DeltaKernelValue(kRoma, 0.0), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(DeltaKernelValue(kRoma, 0.5), 0.5, 1e-15);
  EXPECT_NEAR(DeltaKernelValue(kRoma, 0.5 + 1e-12), 0.5, 1e-11);
  EXPECT_NEAR(DeltaKernelValue(kRoma, -1.0), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(DeltaKernelValue(kRoma, 1.5), 0.0, 1e-15);
  EXPECT_EQ(DeltaKernelValue(kRoma, 1.7), 0.0);
  EXPECT_EQ(ParseDeltaKernel("roma3"), kRoma);
  EXPECT_EQ(ParseDeltaKernel("cosine"), DeltaKernel::kCosine4);
  EXPECT_THROW(ParseDeltaKernel("peskin4"), std::invalid_argument);
}

TEST(Roma3Delta, DiscreteMomentsForAnyOffset) {
  // Roma et al. (1999) build the kernel from sum phi = 1, sum (r - j) phi = 0 and
  // sum phi^2 = 1/2 over the integer nodes, for every offset r.
  for (double r = -3.0; r <= 3.0; r += 0.0173) {
    double m0 = 0.0, m1 = 0.0, m2 = 0.0;
    for (int j = -8; j <= 8; ++j) {
      const double p = DeltaKernelValue(kRoma, r - j);
      m0 += p;
      m1 += (r - j) * p;
      m2 += p * p;
    }
    EXPECT_NEAR(m0, 1.0, 1e-14) << r;
    EXPECT_NEAR(m1, 0.0, 1e-14) << r;
    EXPECT_NEAR(m2, 0.5, 1e-14) << r;
    // The stencil's three nodes carry the kernel's whole support.
    const DeltaStencil st = Roma3DeltaStencil(r);
    double sum = 0.0;
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(st.weight[a], DeltaKernelValue(kRoma, r - (st.first + a)), 1e-15) << r;
      sum += st.weight[a];
    }
    EXPECT_EQ(st.weight[3], 0.0);
    EXPECT_NEAR(sum, 1.0, 1e-15) << r;
  }
}

TEST(Roma3Delta, FourierTransformMatchesABruteForceIntegral) {
  // 2 int_0^{3/2} phi(r) cos(xi r) dr by the midpoint rule on 300000 cells (error ~1e-11).
  for (double xi : {0.0, 0.4, 1.0, 2.0, 3.14159, 5.0, 6.28318}) {
    const int n = 300000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double r = 1.5 * (i + 0.5) / n;
      sum += DeltaKernelValue(kRoma, r) * std::cos(xi * r);
    }
    EXPECT_NEAR(Roma3DeltaTransform(xi), 2.0 * 1.5 * sum / n, 1e-9) << xi;
  }
  EXPECT_NEAR(Roma3DeltaTransform(0.0), 1.0, 1e-14);
}

TEST(Roma3Transfer, TwoDimensionalAdjointConservingAndExactOnLinearFields) {
  const ImmersedBoundaryTransfer<2> ib(test::ContractGrid(), {true, false}, kRoma);
  EXPECT_EQ(ib.kernel(), kRoma);
  test::ExpectAdjointConservingAndExactOnLinearFields(ib, 3);
}

TEST(Roma3Transfer, ThreeDimensionalKernelIsTheProductAndExactOnLinearFields) {
  const Grid3D g{10, 10, 10, 0.25, -1.25, -1.25, -1.25};
  const ImmersedBoundaryTransfer<3> ib(g, {true, true, true}, kRoma);
  Eigen::Matrix3Xd x(3, 1), f(3, 1);
  x << 0.113, -0.271, 0.049;
  f << 1.0, 0.0, 0.0;
  std::vector<double> fx(g.size(), 0.0), fy(g.size(), 0.0), fz(g.size(), 0.0);
  ib.Spread(x, f, {&fx, &fy, &fz});
  int nonzero = 0;
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const double w = DeltaKernelValue(kRoma, (g.x(i) - x(0, 0)) / g.h) *
                         DeltaKernelValue(kRoma, (g.y(j) - x(1, 0)) / g.h) *
                         DeltaKernelValue(kRoma, (g.z(k) - x(2, 0)) / g.h) / (g.h * g.h * g.h);
        EXPECT_NEAR(fx[g.index(i, j, k)], w, 1e-12);
        nonzero += fx[g.index(i, j, k)] != 0.0;
      }
    }
  }
  EXPECT_LE(nonzero, 27);  // 3 nodes per axis in place of the cosine kernel's 4
  // u = (1 + x + 2y - z, y, z): linear, so interpolated exactly at any point.
  std::vector<double> ux(g.size()), uy(g.size()), uz(g.size());
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        ux[g.index(i, j, k)] = 1.0 + g.x(i) + 2.0 * g.y(j) - g.z(k);
        uy[g.index(i, j, k)] = g.y(j);
        uz[g.index(i, j, k)] = g.z(k);
      }
    }
  }
  Eigen::Matrix3Xd p(3, 3), v;
  p << 0.11, -0.3, 0.41, 0.02, 0.37, -0.44, -0.29, 0.0, 0.13;
  ib.Interpolate({&ux, &uy, &uz}, p, v);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(v(0, c), 1.0 + p(0, c) + 2.0 * p(1, c) - p(2, c), 1e-13);
    EXPECT_NEAR(v(1, c), p(1, c), 1e-13);
    EXPECT_NEAR(v(2, c), p(2, c), 1e-13);
  }
}

}  // namespace
}  // namespace ehd
