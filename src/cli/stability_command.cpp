// ehd_sim stability: the extreme cases, each of which must either run stably or stop early with
// a clear error (never a silent NaN).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

#include "command.h"
#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/coupling/steady_state.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd::cli {
namespace {

const char* kUsage =
    "usage: ehd_sim stability [--scene NAME] [--until T] [--steady-tolerance TOL]\n"
    "                         [--set key=value ...]\n\n"
    "Runs the extreme cases on SCENE (default shear_field): sigma_r = 1000 and 1/1000,\n"
    "eps_r = 1/10 and 10, Ca_E = 5, Ca = 0.4, E_b = 0.5, tau near 1/2, V = 10, markers coarser\n"
    "than the grid, a capsule touching the walls. Each runs to a physical horizon, t = T\n"
    "(default 100, the scene's time unit), or until steady (D_xy and theta steady to TOL over a\n"
    "unit of time, relative as in `run --until-steady`; default 1e-4). Outcomes:\n"
    "  steady     reached a steady state (at the time shown)\n"
    "  periodic   bounded oscillation at T: the D_xy range of the last quarter of the run is\n"
    "             no larger than 1.1x that of the quarter before (tumbling, swinging)\n"
    "  unsettled  reached T neither steady nor bounded-periodic (still drifting or growing)\n"
    "  stopped    a watchdog or solver error stopped it (the step and the quantity)\n"
    "  rejected   refused at set-up (the reason)\n"
    "Only 'steady' and 'periodic' are stable. Exit status 1 if any case produced a non-finite\n"
    "state without an error.\n";

struct Case {
  const char* label;
  std::vector<std::string> overrides;
};

int Stability(const std::vector<std::string>& args) {
  std::string scene_name = "shear_field";
  double until = 100.0, steady_tol = 1e-4;
  std::vector<std::string> base;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--scene")
      scene_name = OptionValue(args, i);
    else if (a == "--until")
      until = ParseDouble(a, OptionValue(args, i));
    else if (a == "--steady-tolerance")
      steady_tol = ParseDouble(a, OptionValue(args, i));
    else if (a == "--set")
      base.push_back(OptionValue(args, i));
    else
      throw UsageError("unknown option '" + a + "'");
  }
  if (!(until > 0.0)) throw UsageError("--until must be > 0");
  if (!(steady_tol > 0.0)) throw UsageError("--steady-tolerance must be > 0");
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
  std::printf("stability cases on scene %s, each to t = %g or steady to %g\n", scene_name.c_str(),
              until, steady_tol);
  std::printf("%-38s %-10s %8s %8s %9s %10s %10s %8s  %s\n", "case", "outcome", "t", "steps",
              "D_xy", "theta/pi", "area drift", "Mach", "ms/step");
  bool silent_nan = false;
  for (const Case& c : cases) {
    std::vector<std::string> o = base;
    o.insert(o.end(), c.overrides.begin(), c.overrides.end());
    std::string outcome, message;
    SimulationState last;
    double wall = 0;
    try {
      Simulation sim(LoadScene(scene_name, o));
      SteadyStateMonitor monitor(steady_tol);
      // D_xy samples (t, D) every 1/40 of a time unit for the periodic test.
      std::vector<double> ts, ds;
      const auto start = std::chrono::steady_clock::now();
      try {
        while (sim.state().time < until - 1e-12) {
          sim.Step();
          const SimulationState& st = sim.state();
          if (ts.empty() || st.time >= ts.back() + 0.025) {
            ts.push_back(st.time);
            ds.push_back(st.dxy);
          }
          if (monitor.Update(st.time, st.dxy, st.inclination)) {
            outcome = "steady";
            break;
          }
        }
        if (outcome.empty()) {
          // Ranges of D over the third and the last quarter of the run.
          double lo3 = 1e300, hi3 = -1e300, lo4 = 1e300, hi4 = -1e300;
          const double t_end = sim.state().time;
          for (std::size_t i = 0; i < ts.size(); ++i) {
            if (ts[i] >= 0.75 * t_end) {
              lo4 = std::min(lo4, ds[i]);
              hi4 = std::max(hi4, ds[i]);
            } else if (ts[i] >= 0.5 * t_end) {
              lo3 = std::min(lo3, ds[i]);
              hi3 = std::max(hi3, ds[i]);
            }
          }
          const bool bounded = hi4 - lo4 <= 1.1 * (hi3 - lo3) && hi4 <= hi3 + 0.1 * (hi3 - lo3) &&
                               lo4 >= lo3 - 0.1 * (hi3 - lo3);
          outcome = bounded ? "periodic" : "unsettled";
          message = "D_xy range " + std::to_string(lo4) + " .. " + std::to_string(hi4) +
                    " over the last quarter (" + std::to_string(lo3) + " .. " +
                    std::to_string(hi3) + " over the third)";
        }
      } catch (const SimulationError& e) {
        outcome = "stopped";
        message = e.what();
      }
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      last = sim.state();
      if (outcome != "stopped" && !(std::isfinite(last.dxy) && last.markers.allFinite())) {
        outcome = "SILENT NaN";
        silent_nan = true;
      }
    } catch (const std::exception& e) {
      outcome = "rejected";
      message = e.what();
    }
    if (outcome == "rejected") {
      std::printf("%-38s %-10s  %s\n", c.label, outcome.c_str(), message.c_str());
    } else {
      std::printf("%-38s %-10s %8.4g %8ld %9.5f %10.4f %10.2e %8.4f  %.3f\n", c.label,
                  outcome.c_str(), last.time, last.step, last.dxy, last.inclination / M_PI,
                  last.area_drift, last.max_mach, last.step > 0 ? 1e3 * wall / last.step : 0.0);
      if (!message.empty()) std::printf("%-38s   -> %s\n", "", message.c_str());
    }
    std::fflush(stdout);
  }
  return silent_nan ? 1 : 0;
}

const CommandRegistration kStability(
    {"stability", "extreme cases to a physical horizon: steady, periodic or a clear error", kUsage,
     Stability});

}  // namespace
}  // namespace ehd::cli
