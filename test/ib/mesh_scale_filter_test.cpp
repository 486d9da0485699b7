// Mesh-scale filter of a membrane's deformation (ib/mesh_scale_filter.h): mu_max is the largest
// eigenvalue of the umbrella operator (a bound for every Rayleigh quotient, attained by the
// power iteration's vector), rigid motions and uniform scalings of the reference are left exactly
// as they are, a smooth deformation (an affine stretch, an l = 2 bulge) nearly so, and a
// mesh-scale pattern added to a moved reference is removed.
#include "ehd_capsule/ib/mesh_scale_filter.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace ehd {
namespace {

double MeanEdge(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const auto& e : mesh.edges()) {
    sum += (mesh.vertices().col(e.a) - mesh.vertices().col(e.b)).norm();
  }
  return sum / mesh.edge_count();
}

// The valence-weighted Rayleigh quotient of the umbrella operator.
double Rayleigh(const MeshScaleFilter& f, const TriangleMesh& mesh, const Eigen::Matrix3Xd& x) {
  Eigen::Matrix3Xd ax;
  f.ApplyLaplacian(x, ax);
  double num = 0.0, den = 0.0;
  for (int i = 0; i < x.cols(); ++i) {
    const double w = static_cast<double>(mesh.vertex_edges(i).size());
    num += w * x.col(i).dot(ax.col(i));
    den += w * x.col(i).squaredNorm();
  }
  return num / den;
}

Eigen::Matrix3Xd Pseudorandom(int n, unsigned seed) {
  Eigen::Matrix3Xd x(3, n);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      seed = seed * 1103515245u + 12345u;
      x(a, i) = static_cast<double>(seed >> 8) / 16777216.0 - 0.5;
    }
  }
  return x;
}

TEST(MeshScaleFilter, MuMaxBoundsEveryRayleighQuotient) {
  const TriangleMesh mesh = IcosphereMesh(3, 5.0);
  const MeshScaleFilter f(mesh);
  // A regular triangular lattice has mu_max = 3/2; the icosphere's valence-5 vertices change
  // it a little.
  EXPECT_GT(f.mu_max(), 1.4);
  EXPECT_LE(f.mu_max(), 1.5 + 1e-3);
  for (unsigned seed = 1; seed < 20; ++seed) {
    EXPECT_LE(Rayleigh(f, mesh, Pseudorandom(mesh.vertex_count(), seed)), f.mu_max() + 1e-12);
  }
  EXPECT_DOUBLE_EQ(f.HighPassGain(f.mu_max()), 1.0);
  EXPECT_LT(f.HighPassGain(0.1), 1e-9);
  EXPECT_THROW(MeshScaleFilter(mesh, 0), std::invalid_argument);
}

TEST(MeshScaleFilter, RigidMotionAndUniformScalingAreKept) {
  const TriangleMesh mesh = IcosphereMesh(4, 8.0);
  MeshScaleFilter f(mesh);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  Eigen::Matrix3Xd moved = 1.13 * rotation * mesh.vertices();
  moved.colwise() += Eigen::Vector3d(3.0, -1.0, 2.0);
  Eigen::Matrix3Xd x = moved;
  f.Apply(x);
  EXPECT_LT((x - moved).cwiseAbs().maxCoeff(), 1e-12 * 8.0);
  Eigen::Matrix3Xd wrong(3, 5);
  EXPECT_THROW(f.Apply(wrong), std::invalid_argument);
}

// The plain high-pass X <- X - H X would move the rest icosphere's vertices by a few percent of
// an edge (its own mesh-scale content); relative to the reference, a smooth deformation keeps
// all but a small fraction of the reference's mesh-scale content times the strain.
TEST(MeshScaleFilter, SmoothDeformationsAreKept) {
  const TriangleMesh mesh = IcosphereMesh(4, 8.0);
  const double edge = MeanEdge(mesh);
  MeshScaleFilter f(mesh);
  Eigen::Matrix3Xd high;
  f.HighPass(mesh.vertices(), high);
  const double rest_content = high.colwise().norm().maxCoeff();
  EXPECT_GT(rest_content, 0.01 * edge) << "the rest mesh has mesh-scale content of its own";

  // An affine stretch (strain 0.2) and an l = 2 bulge of 10 % of the radius.
  const Eigen::Matrix3d stretch = Eigen::Vector3d(1.2, 0.9, 0.95).asDiagonal();
  Eigen::Matrix3Xd deformed = stretch * mesh.vertices();
  for (int i = 0; i < deformed.cols(); ++i) {
    const Eigen::Vector3d r = mesh.vertices().col(i).normalized();
    deformed.col(i) += 0.8 * (3.0 * r.z() * r.z() - 1.0) * r;
  }
  Eigen::Matrix3Xd x = deformed;
  f.Apply(x);
  const double moved = (x - deformed).colwise().norm().maxCoeff();
  EXPECT_LT(moved, 0.1 * rest_content) << "moved " << moved / edge << " edges";
}

TEST(MeshScaleFilter, MeshScalePatternOnAMovedReferenceIsRemoved) {
  const TriangleMesh mesh = IcosphereMesh(4, 8.0);
  const double edge = MeanEdge(mesh);
  MeshScaleFilter f(mesh);
  // The top eigenvector (power iteration) and a random pattern, 5 % of an edge.
  Eigen::Matrix3Xd top = Pseudorandom(mesh.vertex_count(), 7), next;
  for (int it = 0; it < 3000; ++it) {
    f.ApplyLaplacian(top, next);
    top = next / next.norm();
  }
  EXPECT_NEAR(Rayleigh(f, mesh, top), f.mu_max(), 1e-4);  // a cluster at the top: slow
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, 1.0, -0.4).normalized()).toRotationMatrix();
  const Eigen::Matrix3Xd moved = rotation * mesh.vertices();
  // The top mode is removed entirely; of a random pattern, the part the high-pass sees (the
  // modes near mu_max) down to a floor (the pattern also perturbs the local maps M_i, by its
  // amplitude over an edge, which times the rest mesh's own mesh-scale content H X_0 is 1e-3 of
  // an edge here), while its smooth part is a smooth deformation and stays.
  for (const bool is_top : {true, false}) {
    const Eigen::Matrix3Xd pattern = is_top ? top : Pseudorandom(mesh.vertex_count(), 3);
    const Eigen::Matrix3Xd noise = 0.05 * edge * pattern / pattern.colwise().norm().maxCoeff();
    Eigen::Matrix3Xd x = moved + noise;
    // A few passes, as a run applies it every n steps.
    for (int pass = 0; pass < 5; ++pass) f.Apply(x);
    Eigen::Matrix3Xd high_before, high_after;
    f.HighPass(noise, high_before);
    f.HighPass(x - moved, high_after);
    EXPECT_LT(high_after.norm(), (is_top ? 0.01 : 0.15) * high_before.norm())
        << (is_top ? "top mode" : "random");
    if (is_top) {
      EXPECT_LT((x - moved).colwise().norm().maxCoeff(), 0.01 * noise.colwise().norm().maxCoeff());
    }
  }
}

}  // namespace
}  // namespace ehd
