// 3D leaky-dielectric solver (electric/leaky_dielectric_solver.h, D = 3): a sphere of radius 0.3 in
// the box [-1, 1]^3 (phi = E z on the z faces, Neumann x and y faces) against the free-space
// solution of a leaky-dielectric sphere in a uniform field (song2019 ch. 6's case A ratios
// sigma^-/sigma^+ = 1.75, eps^-/eps^+ = 3.5): the Maxwell traction at the vertices within 5 % of
// the largest (the box's image dipoles are about (R/L)^3 = 3 %), the net force zero by symmetry,
// the force per vertex the traction times the vertex area, the field scaling (traction ~ E^2,
// warm start from the rescaled G).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/reference/interface_examples_3d.h"

namespace ehd {
namespace {

TEST(LeakyDielectricSolver3D, SphereInAUniformFieldMatchesTheFreeSpaceTraction) {
  const int n = 48;
  const Grid3D grid{n, n, n, 2.0 / n, -1, -1, -1};
  const double sm = 1.75, sp = 1.0, em = 3.5, ep = 1.0, radius = 0.3, e = 1.0;
  LeakyDielectricSolver<3> solver(grid, sm, sp, em, ep);
  solver.SetAppliedField(e);  // phi = E z on the z faces: E_inf = (0, 0, -E)
  const TriangleMesh mesh = IcosphereMesh(4, radius);
  const InterfaceSolveReport report = solver.Solve(mesh, 0.0);
  EXPECT_TRUE(report.converged);
  // Free space (reference/interface_examples_3d.h).
  double worst = 0, scale = 0;
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d exact =
        FreeSpaceSphereTraction(mesh.vertices().col(v), radius, e, sm, sp, em, ep);
    worst = std::max(worst, (solver.traction().col(v) - exact).norm());
    scale = std::max(scale, exact.norm());
    total += solver.force().col(v);
  }
  std::printf(
      "traction: max error %.3e of %.3e; net force (%.2e, %.2e, %.2e); %d iterations, "
      "%.0f ms\n",
      worst, scale, total.x(), total.y(), total.z(), report.iterations, report.solve_ms);
  EXPECT_LT(worst, 0.05 * scale);
  // Net force: zero by symmetry (the mesh is symmetric under z -> -z), against the force scale.
  double force_scale = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) force_scale += solver.force().col(v).norm();
  EXPECT_LT(total.norm(), 1e-3 * force_scale);
  // Force = traction x vertex area.
  const SurfaceGeometry geometry = MeasureSurface(mesh);
  for (int v = 0; v < mesh.vertex_count(); v += 97) {
    EXPECT_NEAR((solver.force().col(v) - solver.traction().col(v) * geometry.vertex_area[v]).norm(),
                0.0, 1e-14);
  }
  // Doubling E: four times the traction; the rescaled G starts GMRES at the answer.
  const Eigen::Matrix3Xd before = solver.traction();
  solver.SetAppliedField(2 * e);
  const InterfaceSolveReport doubled = solver.Solve(mesh, 1.0);
  EXPECT_LT((solver.traction() - 4 * before).norm(), 1e-6 * before.norm());
  EXPECT_LE(doubled.iterations, 1);
  EXPECT_GT(report.iterations, doubled.iterations);
}

TEST(LeakyDielectricSolver3D, RejectsNonPositiveProperties) {
  const Grid3D grid{16, 16, 16, 0.125, -1, -1, -1};
  EXPECT_THROW(LeakyDielectricSolver<3>(grid, 0.0, 1, 1, 1), std::invalid_argument);
  EXPECT_THROW(LeakyDielectricSolver<3>(grid, 1, 1, 1, -2), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
