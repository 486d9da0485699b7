// Finite-element membrane (membrane/surface_elasticity.h, song2019 eqs. (127)-(139)): nodal forces
// against finite differences of the total energy, zero force and no net force or torque for
// rigid motions, principal tensions of a homogeneously stretched element against the closed
// forms of each law (derived in the header), and the inflated sphere against Laplace's law.
#include "ehd_capsule/membrane/surface_elasticity.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace ehd {
namespace {

const SurfaceLawParameters kLaws[] = {
    {SurfaceLaw::kNeoHookean, 1.3, 1.0},
    {SurfaceLaw::kZeroThickness, 0.7, 1.0},
    {SurfaceLaw::kSkalak, 1.1, 15.0},
};

Eigen::Matrix3Xd Deformed(const TriangleMesh& m, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3Xd x = m.vertices();
  for (int v = 0; v < x.cols(); ++v) {
    const Eigen::Vector3d p = x.col(v);
    x.col(v) = Eigen::Vector3d(1.2 * p.x(), 0.9 * p.y() + 0.1 * p.x() * p.z(), 0.85 * p.z()) +
               0.02 * Eigen::Vector3d(u(gen), u(gen), u(gen));
  }
  return x;
}

TEST(SurfaceElasticity, ForceIsMinusTheEnergyGradient) {
  const TriangleMesh m = IcosphereMesh(2);
  for (const SurfaceLawParameters& law : kLaws) {
    const SurfaceElasticity el(law, m);
    Eigen::Matrix3Xd x = Deformed(m, 3);
    Eigen::Matrix3Xd f;
    el.ComputeForces(x, f);
    const double h = 1e-6;
    double worst = 0.0, scale = f.cwiseAbs().maxCoeff();
    for (int v = 0; v < x.cols(); v += 7) {
      for (int a = 0; a < 3; ++a) {
        Eigen::Matrix3Xd xp = x, xm = x;
        xp(a, v) += h;
        xm(a, v) -= h;
        const double fd = -(el.Energy(xp) - el.Energy(xm)) / (2 * h);
        worst = std::max(worst, std::abs(fd - f(a, v)));
      }
    }
    EXPECT_LT(worst, 1e-7 * scale) << ToString(law.law);
  }
}

TEST(SurfaceElasticity, RigidMotionGivesNoForceAndForcesHaveNoResultant) {
  const TriangleMesh m = IcosphereMesh(3);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  for (const SurfaceLawParameters& law : kLaws) {
    const SurfaceElasticity el(law, m);
    Eigen::Matrix3Xd moved = (r * m.vertices()).colwise() + Eigen::Vector3d(3, -1, 2);
    Eigen::Matrix3Xd f;
    const double energy = el.ComputeForces(moved, f);
    EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-12) << ToString(law.law);
    EXPECT_LT(std::abs(energy), 1e-12);
    const Eigen::Matrix3Xd x = Deformed(m, 5);
    el.ComputeForces(x, f);
    Eigen::Vector3d total = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    for (int v = 0; v < x.cols(); ++v) {
      total += f.col(v);
      torque += Eigen::Vector3d(x.col(v)).cross(Eigen::Vector3d(f.col(v)));
    }
    const double scale = f.cwiseAbs().maxCoeff();
    EXPECT_LT(total.norm(), 1e-12 * scale * x.cols());
    EXPECT_LT(torque.norm(), 1e-12 * scale * x.cols());
  }
}

TEST(SurfaceElasticity, StretchedElementHasTheLawsPrincipalTensions) {
  // A flat element, the triangle (0,0), (1,0), (0,1) doubly covered (a closed two-face surface),
  // stretched by l1 along x and l2 along y. Homogeneous state: Cauchy tensions diag(tau_1,
  // tau_2), first Piola-Kirchhoff P = J sigma F^-T = diag(tau_1 l2, tau_2 l1), and the force on
  // vertex (1, 0) of each face is -A_0 P grad N = -(1/2) (tau_1 l2, 0): -tau_1 l2 for the two.
  // The closed-form tensions below are derived independently of the code's W_I, W_J.
  for (const SurfaceLawParameters& law : kLaws) {
    for (double l1 : {0.8, 1.0, 1.3}) {
      for (double l2 : {0.9, 1.1}) {
        Eigen::Matrix3Xd x(3, 3);
        x << 0, 1, 0, 0, 0, 1, 0, 0, 0;
        const TriangleMesh pillow(x, {{0, 1, 2}, {0, 2, 1}});
        const SurfaceElasticity el(law, pillow);
        Eigen::Matrix3Xd deformed = x;
        deformed.row(0) *= l1;
        deformed.row(1) *= l2;
        const double g = law.shear_modulus, j = l1 * l2;
        double exact1, exact2;
        switch (law.law) {
          case SurfaceLaw::kNeoHookean:
            exact1 = g / j * (l1 * l1 - 1 / (j * j));
            exact2 = g / j * (l2 * l2 - 1 / (j * j));
            break;
          case SurfaceLaw::kZeroThickness:
            exact1 = g / j * (l1 * l1 - 1 + 2 * std::log(j));
            exact2 = g / j * (l2 * l2 - 1 + 2 * std::log(j));
            break;
          default:
            exact1 = g * l1 / l2 * (l1 * l1 - 1 + law.area_dilation * l2 * l2 * (j * j - 1));
            exact2 = g * l2 / l1 * (l2 * l2 - 1 + law.area_dilation * l1 * l1 * (j * j - 1));
        }
        const Eigen::Vector2d tau = PrincipalTensions(law, l1, l2);
        EXPECT_NEAR(tau(0), exact1, 1e-13) << ToString(law.law);
        EXPECT_NEAR(tau(1), exact2, 1e-13) << ToString(law.law);
        Eigen::Matrix3Xd f;
        el.ComputeForces(deformed, f);
        EXPECT_NEAR(f(0, 1), -exact1 * l2, 1e-13) << ToString(law.law) << " " << l1 << " " << l2;
        EXPECT_NEAR(f(1, 2), -exact2 * l1, 1e-13) << ToString(law.law);
        EXPECT_NEAR(f(1, 1), 0.0, 1e-13);
        const std::vector<Eigen::Vector2d> s = el.Stretches(deformed);
        EXPECT_NEAR(s[0](0), std::max(l1, l2), 1e-13);
        EXPECT_NEAR(s[0](1), std::min(l1, l2), 1e-13);
      }
    }
  }
}

TEST(SurfaceElasticity, InflatedSphereObeysLaplacesLaw) {
  // A sphere of radius 1 inflated to R = l: isotropic tension tau(l) and an inward force per
  // vertex f.n = -2 tau / R A_i (Laplace), second order in h on average.
  for (const SurfaceLawParameters& law : kLaws) {
    const double l = 1.1;
    const double tau = PrincipalTensions(law, l, l)(0);
    double error[2];
    for (int level = 0; level < 2; ++level) {
      const TriangleMesh m = IcosphereMesh(3 + level);
      const SurfaceElasticity el(law, m);
      const Eigen::Matrix3Xd x = l * m.vertices();
      Eigen::Matrix3Xd f;
      el.ComputeForces(x, f);
      TriangleMesh deformed = m;
      deformed.SetVertices(x);
      const SurfaceGeometry g = MeasureSurface(deformed);
      double sum = 0, weight = 0;
      for (int v = 0; v < x.cols(); ++v) {
        const double pressure = -f.col(v).dot(g.normal.col(v)) / g.vertex_area[v];
        sum += g.vertex_area[v] * std::pow(pressure - 2 * tau / l, 2);
        weight += g.vertex_area[v];
      }
      error[level] = std::sqrt(sum / weight) / (2 * tau / l);
    }
    EXPECT_LT(error[1], 0.02) << ToString(law.law);
    EXPECT_GT(std::log2(error[0] / error[1]), 0.9) << ToString(law.law);
  }
}

TEST(SurfaceElasticity, RejectsBadParametersAndInvertedTriangles) {
  const TriangleMesh m = IcosphereMesh(1);
  EXPECT_THROW(SurfaceElasticity({SurfaceLaw::kNeoHookean, 0.0, 1.0}, m), std::invalid_argument);
  EXPECT_THROW(SurfaceElasticity({SurfaceLaw::kSkalak, 1.0, 0.0}, m), std::invalid_argument);
  const SurfaceElasticity el(kLaws[0], m);
  Eigen::Matrix3Xd x = m.vertices(), f;
  const TriangleMesh::Edge& e = m.edges()[0];
  x.col(e.a) = x.col(e.b);  // collapses the two triangles of this edge
  EXPECT_THROW(el.ComputeForces(x, f), std::runtime_error);
}

TEST(SurfaceElasticity, VertexMeanTensionOfAnInflatedAndARigidlyMovedSphere) {
  // Inflated by l: every triangle has l1 = l2 = l, so every vertex has the isotropic tension of
  // the closed forms above (neo-Hookean g (1 - l^-6), zero-thickness g (1 - l^-2 + 2 log(l^2) /
  // l^2), Skalak g (l^2 - 1 + C l^2 (l^4 - 1))). A rotation and translation: zero.
  const TriangleMesh m = IcosphereMesh(2);
  for (const SurfaceLawParameters& law : kLaws) {
    const SurfaceElasticity el(law, m);
    const double l = 1.15, g = law.shear_modulus;
    const double exact = law.law == SurfaceLaw::kNeoHookean ? g * (1 - std::pow(l, -6))
                         : law.law == SurfaceLaw::kZeroThickness
                             ? g * (1 - 1 / (l * l) + 2 * std::log(l * l) / (l * l))
                             : g * (l * l - 1 + law.area_dilation * l * l * (std::pow(l, 4) - 1));
    for (double tau : el.VertexMeanTension(l * m.vertices())) {
      EXPECT_NEAR(tau, exact, 1e-12 * std::abs(exact)) << ToString(law.law);
    }
    const Eigen::Matrix3d r =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    const Eigen::Matrix3Xd moved = (r * m.vertices()).colwise() + Eigen::Vector3d(0.3, -2, 5);
    for (double tau : el.VertexMeanTension(moved)) EXPECT_NEAR(tau, 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace ehd
