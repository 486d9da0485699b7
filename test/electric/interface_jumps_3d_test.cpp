// 3D immersed interface corrections (electric/interface_jumps_3d.h) on the "known jumps" problem:
// Laplacian u = f on each side of a closed surface with [u] and [du/dn] given, solved by the 3D
// fast Poisson solver with the corrections at the irregular nodes. Exact piecewise solutions on a
// sphere and an ellipsoid (non-constant w, g and curvature) must converge at second order in the
// max norm, while without the corrections the error does not decrease. The local reconstruction
// (geometry/local_surface_fit.h) is checked on its own: the signed distance converges at third
// order on the sphere, and the fitted surface Laplacian of a smooth function at first order.
#include "ehd_capsule/electric/interface_jumps_3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ehd_capsule/electric/fast_poisson_solver_3d.h"

namespace ehd {
namespace {

// Inside: u^- = exp(x) cos(y) + z^2 (f^- = 2). Outside: u^+ = x y + 0.5 / r + z (f^+ = 0).
double Inner(const Eigen::Vector3d& p) { return std::exp(p.x()) * std::cos(p.y()) + p.z() * p.z(); }
Eigen::Vector3d InnerGradient(const Eigen::Vector3d& p) {
  return {std::exp(p.x()) * std::cos(p.y()), -std::exp(p.x()) * std::sin(p.y()), 2 * p.z()};
}
double Outer(const Eigen::Vector3d& p) { return p.x() * p.y() + 0.5 / p.norm() + p.z(); }
Eigen::Vector3d OuterGradient(const Eigen::Vector3d& p) {
  const double r3 = std::pow(p.norm(), 3);
  return Eigen::Vector3d(p.y(), p.x(), 1.0) - 0.5 * p / r3;
}

struct Shape {
  double a, b, c;  // semi-axes
  Eigen::Vector3d Normal(const Eigen::Vector3d& p) const {
    return Eigen::Vector3d(p.x() / (a * a), p.y() / (b * b), p.z() / (c * c)).normalized();
  }
};

// Max error of the corrected (or uncorrected) solve on an n^3 grid of [-1, 1]^3.
double KnownJumpError(const Shape& shape, int n, int subdivisions, bool corrected) {
  const double h = 2.0 / n;
  const Grid3D grid{n, n, n, h, -1.0, -1.0, -1.0};
  const TriangleMesh mesh = EllipsoidMesh(subdivisions, shape.a, shape.b, shape.c);
  const SurfaceClassification3D sides = ClassifyNodes(grid, mesh);
  const LocalSurfaceFit fit(mesh, h);
  SurfaceJumps3D jumps;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d p = mesh.vertices().col(v);
    jumps.w.push_back(Outer(p) - Inner(p));
    jumps.g.push_back((OuterGradient(p) - InnerGradient(p)).dot(shape.Normal(p)));
    jumps.f_jump.push_back(0.0 - 2.0);
  }
  std::vector<double> rhs(grid.size());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = grid.index(i, j, k);
        rhs[c] = sides.side[c] > 0 ? 0.0 : 2.0;
      }
  const PoissonBoundaries3D bc;  // Dirichlet, u^+ on the faces
  const auto outer = [](double x, double y, double z) { return Outer({x, y, z}); };
  const auto outer_gradient = [](double x, double y, double z) { return OuterGradient({x, y, z}); };
  AddBoundaryDataToRhs(grid, bc, SampleBoundaryData(grid, bc, outer, outer_gradient), rhs);
  if (corrected) AddJumpCorrections(grid, sides, fit, jumps, rhs);
  FastPoissonSolver3D solver(grid, bc);
  std::vector<double> u;
  solver.Solve(rhs, u);
  double error = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = grid.index(i, j, k);
        const Eigen::Vector3d p(grid.x(i), grid.y(j), grid.z(k));
        error = std::max(error, std::abs(u[c] - (sides.side[c] > 0 ? Outer(p) : Inner(p))));
      }
  return error;
}

void ExpectSecondOrder(const Shape& shape, const char* name) {
  const int grids[3] = {20, 40, 80}, subdivisions[3] = {3, 4, 5};
  double e[3];
  for (int r = 0; r < 3; ++r) {
    e[r] = KnownJumpError(shape, grids[r], subdivisions[r], true);
    std::printf("%s n = %d  max error %.3e%s\n", name, grids[r], e[r],
                r ? ("  order " + std::to_string(std::log2(e[r - 1] / e[r]))).c_str() : "");
  }
  EXPECT_GT(std::log2(e[1] / e[2]), 1.7) << name;
  EXPECT_LT(e[2], 2e-3) << name;
}

TEST(InterfaceJumps3D, KnownJumpsOnASphereConvergeAtSecondOrder) {
  ExpectSecondOrder({0.5, 0.5, 0.5}, "sphere");
}

TEST(InterfaceJumps3D, KnownJumpsOnAnEllipsoidConvergeAtSecondOrder) {
  ExpectSecondOrder({0.6, 0.45, 0.35}, "ellipsoid");
}

TEST(InterfaceJumps3D, WithoutCorrectionsTheErrorIsOrderOne) {
  const double coarse = KnownJumpError({0.5, 0.5, 0.5}, 20, 3, false);
  const double fine = KnownJumpError({0.5, 0.5, 0.5}, 40, 4, false);
  EXPECT_GT(fine, 0.3 * coarse);
  EXPECT_GT(fine, 0.05);
}

// J against the exact difference of the two smooth solutions, u^+ - u^- (both extend across the
// surface), at points within 1.5 mesh edges of an ellipsoid: O(d^4) expansion and O(h^3) data fits
// give an error that falls at third order or better with the mesh.
TEST(InterfaceJumps3D, JumpExtensionMatchesTheExactDifference) {
  const Shape shape{0.6, 0.45, 0.35};
  double previous = 0;
  for (int s = 3; s <= 5; ++s) {
    const TriangleMesh mesh = EllipsoidMesh(s, shape.a, shape.b, shape.c);
    const double edge = MeasureQuality(mesh).mean_edge;
    const LocalSurfaceFit fit(mesh, edge);
    SurfaceJumps3D jumps;
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      const Eigen::Vector3d p = mesh.vertices().col(v);
      jumps.w.push_back(Outer(p) - Inner(p));
      jumps.g.push_back((OuterGradient(p) - InnerGradient(p)).dot(shape.Normal(p)));
      jumps.f_jump.push_back(-2.0);
    }
    double error = 0;
    for (int v = 0; v < mesh.vertex_count(); v += 7) {
      const Eigen::Vector3d p = mesh.vertices().col(v);
      for (double t : {-1.5, -0.7, 0.4, 1.5}) {
        const Eigen::Vector3d x =
            p + t * edge * shape.Normal(p) + 0.3 * edge * shape.Normal(p).unitOrthogonal();
        error = std::max(error, std::abs(JumpExtension(fit, jumps, x) - (Outer(x) - Inner(x))));
      }
    }
    std::printf("ellipsoid level %d (edge %.3f): max |J - (u+ - u-)| %.3e\n", s, edge, error);
    if (s > 3) {
      EXPECT_GT(std::log2(previous / error), 2.7) << "level " << s;
    }
    previous = error;
  }
}

TEST(LocalSurfaceFit, SignedDistanceOnASphereConvergesAtThirdOrder) {
  double previous = 0;
  for (int s = 3; s <= 5; ++s) {
    const double radius = 0.5;
    const TriangleMesh mesh = IcosphereMesh(s, radius);
    const LocalSurfaceFit fit(mesh, 0.05);
    double error = 0;
    for (int q = 0; q < 400; ++q) {  // points off the surface in many directions
      const Eigen::Vector3d dir =
          Eigen::Vector3d(std::sin(q * 0.37 + 0.1), std::cos(q * 1.13), std::sin(q * 2.71 + 1))
              .normalized();
      const double r = radius + 0.02 * std::sin(q * 0.91);
      const PatchFoot foot = fit.Project(r * dir);
      error = std::max(error, std::abs(foot.signed_distance - (r - radius)));
      EXPECT_NEAR(foot.curvature_sum, 2.0 / radius, 0.2);
    }
    std::printf("icosphere %d: max signed-distance error %.3e\n", s, error);
    if (s > 3) {
      EXPECT_GT(std::log2(previous / error), 2.5) << "subdivisions " << s;
    }
    previous = error;
  }
}

}  // namespace
}  // namespace ehd
