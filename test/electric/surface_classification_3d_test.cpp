// Inside/outside classification of grid nodes against triangulated surfaces
// (electric/surface_classification_3d.h): against the analytic inside test of the sphere and of
// the non-convex biconcave cell, with grid columns through mesh vertices (the icosphere's poles)
// and along shared edges; the irregular nodes are exactly those with a neighbour across.
#include "ehd_capsule/electric/surface_classification_3d.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ehd {
namespace {

Grid3D CenteredGrid(int n, double half) {  // n odd: a column through x = y = 0
  const double h = 2.0 * half / n;
  return Grid3D{n, n, n, h, -half, -half, -half};
}

TEST(SurfaceClassification3D, SphereMatchesTheAnalyticInsideTestOffTheSurface) {
  const Grid3D g = CenteredGrid(41, 1.0);
  for (int k : {2, 3, 4}) {
    const double r = 0.77;
    const TriangleMesh sphere = IcosphereMesh(k, r);  // vertices at (0, 0, +-r): on a column
    const SurfaceClassification3D c = ClassifyNodes(g, sphere);
    // The mesh is inscribed: between it and the sphere lies a shell of depth <= the sagitta.
    const double edge = MeasureQuality(sphere).max_edge;
    const double sagitta = edge * edge / (4.0 * r);
    long mismatches = 0, checked = 0;
    for (int kk = 0; kk < g.nz; ++kk)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
          const double d = std::sqrt(g.x(i) * g.x(i) + g.y(j) * g.y(j) + g.z(kk) * g.z(kk)) - r;
          const int side = c.side[g.index(i, j, kk)];
          if (std::abs(d) > sagitta) {
            ++checked;
            if (side != (d < 0 ? -1 : 1)) ++mismatches;
          } else {
            EXPECT_TRUE(side == 1 || d < 0);  // inside the mesh implies inside the sphere
          }
        }
    EXPECT_EQ(mismatches, 0) << "k " << k;
    EXPECT_GT(checked, g.size() / 2);
    // The column through the poles (x = y = 0) is inside exactly between them.
    for (int kk = 0; kk < g.nz; ++kk) {
      EXPECT_EQ(c.side[g.index(20, 20, kk)], std::abs(g.z(kk)) < r ? -1 : 1) << kk;
    }
  }
}

TEST(SurfaceClassification3D, BiconcaveCellIsClassifiedThroughItsDimple) {
  // Symmetry axis y, columns along z: near the axis a column stays outside above and below the
  // thin centre only within its half-thickness; the rim region within a mesh edge is skipped.
  BiconcaveParameters p;
  p.radius = 0.6;
  const TriangleMesh cell = BiconcaveMesh(5, p);
  const Grid3D g = CenteredGrid(51, 1.0);
  const SurfaceClassification3D c = ClassifyNodes(g, cell);
  const double big_r = p.radius * p.alpha;
  const double edge = MeasureQuality(cell).max_edge;
  long mismatches = 0, checked = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const double r = std::hypot(g.x(i), g.z(k)), y = g.y(j);
        if (r >= big_r + edge) {
          ++checked;
          mismatches += c.side[g.index(i, j, k)] != 1;
          continue;
        }
        if (r >= big_r - edge) continue;  // the rim: within a mesh edge of the surface
        const double s2 = r * r / (big_r * big_r);
        const double half = 0.5 * big_r * (p.c0 + p.c1 * s2 + p.c2 * s2 * s2) * std::sqrt(1 - s2);
        if (std::abs(std::abs(y) - half) < edge) continue;
        ++checked;
        mismatches += c.side[g.index(i, j, k)] != (std::abs(y) < half ? -1 : 1);
      }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(c.inside_count, 0);
  // Volume check: inside nodes times h^3 against the exact volume, within a surface layer.
  const double volume = c.inside_count * std::pow(g.h, 3);
  EXPECT_NEAR(volume, BiconcaveVolume(p), 0.08 * BiconcaveVolume(p));
  EXPECT_GT(checked, g.size() / 2);
}

TEST(SurfaceClassification3D, IrregularNodesHaveANeighbourAcross) {
  const Grid3D g = CenteredGrid(21, 1.0);
  const SurfaceClassification3D c = ClassifyNodes(g, EllipsoidMesh(3, 0.7, 0.5, 0.6));
  long count = 0;
  for (int k = 1; k < g.nz - 1; ++k)
    for (int j = 1; j < g.ny - 1; ++j)
      for (int i = 1; i < g.nx - 1; ++i) {
        const std::size_t n = g.index(i, j, k);
        const bool across = c.side[g.index(i - 1, j, k)] != c.side[n] ||
                            c.side[g.index(i + 1, j, k)] != c.side[n] ||
                            c.side[g.index(i, j - 1, k)] != c.side[n] ||
                            c.side[g.index(i, j + 1, k)] != c.side[n] ||
                            c.side[g.index(i, j, k - 1)] != c.side[n] ||
                            c.side[g.index(i, j, k + 1)] != c.side[n];
        EXPECT_EQ(c.irregular[n] != 0, across);
        count += across;
      }
  EXPECT_EQ(count, c.irregular_count);
  EXPECT_GT(count, 0);
  EXPECT_THROW(ClassifyNodes(g, IcosphereMesh(2, 1.5)), std::invalid_argument);
}

}  // namespace
}  // namespace ehd
