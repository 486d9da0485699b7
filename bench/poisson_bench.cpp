// Wall time per FastPoissonSolver::Solve on N x N cell-centred grids for the boundary sets the
// code uses (all Dirichlet: IIM examples; Neumann x / Dirichlet y: EHD scenes; periodic x /
// Dirichlet y), including sizes whose REDFT10/RODFT10 logical size 2N factors badly.
// Prints N, plan ms, ms per solve (median of repeats) and ms / (N^2 log2 N) * 1e6.
// --dim 3 [--sizes 64,99,100,127,128]: the 3D solver on N^3 boxes instead (all Dirichlet, and
// song2019 ch. 6's Neumann x, y / Dirichlet z), ms / (N^3 log2 N) * 1e6.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ehd_capsule/electric/fast_poisson_solver.h"
#include "ehd_capsule/electric/fast_poisson_solver_3d.h"

namespace {

int Bench3D(const std::vector<int>& sizes) {
  using ehd::BoundaryKind;
  using K = BoundaryKind;
  struct Set {
    const char* name;
    ehd::PoissonBoundaries3D bc;
  };
  const Set sets[] = {
      {"DDDDDD",
       {K::kDirichlet, K::kDirichlet, K::kDirichlet, K::kDirichlet, K::kDirichlet, K::kDirichlet}},
      {"NNNN-DD",
       {K::kNeumann, K::kNeumann, K::kNeumann, K::kNeumann, K::kDirichlet, K::kDirichlet}},
  };
  std::printf("%-8s %5s %9s %11s %16s\n", "bc", "N", "plan ms", "ms/solve", "ns/(N^3 log2 N)");
  for (const Set& set : sets) {
    for (int n : sizes) {
      const ehd::Grid3D g{n, n, n, 1.0 / n, 0.0, 0.0, 0.0};
      const auto t0 = std::chrono::steady_clock::now();
      ehd::FastPoissonSolver3D solver(g, set.bc);
      const double plan_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      std::vector<double> rhs(g.size()), u(g.size());
      for (std::size_t k = 0; k < rhs.size(); ++k) rhs[k] = std::sin(0.001 * k);
      std::vector<double> times;
      for (int r = 0; r < 5; ++r) {
        const auto a = std::chrono::steady_clock::now();
        solver.Solve(rhs, u);
        times.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a)
                .count());
      }
      std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
      const double ms = times[times.size() / 2];
      std::printf("%-8s %5d %9.1f %11.2f %16.2f\n", set.name, n, plan_ms, ms,
                  ms * 1e6 / (double(n) * n * n * std::log2(n)));
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 3 && std::string(argv[1]) == "--dim" && std::string(argv[2]) == "3") {
    std::vector<int> sizes = {32, 48, 63, 64, 99, 100};
    if (argc >= 5 && std::string(argv[3]) == "--sizes") {
      sizes.clear();
      std::string list = argv[4];
      std::size_t pos = 0;
      while (pos <= list.size()) {
        const std::size_t comma = list.find(',', pos);
        sizes.push_back(std::stoi(list.substr(pos, comma - pos)));
        if (comma == std::string::npos) break;
        pos = comma + 1;
      }
    }
    return Bench3D(sizes);
  }
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
