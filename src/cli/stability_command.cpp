// ehd_sim stability: the extreme cases, each of which must either run stably or stop early with
// a clear error (never a silent NaN).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "command.h"
#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd::cli {
namespace {

const char* kUsage =
    "usage: ehd_sim stability [--scene NAME] [--steps N] [--set key=value ...]\n\n"
    "Runs the extreme cases on SCENE (default shear_field) for N steps each (default 20000, t = "
    "2.6/k on shear_field):\n"
    "sigma_r = 1000 and 1/1000, eps_r = 1/10 and 10, Ca_E = 5, Ca = 0.4, E_b = 0.5, tau near\n"
    "1/2, V = 10, markers coarser than the grid, a capsule touching the walls. Each case either\n"
    "runs (final D_xy, theta, area drift, max Mach) or stops with the error that stopped it\n"
    "(rejected at set-up, or the step and the quantity). Exit status 1 if any case produced a\n"
    "non-finite state without an error.\n";

struct Case {
  const char* label;
  std::vector<std::string> overrides;
};

int Stability(const std::vector<std::string>& args) {
  std::string scene_name = "shear_field";
  long steps = 20000;
  std::vector<std::string> base;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--scene")
      scene_name = OptionValue(args, i);
    else if (a == "--steps")
      steps = ParseLong(a, OptionValue(args, i));
    else if (a == "--set")
      base.push_back(OptionValue(args, i));
    else
      throw UsageError("unknown option '" + a + "'");
  }
  if (steps < 1) throw UsageError("--steps must be >= 1");
  const std::vector<Case> cases = {
      {"reference", {}},
      {"sigma_r = 1000", {"sigma_r=1000", "Ca_E=0.3"}},
      {"sigma_r = 1/1000", {"sigma_r=0.001", "Ca_E=0.3"}},
      {"eps_r = 1/10", {"eps_r=0.1", "Ca_E=0.3"}},
      {"eps_r = 10", {"eps_r=10", "Ca_E=0.3"}},
      {"Ca_E = 5", {"Ca_E=5"}},
      {"Ca = 0.4", {"Ca=0.4"}},
      {"E_b = 0.5", {"E_b=0.5"}},
      {"tau = 0.505", {"numerics.tau=0.505"}},
      {"V = 10", {"V=10"}},
      {"M = N/4 (markers coarser than grid)", {"M=16"}},
      {"touching the walls (L = 1.05 a)", {"geometry.half_width=1.05"}},
  };
  std::printf("stability cases on scene %s, %ld steps each\n", scene_name.c_str(), steps);
  std::printf("%-38s %-9s %8s %9s %10s %9s %8s  %s\n", "case", "outcome", "steps", "D_xy",
              "theta/pi", "area drift", "Mach", "ms/step");
  bool silent_nan = false;
  for (const Case& c : cases) {
    std::vector<std::string> o = base;
    o.insert(o.end(), c.overrides.begin(), c.overrides.end());
    std::string outcome = "stable", message;
    SimulationState last;
    double wall = 0;
    try {
      Simulation sim(LoadScene(scene_name, o));
      const auto start = std::chrono::steady_clock::now();
      try {
        for (long i = 0; i < steps; ++i) sim.Step();
      } catch (const SimulationError& e) {
        outcome = "stopped";
        message = e.what();
      }
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      last = sim.state();
      if (outcome == "stable" && !(std::isfinite(last.dxy) && last.markers.allFinite())) {
        outcome = "SILENT NaN";
        silent_nan = true;
      }
    } catch (const std::exception& e) {
      outcome = "rejected";
      message = e.what();
    }
    if (outcome == "rejected") {
      std::printf("%-38s %-9s  %s\n", c.label, outcome.c_str(), message.c_str());
    } else {
      std::printf("%-38s %-9s %8ld %9.5f %10.4f %10.2e %8.4f  %.3f\n", c.label, outcome.c_str(),
                  last.step, last.dxy, last.inclination / M_PI, last.area_drift, last.max_mach,
                  last.step > 0 ? 1e3 * wall / last.step : 0.0);
      if (!message.empty()) std::printf("%-38s   -> %s\n", "", message.c_str());
    }
    std::fflush(stdout);
  }
  return silent_nan ? 1 : 0;
}

const CommandRegistration kStability({"stability",
                                      "extreme cases: each runs stably or stops with a clear error",
                                      kUsage, Stability});

}  // namespace
}  // namespace ehd::cli
