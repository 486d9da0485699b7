// Helfrich bending (membrane/helfrich_bending.h, song2019 eqs. (144)-(145)): the sphere (zero
// force for c0 = 0; the analytic normal force E_B c0 (2 - c0 R)/R^2 otherwise), the virtual work
// of the force against the change of the discrete energy for smooth deformations of an
// ellipsoid (converging as the mesh is refined), and the vanishing resultant on a closed surface.
#include "ehd_capsule/membrane/helfrich_bending.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace ehd {
namespace {

TEST(HelfrichBending, SphereWithoutSpontaneousCurvatureFeelsNoForce) {
  double worst[2];
  for (int level = 0; level < 2; ++level) {
    const TriangleMesh m = IcosphereMesh(3 + level, 2.0);
    const HelfrichBending b({1.5, 0.0});
    Eigen::Matrix3Xd f;
    b.ComputeForces(m, f);
    const SurfaceGeometry g = MeasureSurface(m);
    worst[level] = 0;
    for (int v = 0; v < m.vertex_count(); ++v) {
      worst[level] = std::max(worst[level], f.col(v).norm() / g.vertex_area[v]);
    }
  }
  // Scale of the bending pressure: E_B / R^3 = 0.19. The residual comes from the O(h^2) noise of
  // the discrete K (and of H, through Delta_LB H) and falls at about first order (measured 1.2).
  std::printf("sphere, c0 = 0: largest |f_b| %.3e (642 vertices), %.3e (2562) of E_B/R^3 = %.3f\n",
              worst[0], worst[1], 1.5 / 8.0);
  EXPECT_LT(worst[1], 2e-2 * 1.5 / 8.0);
  EXPECT_GT(std::log2(worst[0] / worst[1]), 1.0) << worst[0] << " " << worst[1];
}

TEST(HelfrichBending, SphereWithSpontaneousCurvatureMatchesTheEnergyDerivative) {
  const double r = 1.5, eb = 0.8;
  for (double c0 : {-1.0, 0.5, 2.0}) {
    const TriangleMesh m = IcosphereMesh(4, r);
    const HelfrichBending b({eb, c0});
    Eigen::Matrix3Xd f;
    const double energy = b.ComputeForces(m, f);
    EXPECT_NEAR(energy, 2 * M_PI * eb * std::pow(2 - c0 * r, 2), 3e-3 * energy + 1e-6);
    const SurfaceGeometry g = MeasureSurface(m);
    const double exact = eb * c0 * (2 - c0 * r) / (r * r);
    for (int v = 0; v < m.vertex_count(); v += 11) {
      EXPECT_NEAR(f.col(v).dot(g.normal.col(v)) / g.vertex_area[v], exact,
                  1.5e-2 * std::abs(eb / (r * r * r)) + 5e-3 * std::abs(exact))
          << "c0 " << c0;
    }
  }
}

// Virtual work: for X(eps) = X + eps psi n with a smooth psi, dE/deps (central difference of the
// discrete energy) should equal -sum f_i . psi_i n_i, up to the discretisation error.
double VirtualWorkMismatch(int subdivisions, double c0) {
  TriangleMesh m = EllipsoidMesh(subdivisions, 1.0, 0.8, 0.6);
  const HelfrichBending b({1.0, c0});
  Eigen::Matrix3Xd f;
  b.ComputeForces(m, f);
  const SurfaceGeometry g = MeasureSurface(m);
  const Eigen::Matrix3Xd x0 = m.vertices();
  Eigen::Matrix3Xd dx(3, x0.cols());
  for (int v = 0; v < x0.cols(); ++v) {
    const double psi = 0.3 * x0(0, v) * x0(1, v) + 0.2 * x0(2, v) * x0(2, v);
    dx.col(v) = psi * g.normal.col(v);
  }
  const double eps = 1e-5;
  m.SetVertices(x0 + eps * dx);
  const double ep = b.Energy(m);
  m.SetVertices(x0 - eps * dx);
  const double em = b.Energy(m);
  const double de = (ep - em) / (2 * eps);
  const double work = -(f.array() * dx.array()).sum();
  return std::abs(work - de) / std::abs(de);
}

TEST(HelfrichBending, VirtualWorkMatchesTheDiscreteEnergyAsTheMeshIsRefined) {
  for (double c0 : {0.0, 1.0}) {
    const double coarse = VirtualWorkMismatch(3, c0), fine = VirtualWorkMismatch(4, c0);
    std::printf("c0 = %.1f: relative mismatch %.3e (642 vertices), %.3e (2562)\n", c0, coarse,
                fine);
    EXPECT_LT(fine, 0.05);
    EXPECT_LT(fine, coarse);
  }
}

TEST(HelfrichBending, ForcesOfAClosedSurfaceHaveNoResultantInTheLimit) {
  double resultant[2];
  for (int level = 0; level < 2; ++level) {
    // A smooth shape without symmetry planes (on the ellipsoid the resultant is zero by symmetry).
    TriangleMesh m = IcosphereMesh(3 + level);
    Eigen::Matrix3Xd x = m.vertices();
    for (int v = 0; v < x.cols(); ++v) {
      const Eigen::Vector3d p = x.col(v);
      x.col(v) = Eigen::Vector3d(p.x() + 0.15 * p.y() * p.y(), 0.9 * p.y() + 0.1 * p.z() * p.x(),
                                 0.8 * p.z() + 0.12 * p.x() * p.x());
    }
    m.SetVertices(x);
    Eigen::Matrix3Xd f;
    HelfrichBending({1.0, 0.0}).ComputeForces(m, f);
    resultant[level] = f.rowwise().sum().norm() / f.colwise().norm().sum();
  }
  std::printf("resultant / sum |f|: %.3e (642 vertices), %.3e (2562)\n", resultant[0],
              resultant[1]);
  EXPECT_LT(resultant[1], 0.5 * resultant[0]);
  EXPECT_LT(resultant[1], 1e-2);
}

TEST(HelfrichBending, RejectsNegativeModulus) {
  EXPECT_THROW(HelfrichBending({-1.0, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
