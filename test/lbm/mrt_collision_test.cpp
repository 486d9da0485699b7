// The D2Q9 MRT basis and the single-node collision (song2019 section 3.1.1, eqs. (107)-(108)).
// Every expected value follows from the algebra of the scheme: orthogonality of M, conservation
// laws of the collision, and the kernel compared with the textbook matrix form f - M^-1 S (m -
// m^eq) evaluated independently with the 9x9 matrix.
#include "ehd_capsule/lbm/mrt_collision.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "ehd_capsule/lbm/d2q9.h"

namespace ehd {
namespace {

using d2q9::kQ;
using Vec9 = std::array<double, kQ>;

Vec9 Moments(const Vec9& f) {
  Vec9 m{};
  for (int k = 0; k < kQ; ++k) {
    for (int i = 0; i < kQ; ++i) m[k] += d2q9::kMomentMatrix[k][i] * f[i];
  }
  return m;
}

// M^-1 m = M^T diag(1/|row|^2) m (valid because the rows are orthogonal, checked below).
Vec9 Populations(const Vec9& m) {
  Vec9 f{};
  for (int i = 0; i < kQ; ++i) {
    for (int k = 0; k < kQ; ++k) f[i] += d2q9::kMomentMatrix[k][i] * m[k] / d2q9::kMomentNorm[k];
  }
  return f;
}

Vec9 RandomPopulations(std::mt19937& gen) {
  std::uniform_real_distribution<double> d(0.02, 0.3);
  Vec9 f;
  for (double& v : f) v = d(gen);
  return f;
}

template <ForcingScheme kForcing>
Vec9 Collide(Vec9 f, double fx, double fy, double s_nu, const MrtRates& rates, double* rho,
             double* ux, double* uy) {
  MrtCollideNode<kForcing>(f[0], f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8], fx, fy, s_nu,
                           rates, *rho, *ux, *uy);
  return f;
}

TEST(D2q9Basis, RowsOrthogonalAndInverseIsIdentity) {
  // M M^T must be diag(kMomentNorm); then M^-1 = M^T diag(1/norm) and M M^-1 = I exactly.
  for (int a = 0; a < kQ; ++a) {
    for (int b = 0; b < kQ; ++b) {
      double dot = 0.0;
      for (int i = 0; i < kQ; ++i) dot += d2q9::kMomentMatrix[a][i] * d2q9::kMomentMatrix[b][i];
      EXPECT_EQ(dot, a == b ? d2q9::kMomentNorm[a] : 0.0) << "rows " << a << ", " << b;
    }
  }
  for (int i = 0; i < kQ; ++i) {
    Vec9 unit{};
    unit[i] = 1.0;
    const Vec9 back = Populations(Moments(unit));
    for (int k = 0; k < kQ; ++k) EXPECT_NEAR(back[k], unit[k], 1e-15);
  }
}

TEST(D2q9Basis, MomentRowsAreTheNamedPolynomialsOfTheVelocities) {
  // Lallemand & Luo (2000): rho = 1, e = 3c^2 - 4, epsilon = (9c^4 - 21c^2 + 8)/2, j = c,
  // q = (3c^2 - 5) c, p_xx = cx^2 - cy^2, p_xy = cx cy. Ties the printed matrix to eq. (98).
  for (int i = 0; i < kQ; ++i) {
    const double cx = d2q9::kCx[i], cy = d2q9::kCy[i], c2 = cx * cx + cy * cy;
    const auto& M = d2q9::kMomentMatrix;
    EXPECT_EQ(M[0][i], 1.0);
    EXPECT_EQ(M[1][i], 3 * c2 - 4);
    EXPECT_EQ(M[2][i], (9 * c2 * c2 - 21 * c2 + 8) / 2);
    EXPECT_EQ(M[3][i], cx);
    EXPECT_EQ(M[4][i], (3 * c2 - 5) * cx);
    EXPECT_EQ(M[5][i], cy);
    EXPECT_EQ(M[6][i], (3 * c2 - 5) * cy);
    EXPECT_EQ(M[7][i], cx * cx - cy * cy);
    EXPECT_EQ(M[8][i], cx * cy);
    EXPECT_EQ(d2q9::kCx[d2q9::kOpposite[i]], -cx);
    EXPECT_EQ(d2q9::kCy[d2q9::kOpposite[i]], -cy);
  }
}

TEST(MrtCollision, EquilibriumIsAFixedPoint) {
  // f^eq_i = w_i [rho + 3 c.u + 4.5 (c.u)^2 - 1.5 u^2] has exactly the moments m^eq of section
  // 3.1.1, so without force the collision must leave it unchanged for any rates.
  const double rho = 1.03, ux = 0.04, uy = -0.07;
  Vec9 feq;
  for (int i = 0; i < kQ; ++i) {
    const double cu = d2q9::kCx[i] * ux + d2q9::kCy[i] * uy;
    feq[i] = d2q9::kWeight[i] * (rho + 3 * cu + 4.5 * cu * cu - 1.5 * (ux * ux + uy * uy));
  }
  double r, u, v;
  const Vec9 out = Collide<ForcingScheme::kGuo>(feq, 0, 0, 1.3, {1.1, 1.54, 1.9}, &r, &u, &v);
  for (int i = 0; i < kQ; ++i) EXPECT_NEAR(out[i], feq[i], 1e-15);  // round-off
  EXPECT_NEAR(r, rho, 1e-15);
  EXPECT_NEAR(u, ux, 1e-15);
  EXPECT_NEAR(v, uy, 1e-15);
}

TEST(MrtCollision, ConservesMassAndMomentumWithoutForceAndAddsFWithForce) {
  // Mass and momentum are collision invariants; with a force the momentum gains exactly F
  // (eq. (108): j'' = j + F) and the mass is unchanged.
  std::mt19937 gen(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec9 f = RandomPopulations(gen);
    const Vec9 m = Moments(f);
    const double fx = trial == 0 ? 0.0 : 1e-3 * (trial - 10), fy = trial == 0 ? 0.0 : 2e-4 * trial;
    for (bool guo : {false, true}) {
      double r, u, v;
      const Vec9 out =
          guo ? Collide<ForcingScheme::kGuo>(f, fx, fy, 1.7, {1.64, 1.54, 1.9}, &r, &u, &v)
              : Collide<ForcingScheme::kSplitMomentum>(f, fx, fy, 1.7, {1.64, 1.54, 1.9}, &r, &u,
                                                       &v);
      const Vec9 mo = Moments(out);
      EXPECT_NEAR(mo[d2q9::kRho], m[d2q9::kRho], 1e-15);
      EXPECT_NEAR(mo[d2q9::kMomentumX], m[d2q9::kMomentumX] + fx, 1e-15);
      EXPECT_NEAR(mo[d2q9::kMomentumY], m[d2q9::kMomentumY] + fy, 1e-15);
      EXPECT_NEAR(u, m[d2q9::kMomentumX] + 0.5 * fx, 1e-15);  // u = j + F/2, rho_0 = 1
      EXPECT_NEAR(v, m[d2q9::kMomentumY] + 0.5 * fy, 1e-15);
    }
  }
}

TEST(MrtCollision, MatchesMatrixFormWithSplitAndGuoForcing) {
  // Independent evaluation: m* = m - S (m - m^eq(j')) with j* = j + F, f* = M^-1 m*; for Guo add
  // M^-1 (I - S/2) M F_i with F_i = w_i [3 c.F + 9 (c.u)(c.F) - 3 u.F] built in velocity space.
  std::mt19937 gen(11);
  const MrtRates rates{1.64, 1.54, 1.9};
  const double s_nu = 1.25;
  const Vec9 s = {0, rates.s_e, rates.s_epsilon, 0, rates.s_q, 0, rates.s_q, s_nu, s_nu};
  for (int trial = 0; trial < 10; ++trial) {
    const Vec9 f = RandomPopulations(gen);
    const double fx = 0.01 * (trial - 4), fy = -0.003 * trial;
    const Vec9 m = Moments(f);
    const double ux = m[3] + fx / 2, uy = m[5] + fy / 2, u2 = ux * ux + uy * uy;
    const Vec9 meq = {m[0], -2 * m[0] + 3 * u2, m[0] - 3 * u2, ux, -ux, uy,
                      -uy,  ux * ux - uy * uy,  ux * uy};
    Vec9 mstar;
    for (int k = 0; k < kQ; ++k) mstar[k] = m[k] - s[k] * (m[k] - meq[k]);
    mstar[3] = m[3] + fx;
    mstar[5] = m[5] + fy;
    const Vec9 expected_split = Populations(mstar);

    Vec9 force_pop;
    for (int i = 0; i < kQ; ++i) {
      const double cx = d2q9::kCx[i], cy = d2q9::kCy[i];
      force_pop[i] = d2q9::kWeight[i] *
                     (3 * (cx * fx + cy * fy) + 9 * (cx * ux + cy * uy) * (cx * fx + cy * fy) -
                      3 * (ux * fx + uy * fy));
    }
    Vec9 source = Moments(force_pop);
    for (int k = 0; k < kQ; ++k) source[k] *= (k == 3 || k == 5) ? 0.0 : 1.0 - 0.5 * s[k];
    Vec9 mguo = mstar;
    for (int k = 0; k < kQ; ++k) mguo[k] += source[k];
    const Vec9 expected_guo = Populations(mguo);

    double r, u, v;
    const Vec9 split = Collide<ForcingScheme::kSplitMomentum>(f, fx, fy, s_nu, rates, &r, &u, &v);
    const Vec9 guo = Collide<ForcingScheme::kGuo>(f, fx, fy, s_nu, rates, &r, &u, &v);
    for (int i = 0; i < kQ; ++i) {
      EXPECT_NEAR(split[i], expected_split[i], 1e-15) << "i = " << i;
      EXPECT_NEAR(guo[i], expected_guo[i], 1e-15) << "i = " << i;
    }
  }
}

}  // namespace
}  // namespace ehd
