// `ehd_sim eforce`: convergence of the interfacial electric force (song2019 sec. 4.2.1,
// Table 10). Drop of radius 1 at the centre of [-4, 4]^2, E_inf = (0, -1) (phi = y on y = +-4,
// dphi/dx = 0 on x = +-4), sigma_r = sigma^-/sigma^+ = 3, eps_r = eps^-/eps^+ = 2, M markers on
// an N = M grid (so the marker spacing 2 pi / M < h = 8 / N as sec. 4.2 requires). The force of
// M = 32..256 is compared with M = 512 at the shared marker angles theta_k = 2 pi k / M.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "ehd_capsule/electric/leaky_dielectric_solver.h"

namespace ehd::cli {
namespace {

Eigen::Matrix2Xd ForceFor(int m, double sigma_r, double eps_r, int* iterations, double* ms) {
  const Grid2D grid{m, m, 8.0 / m, -4.0, -4.0};
  LeakyDielectricSolver solver(grid, sigma_r, 1.0, eps_r, 1.0);
  solver.SetAppliedField(1.0);
  Eigen::Matrix2Xd x(2, m);
  for (int k = 0; k < m; ++k) x.col(k) << std::cos(2 * M_PI * k / m), std::sin(2 * M_PI * k / m);
  const InterfaceSolveReport& r = solver.Solve(ClosedCurve(x));
  *iterations = r.iterations;
  *ms = r.solve_ms;
  return solver.force();
}

int RunEforce(const std::vector<std::string>& args) {
  double sigma_r = 3.0, eps_r = 2.0;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--sigma-ratio") {
      sigma_r = ParseDouble(args[i], OptionValue(args, i));
    } else if (args[i] == "--eps-ratio") {
      eps_r = ParseDouble(args[i], OptionValue(args, i));
    } else {
      throw UsageError("unknown option '" + args[i] + "'");
    }
  }
  if (!(sigma_r > 0) || !(eps_r > 0)) throw UsageError("ratios must be > 0");
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
     "usage: ehd_sim eforce [--sigma-ratio 3] [--eps-ratio 2]\n"
     "Drop R = 1 in [-4,4]^2, E_inf = (0,-1); M = 32..256 markers on N = M grids compared with\n"
     "M = 512 at shared marker angles; prints the L-inf differences of Fx, Fy, rates and orders.\n",
     RunEforce});

}  // namespace
}  // namespace ehd::cli
