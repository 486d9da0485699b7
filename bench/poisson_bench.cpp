// Wall time per FastPoissonSolver::Solve on N x N cell-centred grids for the boundary sets the
// code uses (all Dirichlet: IIM examples; Neumann x / Dirichlet y: EHD scenes; periodic x /
// Dirichlet y), including sizes whose REDFT10/RODFT10 logical size 2N factors badly.
// Prints N, plan ms, ms per solve (median of repeats) and ms / (N^2 log2 N) * 1e6.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "ehd_capsule/electric/fast_poisson_solver.h"

int main() {
  using ehd::BoundaryKind;
  struct Set {
    const char* name;
    ehd::PoissonBoundaries bc;
  };
  const Set sets[] = {
      {"DDDD",
       {BoundaryKind::kDirichlet, BoundaryKind::kDirichlet, BoundaryKind::kDirichlet,
        BoundaryKind::kDirichlet}},
      {"NN-DD",
       {BoundaryKind::kNeumann, BoundaryKind::kNeumann, BoundaryKind::kDirichlet,
        BoundaryKind::kDirichlet}},
      {"PP-DD",
       {BoundaryKind::kPeriodic, BoundaryKind::kPeriodic, BoundaryKind::kDirichlet,
        BoundaryKind::kDirichlet}},
  };
  std::printf("%-6s %5s %9s %11s %16s\n", "bc", "N", "plan ms", "ms/solve", "ns/(N^2 log2 N)");
  for (const Set& set : sets) {
    for (int n : {40, 64, 80, 128, 160, 256, 320, 512, 640, 251, 331}) {
      const ehd::Grid2D g{n, n, 1.0 / n, 0.0, 0.0};
      const auto t0 = std::chrono::steady_clock::now();
      ehd::FastPoissonSolver solver(g, set.bc);
      const double plan_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      std::vector<double> rhs(g.size()), u(g.size());
      for (std::size_t k = 0; k < rhs.size(); ++k) rhs[k] = std::sin(0.001 * k);
      const int repeats = std::max(5, static_cast<int>(2e7 / (double(n) * n * std::log2(n))));
      std::vector<double> times;
      for (int r = 0; r < repeats; ++r) {
        const auto a = std::chrono::steady_clock::now();
        solver.Solve(rhs, u);
        times.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a)
                .count());
      }
      std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
      const double ms = times[times.size() / 2];
      std::printf("%-6s %5d %9.1f %11.3f %16.2f\n", set.name, n, plan_ms, ms,
                  ms * 1e6 / (double(n) * n * std::log2(n)));
    }
  }
  return 0;
}
