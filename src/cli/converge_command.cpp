// ehd_sim converge: grid (and marker) refinement study of one scene.
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <iostream>

#include "command.h"
#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/coupling/steady_state.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd::cli {
namespace {

const char* kUsage =
    "usage: ehd_sim converge SCENE [--grids 32,64,128] [--set key=value ...]\n"
    "                       [--until T | --until-steady TOL]\n\n"
    "Runs SCENE at each grid N (markers refined with the grid: M = round(N M0 / N0) from the\n"
    "scene's N0, M0) and prints per resolution D_xy and theta at the end time (default\n"
    "numerics.t_end) or at steady state, the difference to the finest grid (or, for a drop in a\n"
    "field without shear, to Feng's small-deformation D = f_d Ca_E / (3 (1 + sigma_r)^2)), the\n"
    "observed order log(e_coarse / e_fine) / log(N_fine / N_coarse), steps, wall s and ms/step.\n"
    "With the field, D is signed: + elongated along the field (y), - across it.\n"
    "A 3D SCENE refines its mesh with the grid instead (the icosphere level whose edge in cells\n"
    "is nearest the scene's own) and adds D_z, the deformation along the field axis z.\n";

// 3D: the icosphere level whose mean edge, in cells, is nearest (in ratio) to the scene's own at
// N0 (each level halves the edge: edge ~ 0.151 a 2^(3 - level) for the icosphere; the biconcave
// mesh scales the same way).
int MeshLevelForGrid(const Scene& base, int n) {
  const double edge_h0 = std::pow(2.0, -base.mesh_subdivisions) * base.N;  // up to a constant
  int best = base.mesh_subdivisions;
  double best_gap = 1e300;
  for (int level = 1; level <= 6; ++level) {
    const double gap = std::abs(std::log(std::pow(2.0, -level) * n / edge_h0));
    if (gap < best_gap - 1e-12) {
      best_gap = gap;
      best = level;
    }
  }
  return best;
}

struct Result {
  int n = 0, m = 0;
  long steps = 0;
  double wall = 0, dxy = 0, theta = 0, signed_d = 0, time = 0;
  double d_field = 0;  // 3D: the deformation along the field axis z
  bool steady = false;
  std::string error;
};

int Converge(const std::vector<std::string>& args) {
  std::string scene_name;
  std::vector<std::string> overrides;
  std::vector<int> grids = {32, 64, 128};
  double until = -1, steady_tol = -1;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--grids")
      grids = ParseIntList(a, OptionValue(args, i));
    else if (a == "--set")
      overrides.push_back(OptionValue(args, i));
    else if (a == "--until")
      until = ParseDouble(a, OptionValue(args, i));
    else if (a == "--until-steady")
      steady_tol = ParseDouble(a, OptionValue(args, i));
    else if (!a.empty() && a[0] == '-')
      throw UsageError("unknown option '" + a + "'");
    else if (scene_name.empty())
      scene_name = a;
    else
      throw UsageError("more than one scene given");
  }
  if (scene_name.empty()) throw UsageError("no scene given");
  if (grids.size() < 2) throw UsageError("--grids needs at least two resolutions");
  for (int n : grids) {
    if (n < 16) throw UsageError("--grids: each N must be >= 16, got " + std::to_string(n));
  }
  if (until >= 0 && steady_tol >= 0) throw UsageError("give --until or --until-steady");

  const Scene base = LoadScene(scene_name, overrides);
  const bool three_d = base.dimension == 3;
  const double t_end = until >= 0 ? until : base.numerics.t_end;
  const bool feng = !three_d && !base.has_shear() && base.electric_field &&
                    base.membrane == MembraneKind::kDrop && base.Ca_E > 0;
  const double fd = base.sigma_r * base.sigma_r + base.sigma_r + 1 - 3 * base.eps_r;
  const double d_feng = fd * base.Ca_E / (3 * (1 + base.sigma_r) * (1 + base.sigma_r));
  std::cout << DescribeScene(base);
  std::cout << "end: " << (steady_tol > 0 ? "steady to " + std::to_string(steady_tol) + " or " : "")
            << "t = " << t_end << '\n';
  if (feng) std::printf("Feng small-deformation D = %.5f (f_d = %.4g)\n", d_feng, fd);

  std::vector<Result> results;
  for (int n : grids) {
    Result r;
    r.n = n;
    std::vector<std::string> o = overrides;
    o.push_back("N=" + std::to_string(n));
    if (three_d) {
      r.m = MeshLevelForGrid(base, n);
      o.push_back("mesh_subdivisions=" + std::to_string(r.m));
    } else {
      r.m = static_cast<int>(std::lround(static_cast<double>(n) * base.M / base.N));
      o.push_back("M=" + std::to_string(r.m));
    }
    const auto start = std::chrono::steady_clock::now();
    try {
      Simulation sim(LoadScene(scene_name, o));
      SteadyStateMonitor monitor(steady_tol > 0 ? steady_tol : 1.0);
      while (sim.state().time < t_end - 1e-12) {
        sim.Step();
        const SimulationState& s = sim.state();
        if (steady_tol > 0 && monitor.Update(s.time, s.dxy, s.inclination)) {
          r.steady = true;
          break;
        }
      }
      const SimulationState& s = sim.state();
      r.steps = s.step;
      r.dxy = s.dxy;
      r.theta = s.inclination;
      r.time = s.time;
      r.signed_d = std::abs(s.inclination) > M_PI / 4 ? s.dxy : -s.dxy;
      r.d_field = s.d_field;
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("  N = %d done (%ld steps, %.1f s)%s%s\n", n, r.steps, r.wall,
                r.error.empty() ? "" : ": ", r.error.c_str());
    std::fflush(stdout);
    results.push_back(r);
  }

  const Result& finest = results.back();
  std::printf("\n%6s %6s %9s %8s %10s %10s %11s %6s", "N", three_d ? "level" : "M", "t", "D_xy",
              feng ? "D(signed)" : "theta/pi", "|D-fine|", "|theta-fine|", "order");
  if (feng) std::printf(" %10s", "|D-Feng|");
  if (three_d) std::printf(" %9s %10s", "D_z", "|D_z-fine|");
  std::printf(" %9s %8s %9s\n", "steps", "wall s", "ms/step");
  double prev_err = NAN;
  int prev_n = 0;
  for (const Result& r : results) {
    if (!r.error.empty()) {
      std::printf("%6d %6d  failed: %s\n", r.n, r.m, r.error.c_str());
      continue;
    }
    const bool is_finest = &r == &finest;
    const double err = feng ? std::abs(r.signed_d - finest.signed_d) : std::abs(r.dxy - finest.dxy);
    const double terr = std::abs(r.theta - finest.theta);
    double order = NAN;
    if (prev_n > 0 && err > 0 && prev_err > 0 && !is_finest) {
      order = std::log(prev_err / err) / std::log(static_cast<double>(r.n) / prev_n);
    }
    std::printf("%6d %6d %9.4g %8.5f %10.5f", r.n, r.m, r.time, r.dxy,
                feng ? r.signed_d : r.theta / M_PI);
    if (is_finest)
      std::printf(" %10s %11s %6s", "-", "-", "-");
    else
      std::printf(" %10.3e %11.3e %6.2f", err, terr, order);
    if (feng) std::printf(" %10.3e", std::abs(r.signed_d - d_feng));
    if (three_d && is_finest) std::printf(" %+9.5f %10s", r.d_field, "-");
    if (three_d && !is_finest) {
      std::printf(" %+9.5f %10.3e", r.d_field, std::abs(r.d_field - finest.d_field));
    }
    std::printf(" %9ld %8.2f %9.3f%s\n", r.steps, r.wall,
                r.steps > 0 ? 1e3 * r.wall / r.steps : 0.0, r.steady ? " steady" : "");
    if (!is_finest) {
      prev_err = err;
      prev_n = r.n;
    }
  }
  std::printf("(differences to the finest grid; order from consecutive rows%s)\n",
              feng ? "; Feng's D is first order in Ca_E in an unbounded domain" : "");
  return 0;
}

const CommandRegistration kConverge({"converge",
                                     "grid/marker refinement study of a scene (D_xy, theta, order)",
                                     kUsage, Converge});

}  // namespace
}  // namespace ehd::cli
