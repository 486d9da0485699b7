// 3D fast immersed interface method (electric/fast_iim_solver_3d.h) against exact solutions:
// a sphere in a uniform field (the leaky-dielectric conduction problem, [phi] = 0, [sigma phi_n]
// = 0) at conductivity ratios sigma^-/sigma^+ = 0.1, 0.5, 2, 10 and 1000, a general problem on an
// ellipsoid ([phi], [sigma phi_n] and f all non-zero) at 1/10, 10 and 1000 and on the non-convex
// red-cell surface (reference/interface_examples_3d.h). The potential and [phi_n] at the vertices
// must converge at second order, and so must the Maxwell traction at the vertices and the grid
// field E = -grad phi (observed orders printed). Above sigma^-/sigma^+ = 10 the solver seeks
// [phi_n] in a spherical-harmonic basis with the flux balance deflated; without it GMRES stalls at
// 1000:1; the basis works on any triangulation of a star-shaped surface. Refusals (a ratio above
// max_inner_ratio, an icosphere below level 2 or another mesh not star-shaped about its centroid,
// a source without its interior integral, an unresolved curvature, a surface within 1 h of a box
// face, a coarse mesh, a dimple thinner than h, an unresolved potential) are checked by name.
#include "ehd_capsule/electric/fast_iim_solver_3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ehd_capsule/reference/interface_examples_3d.h"
#include "support/interface_case.h"

namespace ehd {
namespace {

struct Errors {
  double phi = 0, g = 0, dn_plus = 0, traction = 0, traction_scale = 0, grid_field = 0;
  int iterations = 0;
};

// Max |phi - exact| over the grid's nodes; exact(p, outside) is the exact potential on the side
// the solver classified the node on.
double MaxNodeError(const Grid3D& grid, const FastIimSolver3D& solver,
                    const std::vector<double>& phi,
                    const std::function<double(const Eigen::Vector3d&, bool outside)>& exact) {
  double err = 0;
  for (int k = 0; k < grid.nz; ++k)
    for (int j = 0; j < grid.ny; ++j)
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t c = grid.index(i, j, k);
        const Eigen::Vector3d p(grid.x(i), grid.y(j), grid.z(k));
        err = std::max(err, std::abs(phi[c] - exact(p, solver.classification().side[c] > 0)));
      }
  return err;
}

// Sphere of radius R in E along z: phi^- = -A E z, phi^+ = -E z + B E R^3 z / r^3,
// A = 3 s^+/(s^- + 2 s^+), B = (s^- - s^+)/(s^- + 2 s^+).
Errors SphereInField(int n, int subdivisions, double sigma_minus, double sigma_plus) {
  const double radius = 0.5, e = 1.0;
  const double a = 3 * sigma_plus / (sigma_minus + 2 * sigma_plus);
  const double b = (sigma_minus - sigma_plus) / (sigma_minus + 2 * sigma_plus);
  const auto outer = [&](double x, double y, double z) {
    const double r = std::sqrt(x * x + y * y + z * z);
    return -e * z + b * e * std::pow(radius, 3) * z / (r * r * r);
  };
  const auto outer_gradient = [&](double x, double y, double z) -> Eigen::Vector3d {
    const Eigen::Vector3d p(x, y, z);
    const double r = p.norm(), r3 = std::pow(radius, 3);
    return Eigen::Vector3d(0, 0, -e) +
           b * e * r3 * (Eigen::Vector3d(0, 0, 1) / std::pow(r, 3) - 3 * z * p / std::pow(r, 5));
  };
  const double h = 2.0 / n;
  const Grid3D grid{n, n, n, h, -1, -1, -1};
  PoissonBoundaries3D bc;
  bc.x_min = bc.x_max = bc.y_min = bc.y_max = BoundaryKind::kNeumann;  // ch. 6's box
  FastIimSolver3D solver(grid, bc);
  const TriangleMesh mesh = IcosphereMesh(subdivisions, radius);
  InterfaceProblem3D problem;
  problem.sigma_minus = sigma_minus;
  problem.sigma_plus = sigma_plus;
  problem.boundary = SampleBoundaryData(grid, bc, outer, outer_gradient);
  std::vector<double> g, phi;
  const InterfaceSolveReport report = solver.Solve(mesh, problem, g, phi);
  Errors out;
  out.iterations = report.iterations;
  out.phi = MaxNodeError(grid, solver, phi, [&](const Eigen::Vector3d& p, bool outside) {
    return outside ? outer(p.x(), p.y(), p.z()) : -a * e * p.z();
  });
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d p = mesh.vertices().col(v);
    const double cos_theta = p.z() / p.norm();
    const double dn_minus = -a * e * cos_theta;
    const double dn_plus = -e * cos_theta * (1 + 2 * b);
    out.g = std::max(out.g, std::abs(g[v] - (dn_plus - dn_minus)));
    out.dn_plus = std::max(out.dn_plus, std::abs(solver.normal_derivative_plus()[v] - dn_plus));
  }
  // Maxwell traction with eps^- = 3.5, eps^+ = 1 (song2019 ch. 6's ratio) against the exact
  // fields E^- = A E z_hat and E^+ = -grad phi^+ at the vertices.
  const double eps_minus = 3.5, eps_plus = 1.0;
  std::vector<double> en_minus(mesh.vertex_count()), en_plus(mesh.vertex_count());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    en_minus[v] = -solver.normal_derivative_minus()[v];
    en_plus[v] = -solver.normal_derivative_plus()[v];
  }
  const Eigen::Matrix3Xd traction =
      MaxwellTraction3D(solver.normals(), eps_minus, eps_plus, en_minus, en_plus,
                        -solver.tangential_gradient_minus(), -solver.tangential_gradient_plus());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d p = mesh.vertices().col(v), n = p.normalized();
    const Eigen::Vector3d e_minus(0, 0, a * e), e_plus = -outer_gradient(p.x(), p.y(), p.z());
    const auto normal_and_tangent = [&](const Eigen::Vector3d& field, double& fn,
                                        Eigen::Vector3d& ft) {
      fn = field.dot(n);
      ft = field - fn * n;
    };
    double fn_minus, fn_plus;
    Eigen::Vector3d ft_minus, ft_plus;
    normal_and_tangent(e_minus, fn_minus, ft_minus);
    normal_and_tangent(e_plus, fn_plus, ft_plus);
    const Eigen::Vector3d exact = 0.5 *
                                      (eps_plus * (fn_plus * fn_plus - ft_plus.squaredNorm()) -
                                       eps_minus * (fn_minus * fn_minus - ft_minus.squaredNorm())) *
                                      n +
                                  eps_plus * fn_plus * ft_plus - eps_minus * fn_minus * ft_minus;
    out.traction = std::max(out.traction, (traction.col(v) - exact).norm());
    out.traction_scale = std::max(out.traction_scale, exact.norm());
  }
  std::vector<double> ex, ey, ez;
  solver.GridField(phi, ex, ey, ez);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = grid.index(i, j, k);
        const double x = grid.x(i), y = grid.y(j), z = grid.z(k);
        const Eigen::Vector3d exact = solver.classification().side[c] > 0
                                          ? Eigen::Vector3d(-outer_gradient(x, y, z))
                                          : Eigen::Vector3d(0, 0, a * e);
        out.grid_field =
            std::max(out.grid_field, (Eigen::Vector3d(ex[c], ey[c], ez[c]) - exact).norm());
      }
  return out;
}

void ExpectSecondOrderSphere(double sigma_minus, double sigma_plus) {
  const int grids[3] = {20, 40, 80}, subdivisions[3] = {3, 4, 5};
  Errors e[3];
  for (int r = 0; r < 3; ++r) {
    e[r] = SphereInField(grids[r], subdivisions[r], sigma_minus, sigma_plus);
    std::printf(
        "sigma-/sigma+ = %g  n = %d  phi %.2e  [phi_n] %.2e  phi_n+ %.2e  traction %.2e (of %.2f)"
        "  grid E %.2e  (%d its)\n",
        sigma_minus / sigma_plus, grids[r], e[r].phi, e[r].g, e[r].dn_plus, e[r].traction,
        e[r].traction_scale, e[r].grid_field, e[r].iterations);
  }
  const double order_phi = std::log2(e[1].phi / e[2].phi);
  const double order_g = std::log2(e[1].g / e[2].g);
  const double order_traction = std::log2(e[1].traction / e[2].traction);
  const double order_field = std::log2(e[1].grid_field / e[2].grid_field);
  std::printf("  orders 40 -> 80: phi %.2f  [phi_n] %.2f  traction %.2f  grid E %.2f\n", order_phi,
              order_g, order_traction, order_field);
  EXPECT_GT(order_phi, 1.6);
  EXPECT_GT(order_g, 1.8);
  EXPECT_GT(order_traction, 1.6);
  EXPECT_GT(order_field, 1.5);
  EXPECT_LT(e[2].phi, 2e-3);
}

TEST(FastIimSolver3D, SphereInAFieldLessConductingInside) { ExpectSecondOrderSphere(0.1, 1.0); }
TEST(FastIimSolver3D, SphereInAFieldHalfConducting) { ExpectSecondOrderSphere(0.5, 1.0); }
TEST(FastIimSolver3D, SphereInAFieldMoreConductingInside) { ExpectSecondOrderSphere(2.0, 1.0); }
TEST(FastIimSolver3D, SphereInAFieldTenTimesMoreConductingInside) {
  ExpectSecondOrderSphere(10.0, 1.0);
}
TEST(FastIimSolver3D, SphereInAFieldThousandTimesMoreConductingInside) {
  ExpectSecondOrderSphere(1000.0, 1.0);
}

// A shared example (reference/interface_examples_3d.h) on N^3: max errors of phi over the nodes
// and of [phi_n] at the vertices.
Errors SharedExample(const std::string& name, int n, double sigma_minus, double sigma_plus) {
  const test::InterfaceCase3D c(name, n, sigma_minus, sigma_plus);
  FastIimSolver3D solver(c.grid, c.example.boundaries);
  std::vector<double> g, phi;
  const InterfaceSolveReport report = solver.Solve(c.mesh, c.problem, g, phi);
  Errors out;
  out.iterations = report.iterations;
  out.phi = c.MaxNodeError(solver, phi);
  out.g = c.MaxJumpError(g);
  return out;
}

// The ellipsoid with [phi], [sigma phi_n] and f non-zero, at sigma^-/sigma^+ = 1/10, 10 and 1000
// (the last in the harmonic basis, with the flux balance's high-order radial quadrature).
TEST(FastIimSolver3D, GeneralProblemOnAnEllipsoid) {
  for (const double ratio : {0.1, 10.0, 1000.0}) {
    const int grids[3] = {24, 48, 96};
    Errors e[3];
    for (int r = 0; r < 3; ++r) {
      e[r] = SharedExample("ellipsoid", grids[r], ratio, 1.0);
      std::printf("ellipsoid sigma-/sigma+ = %g  n = %d  phi %.2e  [phi_n] %.2e  (%d its)\n", ratio,
                  grids[r], e[r].phi, e[r].g, e[r].iterations);
    }
    const double order_phi = std::log2(e[1].phi / e[2].phi);
    const double order_g = std::log2(e[1].g / e[2].g);
    std::printf("  orders 48 -> 96: phi %.2f  [phi_n] %.2f\n", order_phi, order_g);
    EXPECT_GT(order_phi, 1.7) << ratio;
    EXPECT_GT(order_g, 1.7) << ratio;
    EXPECT_LE(e[2].iterations, 30) << ratio;
  }
}

// The non-convex red-cell surface: resolved from N = 24 (dimple 1.6 h thick), errors falling.
TEST(FastIimSolver3D, BiconcaveCell) {
  const Errors coarse = SharedExample("biconcave", 24, 1.0, 10.0);
  const Errors fine = SharedExample("biconcave", 48, 1.0, 10.0);
  std::printf("biconcave: phi %.2e -> %.2e, [phi_n] %.2e -> %.2e\n", coarse.phi, fine.phi, coarse.g,
              fine.g);
  EXPECT_LT(fine.phi, 2e-3);
  EXPECT_LT(fine.g, 2e-2);
  EXPECT_GT(std::log2(coarse.phi / fine.phi), 1.7);
}

// A dimple thinner than h (c0 = 0.05: 0.03 thick on h = 0.0625) is refused, naming the
// resolution it needs; so is the shipped cell's on N = 16, where the grid does not resolve the
// potential near the dimple (the cubic/quadratic fit check).
TEST(FastIimSolver3D, RefusesADimpleThinnerThanTheGrid) {
  InterfaceExample3D e = MakeInterfaceExample3D("biconcave", 1.0, 10.0);
  BiconcaveParameters thin;
  thin.radius = 0.45;
  thin.c0 = 0.05;
  const Grid3D grid = e.MakeGrid(32);
  const TriangleMesh mesh = BiconcaveMesh(4, thin);
  FastIimSolver3D solver(grid, e.boundaries);
  InterfaceProblem3D problem;
  problem.sigma_plus = 10;
  problem.boundary = SampleBoundaryData(
      grid, e.boundaries, [](double, double, double) { return 0.0; },
      [](double, double, double) { return Eigen::Vector3d(0, 0, 0); });
  std::vector<double> g, phi;
  try {
    solver.Solve(mesh, problem, g, phi);
    FAIL() << "a dimple 0.5 h thick was accepted";
  } catch (const SolverError& err) {
    EXPECT_NE(std::string(err.what()).find("thinner than the grid spacing"), std::string::npos)
        << err.what();
  }
  try {
    SharedExample("biconcave", 16, 1.0, 10.0);
    FAIL() << "the cell on N = 16 was accepted";
  } catch (const SolverError& err) {
    EXPECT_NE(std::string(err.what()).find("max_fit_disagreement"), std::string::npos)
        << err.what();
  }
}

// The need for the basis: at 1000:1 GMRES on the vertex values of [phi_n] stalls (the near-null
// modes' eigenvalues, about -1/999, are below the discretisation error of phi_n^-), and the
// solver says so instead of returning its iterate.
TEST(FastIimSolver3D, VertexValuesStallAtThousandToOne) {
  const test::InterfaceCase3D c("ellipsoid", 32, 1000.0, 1.0);
  const Grid3D& grid = c.grid;
  const TriangleMesh& mesh = c.mesh;
  const InterfaceExample3D& e = c.example;
  const InterfaceProblem3D& problem = c.problem;
  FastIim3DOptions options;
  options.basis_min_ratio = 1e4;  // vertex values
  options.gmres.max_iterations = 200;
  FastIimSolver3D solver(grid, e.boundaries, options);
  std::vector<double> g, phi;
  try {
    solver.Solve(mesh, problem, g, phi);
    FAIL() << "GMRES on the vertex values converged at 1000:1";
  } catch (const SolverError& err) {
    EXPECT_NE(std::string(err.what()).find("did not converge"), std::string::npos) << err.what();
  }
  FastIimSolver3D basis_solver(grid, e.boundaries);
  g.clear();
  const InterfaceSolveReport report = basis_solver.Solve(mesh, problem, g, phi);
  EXPECT_LE(report.iterations, 30);
  EXPECT_GE(basis_solver.harmonic_degree(), 8);
  EXPECT_LT(basis_solver.flux_balance_error(), 1e-3);
}

// The harmonic basis needs no particular mesh generator: the ellipsoid of
// GeneralProblemOnAnEllipsoid at 1000:1 ([phi], [sigma phi_n] and f non-zero, so the flux balance's
// quadrature matters), its vertices renumbered and each triangle's list rotated, and an
// octahedron-based triangulation of the same ellipsoid (valences 4 and 6), must
// match the exact solution as the icosphere mesh does: the same errors to within 20 %. The
// icosphere keeps the icosphere parametrisation and extrapolated weights; the other two (a
// renumbered icosphere is not of icosphere connectivity by its triangle list) take the radial
// parametrisation and its quadrature.
TriangleMesh Relabelled(const TriangleMesh& mesh) {
  const int nv = mesh.vertex_count();
  std::vector<int> order(nv);
  for (int i = 0; i < nv; ++i) order[i] = (i * 7919 + 13) % nv;  // 7919 prime, nv = 10 4^k + 2
  Eigen::Matrix3Xd x(3, nv);
  for (int i = 0; i < nv; ++i) x.col(order[i]) = mesh.vertices().col(i);
  std::vector<TriangleMesh::Triangle> triangles;
  const auto& old = mesh.triangles();
  for (std::size_t t = 0; t < old.size(); ++t) {
    const auto& tri = old[(t * 101) % old.size()];  // 101 prime, 20 4^k triangles
    const int r = static_cast<int>(t % 3);
    triangles.push_back({order[tri[r]], order[tri[(r + 1) % 3]], order[tri[(r + 2) % 3]]});
  }
  return TriangleMesh(x, triangles);
}

// The octahedron with each triangle cut into four at its edge midpoints k times (valences 4 and
// 6: not an icosphere's), each vertex moved along its direction onto the ellipsoid
// x^2/a^2 + y^2/b^2 + z^2/c^2 = 1.
TriangleMesh OctasphereEllipsoid(int k, double a, double b, double c) {
  std::vector<Eigen::Vector3d> points = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                         {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  std::vector<TriangleMesh::Triangle> triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < k; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto middle = [&](int i, int j) {
      const auto key = std::make_pair(std::min(i, j), std::max(i, j));
      const auto found = midpoint.find(key);
      if (found != midpoint.end()) return found->second;
      points.push_back((points[i] + points[j]).normalized());
      return midpoint[key] = static_cast<int>(points.size()) - 1;
    };
    std::vector<TriangleMesh::Triangle> finer;
    for (const auto& t : triangles) {
      const int ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({t[1], bc, ab});
      finer.push_back({t[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    triangles = finer;
  }
  Eigen::Matrix3Xd x(3, points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d d = points[i].normalized();
    const double s = 1.0 / std::sqrt(d.x() * d.x() / (a * a) + d.y() * d.y() / (b * b) +
                                     d.z() * d.z() / (c * c));
    x.col(i) = s * d;
  }
  return TriangleMesh(x, triangles);
}

TEST(FastIimSolver3D, HarmonicBasisOnAnyTriangulation) {
  const InterfaceExample3D e = MakeInterfaceExample3D("ellipsoid", 1000.0, 1.0);
  const int n = 32;
  const test::InterfaceCase3D reference("ellipsoid", n, 1000.0, 1.0);
  const TriangleMesh octasphere = OctasphereEllipsoid(5, 0.6, 0.45, 0.35);  // 4098 vertices
  ASSERT_EQ(octasphere.EulerCharacteristic(), 2);
  const TriangleMesh meshes[3] = {reference.mesh, Relabelled(reference.mesh), octasphere};
  const char* names[3] = {"icosphere", "relabelled", "octasphere"};
  Errors err[3];
  for (int m = 0; m < 3; ++m) {
    const test::InterfaceCase3D c(e, n, meshes[m]);
    FastIimSolver3D solver(c.grid, c.example.boundaries);
    std::vector<double> g, phi;
    const InterfaceSolveReport report = solver.Solve(c.mesh, c.problem, g, phi);
    err[m].phi = c.MaxNodeError(solver, phi);
    err[m].g = c.MaxJumpError(g);
    err[m].iterations = report.iterations;
    std::printf("%-12s %5d vertices: phi %.2e  [phi_n] %.2e  (%d its, L = %d, flux err %.1e)\n",
                names[m], c.mesh.vertex_count(), err[m].phi, err[m].g, report.iterations,
                solver.harmonic_degree(), solver.flux_balance_error());
    EXPECT_GE(solver.harmonic_degree(), 2) << names[m];
    EXPECT_LE(report.iterations, 30) << names[m];
  }
  for (int m = 1; m < 3; ++m) {
    EXPECT_LT(err[m].phi, 1.2 * err[0].phi) << names[m];
    EXPECT_LT(err[m].g, 1.2 * err[0].g) << names[m];
  }
}

TEST(FastIimSolver3D, RefusesWhatItCannotTrust) {
  const Grid3D grid{20, 20, 20, 0.1, -1, -1, -1};
  FastIimSolver3D solver(grid, PoissonBoundaries3D{});
  std::vector<double> g, phi;
  InterfaceProblem3D problem;
  problem.sigma_minus = 2000;
  try {
    solver.Solve(IcosphereMesh(3, 0.5), problem, g, phi);
    FAIL() << "a ratio of 2000 was accepted";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("max_inner_ratio"), std::string::npos) << e.what();
  }
  // Above 10 the harmonic basis of a mesh not of icosphere connectivity lives on the directions
  // from the centroid: a surface that is not star-shaped about it (an ellipsoid bent into a C and
  // renumbered, whose centroid lies in the C's opening, so the inner side of the C is seen from
  // behind) is refused, naming the problem. An icosphere below level 2 is refused as before.
  problem.sigma_minus = 100;
  try {
    solver.Solve(IcosphereMesh(1, 0.5), problem, g, phi);
    FAIL() << "an icosphere of level 1 was accepted at 100:1";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("coarser"), std::string::npos) << e.what();
  }
  {
    TriangleMesh bent = EllipsoidMesh(3, 0.8, 0.2, 0.2);
    Eigen::Matrix3Xd x = bent.vertices();
    const double bend_radius = 0.35;
    for (int i = 0; i < x.cols(); ++i) {
      const double angle = x(0, i) / bend_radius, rho = bend_radius + x(1, i);
      x(0, i) = rho * std::sin(angle);
      x(1, i) = rho * std::cos(angle) - bend_radius;
    }
    try {
      solver.Solve(Relabelled(TriangleMesh(x, bent.triangles())), problem, g, phi);
      FAIL() << "a surface that is not star-shaped was accepted at 100:1";
    } catch (const SolverError& e) {
      EXPECT_NE(std::string(e.what()).find("not star-shaped"), std::string::npos) << e.what();
    }
  }
  {
    const TriangleMesh sphere = IcosphereMesh(3, 0.5);
    // A source without the integral the flux balance needs.
    InterfaceProblem3D with_source = problem;
    with_source.f.assign(grid.size(), 1.0);
    with_source.f_over_sigma_jump.assign(sphere.vertex_count(), 0.0);
    EXPECT_THROW(solver.Solve(sphere, with_source, g, phi), std::invalid_argument);
  }
  problem.sigma_minus = 1;
  problem.sigma_plus = 2;
  try {  // radius 0.15 = 1.5 h: kappa h = 0.67 passes; radius 0.08: kappa h = 1.25 refused
    solver.Solve(IcosphereMesh(2, 0.08), problem, g, phi);
    FAIL() << "a sphere of radius 0.8 h was accepted";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("max_curvature_h"), std::string::npos) << e.what();
  }
  try {
    solver.Solve(IcosphereMesh(1, 0.7), problem, g, phi);
    FAIL() << "a 42-vertex mesh on a 20^3 grid was accepted";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("max_edge_h"), std::string::npos) << e.what();
  }
}

// The "sphere" example's phi without its interior source term (both sides smooth everywhere, so
// the sphere may move), Neumann x faces (the ch. 6 box), the sphere shifted along x until it is
// d h from the face x = 1 on N = 32: the max error of phi, or -1 when refused (*refusal).
double ErrorNearTheFace(double d, double min_face_distance_h, std::string* refusal) {
  InterfaceExample3D e = MakeInterfaceExample3D("sphere", 1.0, 2.0);
  e.phi_plus = [](const Eigen::Vector3d& p) {
    return p.x() * p.y() + p.z() + 0.5 * (p.x() * p.x() - p.z() * p.z());
  };
  e.grad_plus = [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p.y() + p.x(), p.x(), 1.0 - p.z());
  };
  e.boundaries.x_min = e.boundaries.x_max = BoundaryKind::kNeumann;
  const int n = 32;
  const Grid3D grid = e.MakeGrid(n);
  TriangleMesh mesh = e.MeshFor(grid.h);
  const Eigen::Vector3d centre(1.0 - d * grid.h - 0.5, 0, 0);
  mesh.SetVertices(mesh.vertices().colwise() + centre);
  e.normal = [centre](const Eigen::Vector3d& p) {
    return Eigen::Vector3d((p - centre).normalized());
  };
  FastIim3DOptions options;
  options.min_face_distance_h = min_face_distance_h;
  const test::InterfaceCase3D c(e, n, mesh);
  FastIimSolver3D solver(grid, e.boundaries, options);
  std::vector<double> g, phi;
  try {
    solver.Solve(mesh, c.problem, g, phi);
  } catch (const SolverError& err) {
    if (refusal) *refusal = err.what();
    return -1.0;
  }
  return c.MaxNodeError(solver, phi);
}

TEST(FastIimSolver3D, SurfaceNearABoxFaceIsAccurateOrRefused) {
  // Measured without the check: 5.2e-4 at 6 h, 5.8e-4 at 2 h, 6.0e-4 at 1 h, 5.3e-4 at 0.5 h;
  // at 0.3 h (the surface between the last node layer and the Neumann face) 0.15, accepted, on an
  // Intel Xeon; on an AMD EPYC (same code, -march=native) the fit-agreement check refuses it
  // instead (cubic and quadratic fits of phi_n^- 0.61 apart). Either way no accurate answer
  // exists there: without the face check it is O(1) wrong or refused by chance of another check.
  const double far = ErrorNearTheFace(6.0, 0.0, nullptr);
  EXPECT_LT(far, 1e-3);
  const double unchecked = ErrorNearTheFace(0.3, 0.0, nullptr);
  EXPECT_TRUE(unchecked == -1.0 || unchecked > 0.05) << unchecked;  // why the check exists
  EXPECT_LT(ErrorNearTheFace(1.25, FastIim3DOptions().min_face_distance_h, nullptr), 2.0 * far);
  std::string refusal;
  EXPECT_EQ(ErrorNearTheFace(0.75, FastIim3DOptions().min_face_distance_h, &refusal), -1.0);
  EXPECT_NE(refusal.find("min_face_distance_h"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("face x = 1"), std::string::npos) << refusal;
}

}  // namespace
}  // namespace ehd
