// `ehd_sim eforce`: convergence of the interfacial electric force (song2019 sec. 4.2.1,
// Table 10). Drop of radius 1 at the centre of [-4, 4]^2, E_inf = (0, -1) (phi = y on y = +-4,
// dphi/dx = 0 on x = +-4), sigma_r = sigma^-/sigma^+ = 3, eps_r = eps^-/eps^+ = 2, M markers on
// an N = M grid (so the marker spacing 2 pi / M < h = 8 / N as sec. 4.2 requires). The force of
// M = 32..256 is compared with M = 512 at the shared marker angles theta_k = 2 pi k / M.
//
// `ehd_sim eforce --dim 3`: the same in 3D (song2019 ch. 6's box and sec. 3.5): a sphere of
// radius 1 (icosphere level 4, 2562 vertices, the same vertices on every grid) at the centre of
// [-4, 4]^3, phi = E z on the z faces, Neumann on the x and y faces, the ch. 6 ratios
// sigma_r = 1.75, eps_r = 3.5 by default. The force per vertex ([M_E].n times the vertex area)
// of N = 24..64 is compared with N = 96 at the same vertices; the net force (zero by symmetry)
// and the distance from the free-space traction (the box's image dipoles, ~ (a/L)^3) are printed
// beside it.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/reference/interface_examples_3d.h"

namespace ehd::cli {
namespace {

Eigen::Matrix2Xd ForceFor(int m, double sigma_r, double eps_r, int* iterations, double* ms) {
  const Grid2D grid{m, m, 8.0 / m, -4.0, -4.0};
  LeakyDielectricSolver<2> solver(grid, sigma_r, 1.0, eps_r, 1.0);
  solver.SetAppliedField(1.0);
  Eigen::Matrix2Xd x(2, m);
  for (int k = 0; k < m; ++k) x.col(k) << std::cos(2 * M_PI * k / m), std::sin(2 * M_PI * k / m);
  const InterfaceSolveReport& r = solver.Solve(ClosedCurve(x));
  *iterations = r.iterations;
  *ms = r.solve_ms;
  return solver.force();
}

struct Force3D {
  Eigen::Matrix3Xd force, traction;
  int iterations = 0;
  double ms = 0;
};

Force3D Force3DFor(int n, const TriangleMesh& mesh, double sigma_r, double eps_r) {
  const Grid3D grid{n, n, n, 8.0 / n, -4, -4, -4};
  LeakyDielectricSolver<3> solver(grid, sigma_r, 1.0, eps_r, 1.0);
  solver.SetAppliedField(1.0);
  const auto start = std::chrono::steady_clock::now();
  const InterfaceSolveReport& r = solver.Solve(mesh, 0.0);
  Force3D out;
  out.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  out.iterations = r.iterations;
  out.force = solver.force();
  out.traction = solver.traction();
  return out;
}

Eigen::Vector3d FreeSpaceTraction(const Eigen::Vector3d& p, double sigma_r, double eps_r) {
  return FreeSpaceSphereTraction(p, 1.0, 1.0, sigma_r, 1.0, eps_r, 1.0);
}

int RunEforce3D(double sigma_r, double eps_r) {
  const TriangleMesh mesh = IcosphereMesh(4, 1.0);
  const Force3D ref = Force3DFor(96, mesh, sigma_r, eps_r);
  double scale = 0, traction_scale = 0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    scale = std::max(scale, ref.force.col(v).norm());
    traction_scale =
        std::max(traction_scale, FreeSpaceTraction(mesh.vertices().col(v), sigma_r, eps_r).norm());
  }
  std::printf(
      "3D interfacial electric force convergence, sphere R = 1 in [-4,4]^3, %d vertices, "
      "sigma_r = %g, eps_r = %g (ref: N = 96, %d GMRES iterations, %.0f ms)\n",
      mesh.vertex_count(), sigma_r, eps_r, ref.iterations, ref.ms);
  std::printf("%5s %14s %8s %7s %14s %16s %5s %9s\n", "N", "|F-F96|/|F|inf", "rate", "order",
              "|sum F|/sum|F|", "|t-t_free|/|t|", "iter", "ms");
  double previous = 0;
  int previous_n = 0, refused = 0;
  for (int n : {24, 32, 48, 64}) {
    Force3D f;
    try {
      f = Force3DFor(n, mesh, sigma_r, eps_r);
    } catch (const SolverError& e) {  // a grid the solver cannot trust: a row, then go on
      std::printf("%5d   refused: %s\n", n, e.what());
      ++refused;
      previous = 0;
      continue;
    }
    double err = 0, sum_abs = 0, free_err = 0;
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (int v = 0; v < mesh.vertex_count(); ++v) {
      err = std::max(err, (f.force.col(v) - ref.force.col(v)).norm());
      total += f.force.col(v);
      sum_abs += f.force.col(v).norm();
      const Eigen::Vector3d exact = FreeSpaceTraction(mesh.vertices().col(v), sigma_r, eps_r);
      free_err = std::max(free_err, (f.traction.col(v) - exact).norm());
    }
    err /= scale;
    if (previous > 0) {
      // The order against the N = 96 reference (its own error is part of the difference).
      std::printf("%5d %14.4e %8.3f %7.2f %14.2e %16.3e %5d %9.0f\n", n, err, previous / err,
                  std::log(previous / err) / std::log(static_cast<double>(n) / previous_n),
                  total.norm() / sum_abs, free_err / traction_scale, f.iterations, f.ms);
    } else {
      std::printf("%5d %14.4e %8s %7s %14.2e %16.3e %5d %9.0f\n", n, err, "-", "-",
                  total.norm() / sum_abs, free_err / traction_scale, f.iterations, f.ms);
    }
    previous = err;
    previous_n = n;
  }
  return refused > 0 ? 1 : 0;
}

int RunEforce(const std::vector<std::string>& args) {
  double sigma_r = 3.0, eps_r = 2.0;
  int dim = 2;
  bool ratios_given = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--sigma-ratio") {
      sigma_r = ParseDouble(args[i], OptionValue(args, i));
      ratios_given = true;
    } else if (args[i] == "--eps-ratio") {
      eps_r = ParseDouble(args[i], OptionValue(args, i));
      ratios_given = true;
    } else if (args[i] == "--dim") {
      const std::string value = OptionValue(args, i);
      if (value != "2" && value != "3")
        throw UsageError("--dim: expected 2 or 3, got '" + value + "'");
      dim = value == "3" ? 3 : 2;
    } else {
      throw UsageError("unknown option '" + args[i] + "'");
    }
  }
  if (!(sigma_r > 0) || !(eps_r > 0)) throw UsageError("ratios must be > 0");
  if (dim == 3 && !ratios_given) {
    sigma_r = 1.75;  // song2019 ch. 6, case A
    eps_r = 3.5;
  }
  if (sigma_r > InterfaceSolverOptions<2>().max_inner_ratio) {
    throw UsageError(
        "--sigma-ratio " + std::to_string(sigma_r) + ": the interface solver accepts at most " +
        std::to_string(InterfaceSolverOptions<2>().max_inner_ratio) + " (max_inner_ratio)");
  }
  if (dim == 3) return RunEforce3D(sigma_r, eps_r);
  int it_ref = 0;
  double ms_ref = 0;
  const Eigen::Matrix2Xd ref = ForceFor(512, sigma_r, eps_r, &it_ref, &ms_ref);
  std::printf(
      "interfacial electric force convergence, sigma_r = %g, eps_r = %g (ref: M = 512, "
      "%d GMRES iterations, %.1f ms)\n",
      sigma_r, eps_r, it_ref, ms_ref);
  std::printf("%5s %14s %8s %7s %14s %8s %7s %5s %8s\n", "M", "|Fx-Fx512|inf", "rate", "order",
              "|Fy-Fy512|inf", "rate", "order", "iter", "ms");
  double prev_x = 0, prev_y = 0;
  for (int m : {32, 64, 128, 256}) {
    int it = 0;
    double ms = 0;
    const Eigen::Matrix2Xd f = ForceFor(m, sigma_r, eps_r, &it, &ms);
    double ex = 0, ey = 0;
    for (int k = 0; k < m; ++k) {
      const int kr = k * (512 / m);
      ex = std::max(ex, std::abs(f(0, k) - ref(0, kr)));
      ey = std::max(ey, std::abs(f(1, k) - ref(1, kr)));
    }
    if (prev_x > 0) {
      std::printf("%5d %14.5e %8.4f %7.3f %14.5e %8.4f %7.3f %5d %8.2f\n", m, ex, prev_x / ex,
                  std::log2(prev_x / ex), ey, prev_y / ey, std::log2(prev_y / ey), it, ms);
    } else {
      std::printf("%5d %14.5e %8s %7s %14.5e %8s %7s %5d %8.2f\n", m, ex, "-", "-", ey, "-", "-",
                  it, ms);
    }
    prev_x = ex;
    prev_y = ey;
  }
  return 0;
}

const CommandRegistration kEforce(
    {"eforce", "convergence of the interfacial electric force (song2019 Table 10)",
     "usage: ehd_sim eforce [--dim 2|3] [--sigma-ratio 3] [--eps-ratio 2]\n"
     "2D: drop R = 1 in [-4,4]^2, E_inf = (0,-1); M = 32..256 markers on N = M grids compared\n"
     "with M = 512 at shared marker angles; prints the L-inf differences of Fx, Fy, rates and\n"
     "orders.\n"
     "3D: sphere R = 1 (2562 vertices) in [-4,4]^3, phi = E z on the z faces (song2019 ch. 6),\n"
     "ratios 1.75 and 3.5 unless given; the force per vertex on N = 24..64 against N = 96 at\n"
     "the same vertices, the net force, the distance from the free-space traction.\n",
     RunEforce});

}  // namespace
}  // namespace ehd::cli
