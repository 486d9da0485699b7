// Validation tables of the 2D fluid-structure core (capsule in shear, no field), song2019 sec.
// 4.1 and 5.2-5.4; the tables of docs/validation_fsi.md are the output of this program.
//
// Per run (Simulation from a scene + overrides, numerics.threads = 1) it reports:
//   D_xy, theta/pi at steady state: SteadyStateMonitor (range of D_xy and theta over the last
//     unit of 1/k below TOL) or at t_max;
//   t_2%: first time after which D_xy stays within 2% of its final value (time to steady);
//   f = 4 pi / (k T), tank-treading frequency (song2019 sec. 5.1), from the steady membrane
//     velocity: a material point goes round in T = sum_k dl_k / |u_t,k| (u_t: marker velocity
//     relative to the centroid, along the tangent; exact for a steady tank-treading shape, no need
//     to wait a full turn). f_KS = 2 a b / (a^2 + b^2) = (1 - D^2) / (1 + D^2): a fixed ellipse
//     whose interior keeps the vorticity k of the shear (Keller-Skalak-type estimate at V = 1;
//     f = 1 for a circle turning at k/2);
//   flips: half turns of the long axis through the vertical (TankTreadingTracker), over the
//     whole run / over its second half (tumbling goes on: late flips > 0);
//   max |A/A0 - 1| over the run; whether the membrane polygon ever self-intersected (markers
//     crossing), checked every 0.1/k;
//   steps and wall seconds.
// Grid refinement keeps M/N (markers refined with the grid); observed order
//   p = log(|D_N1 - D_N2| / |D_N2 - D_N3|) / log(N2 / N1) from three consecutive grids.
//
// Usage (from the repository root):
//   fsi_validation_bench ca        [--grids 32,64,128] [--ca 0.0125,...] [--tol 5e-4] [--t-max 30]
//   fsi_validation_bench bending   [--grids 64,128]
//   fsi_validation_bench biconcave [--grids 64]
//   fsi_validation_bench viscosity [--grids 64,128]
// Common: --m-per-n R (markers per cell across, default 1), --set key=value (extra overrides).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/coupling/steady_state.h"
#include "ehd_capsule/diagnostics/shape_diagnostics.h"
#include "ehd_capsule/diagnostics/tank_treading.h"
#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/scene/scene.h"

namespace {

using ehd::Simulation;

struct RunResult {
  double dxy = NAN, theta = NAN, time = 0, t2 = NAN, f = NAN, f_ks = NAN;
  double max_drift = 0, wall = 0;
  double stretch_mean = NAN, stretch_min = NAN, stretch_max = NAN;  // lambda at the end
  long steps = 0;
  bool steady = false, tumbling = false, crossed = false;
  int flips = 0, late_flips = 0;  // long-axis half turns: whole run, second half
  std::string error;
};

bool SegmentsIntersect(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                       const Eigen::Vector2d& q1, const Eigen::Vector2d& q2) {
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  };
  const double d1 = cross(q1, q2, p1), d2 = cross(q1, q2, p2);
  const double d3 = cross(p1, p2, q1), d4 = cross(p1, p2, q2);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

// True if two non-adjacent segments of the closed marker polygon intersect.
bool SelfIntersects(const Eigen::Matrix2Xd& x) {
  const int m = static_cast<int>(x.cols());
  for (int i = 0; i < m; ++i) {
    for (int j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;  // adjacent through the closure
      if (SegmentsIntersect(x.col(i), x.col((i + 1) % m), x.col(j), x.col((j + 1) % m)))
        return true;
    }
  }
  return false;
}

// f = 4 pi / (k T), T = sum dl / |u_t| from the displacement of the markers over one step.
double TankTreadingFrequency(const Eigen::Matrix2Xd& before, const Eigen::Matrix2Xd& after,
                             double shear_rate_lattice) {
  const ehd::ClosedCurve c(after);
  const int m = c.size();
  Eigen::Vector2d drift = Eigen::Vector2d::Zero();
  for (int k = 0; k < m; ++k) drift += after.col(k) - before.col(k);
  drift /= m;
  double period = 0.0;  // lattice steps
  for (int k = 0; k < m; ++k) {
    const double ut = (after.col(k) - before.col(k) - drift).dot(c.AtMarker(k).tangent);
    const double dl = 0.5 * (c.SegmentArcLength((k + m - 1) % m) + c.SegmentArcLength(k));
    period += dl / std::max(std::abs(ut), 1e-300);
  }
  return 4.0 * M_PI / (shear_rate_lattice * period);
}

RunResult Run(const std::string& scene, std::vector<std::string> overrides, double t_max,
              double tol, bool need_steady = true) {
  RunResult r;
  overrides.push_back("numerics.threads=1");
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> ts, ds;
  try {
    Simulation sim(ehd::LoadScene(scene, overrides));
    const ehd::ClosedCurve reference(sim.state().markers.topRows<2>());
    ehd::SteadyStateMonitor monitor(tol);
    ehd::TankTreadingTracker tracker(0);
    const double k = sim.units().shear_rate;
    const long check_every = std::max(1L, std::lround(0.1 / (k > 0 ? k : 1.0)));
    const long sample_every = std::max(1L, std::lround(0.01 / (k > 0 ? k : 1.0)));
    int flips_at_half = -1;
    while (sim.state().time < t_max - 1e-12) {
      if (flips_at_half < 0 && sim.state().time >= 0.5 * t_max) flips_at_half = tracker.flips();
      sim.Step();
      const auto& s = sim.state();
      r.max_drift = std::max(r.max_drift, std::abs(s.area_drift));
      if (s.step % sample_every == 0) {
        ts.push_back(s.time);
        ds.push_back(s.dxy);
        const Eigen::Matrix2Xd x = s.markers.topRows<2>();
        const ehd::ShapeDiagnostics d = ehd::MeasureShape(ehd::ClosedCurve(x));
        tracker.Update(s.time, x, d.centroid, s.inclination);
      }
      if (s.step % check_every == 0 && !r.crossed)
        r.crossed = SelfIntersects(s.markers.topRows<2>());
      if (need_steady && monitor.Update(s.time, s.dxy, s.inclination)) {
        r.steady = true;
        break;
      }
    }
    const Eigen::Matrix2Xd before = sim.state().markers.topRows<2>();
    sim.Step();
    const auto& s = sim.state();
    r.f = TankTreadingFrequency(before, s.markers.topRows<2>(), k);
    r.dxy = s.dxy;
    r.theta = s.inclination;
    r.time = s.time;
    r.steps = s.step;
    r.f_ks = (1 - r.dxy * r.dxy) / (1 + r.dxy * r.dxy);
    r.tumbling = tracker.tumbling();
    r.flips = tracker.flips();
    r.late_flips = flips_at_half < 0 ? 0 : r.flips - flips_at_half;
    r.crossed = r.crossed || SelfIntersects(s.markers.topRows<2>());
    {
      const ehd::ClosedCurve c(s.markers.topRows<2>());
      double sum = 0.0;
      r.stretch_min = 1e300;
      r.stretch_max = 0.0;
      for (int k = 0; k < c.size(); ++k) {
        const double lambda = c.SegmentArcLength(k) / reference.SegmentArcLength(k);
        sum += lambda;
        r.stretch_min = std::min(r.stretch_min, lambda);
        r.stretch_max = std::max(r.stretch_max, lambda);
      }
      r.stretch_mean = sum / c.size();
    }
    // Time to steady: last sample outside 2% of the final D.
    r.t2 = 0.0;
    for (std::size_t i = 0; i < ts.size(); ++i) {
      if (std::abs(ds[i] - r.dxy) > 0.02 * r.dxy) r.t2 = ts[i];
    }
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<double> ParseList(const std::string& s) {
  std::vector<double> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::atof(item.c_str()));
  return v;
}

struct Options {
  std::string mode;
  std::vector<double> grids;
  std::vector<double> ca;
  double tol = 5e-4, t_max = 30.0, m_per_n = 1.0;
  std::vector<std::string> sets;
};

std::vector<std::string> GridOverrides(const Options& o, int n) {
  std::vector<std::string> v = o.sets;
  v.push_back("N=" + std::to_string(n));
  v.push_back("M=" + std::to_string(static_cast<int>(std::lround(o.m_per_n * n))));
  return v;
}

void PrintHeader() {
  std::printf("%6s %5s %5s %8s %8s %7s %6s %6s %6s %8s %5s %6s %9s %8s\n", "case", "N", "M", "D_xy",
              "theta/pi", "t", "t_2%", "f", "f_KS", "|dA|max", "cross", "flips", "steps", "wall s");
}

void PrintRow(const std::string& label, int n, int m, const RunResult& r) {
  if (!r.error.empty()) {
    std::printf("%6s %5d %5d  failed: %s\n", label.c_str(), n, m, r.error.c_str());
    return;
  }
  std::printf("%6s %5d %5d %8.5f %8.5f %7.3g %6.2f %6.3f %6.3f %8.1e %5s %6s %9ld %8.1f%s\n",
              label.c_str(), n, m, r.dxy, r.theta / M_PI, r.time, r.t2, r.f, r.f_ks, r.max_drift,
              r.crossed ? "YES" : "no",
              (std::to_string(r.flips) + "/" + std::to_string(r.late_flips)).c_str(), r.steps,
              r.wall, r.steady ? "" : " (not steady)");
  std::fflush(stdout);
}

// Convergence summary of one case over the grids: difference to the finest and observed order.
void PrintConvergence(const std::string& label, const std::vector<int>& n,
                      const std::vector<RunResult>& r) {
  const std::size_t last = r.size() - 1;
  std::printf("  %s:", label.c_str());
  for (std::size_t i = 0; i < last; ++i) {
    std::printf(" |D_%d - D_%d| = %.2e (%.1f%%), |theta/pi diff| = %.1e;", n[i], n[last],
                std::abs(r[i].dxy - r[last].dxy),
                100 * std::abs(r[i].dxy - r[last].dxy) / r[last].dxy,
                std::abs(r[i].theta - r[last].theta) / M_PI);
  }
  if (r.size() >= 3) {
    const double e1 = std::abs(r[last - 2].dxy - r[last - 1].dxy);
    const double e2 = std::abs(r[last - 1].dxy - r[last].dxy);
    const double p = std::log(e1 / e2) / std::log(static_cast<double>(n[last - 1]) / n[last - 2]);
    // Richardson estimate of the grid-converged D from the last two grids with that order.
    const double ratio = std::pow(static_cast<double>(n[last]) / n[last - 1], p);
    const double d_inf = r[last].dxy + (r[last].dxy - r[last - 1].dxy) / (ratio - 1.0);
    std::printf(" observed order p = %.2f, Richardson D = %.5f", p, d_inf);
  }
  std::printf("\n");
}

void SweepCa(const Options& o) {
  std::printf("Hookean circle in shear (capsule_shear: Re = 0.05, L = 4a, E_b = 0, V = 1)\n");
  PrintHeader();
  std::vector<std::vector<RunResult>> all;
  std::vector<int> grids;
  for (double g : o.grids) grids.push_back(static_cast<int>(g));
  for (double ca : o.ca) {
    std::vector<RunResult> rows;
    char label[32];
    std::snprintf(label, sizeof label, "%g", ca);
    for (int n : grids) {
      std::vector<std::string> ov = GridOverrides(o, n);
      ov.push_back("Ca=" + std::to_string(ca));
      rows.push_back(Run("capsule_shear", ov, o.t_max, o.tol));
      PrintRow(label, n, static_cast<int>(std::lround(o.m_per_n * n)), rows.back());
    }
    all.push_back(rows);
  }
  std::printf("\nconvergence (Ca: differences to the finest grid):\n");
  for (std::size_t i = 0; i < all.size(); ++i) {
    char label[32];
    std::snprintf(label, sizeof label, "Ca = %g", o.ca[i]);
    bool ok = true;
    for (const auto& r : all[i]) ok = ok && r.error.empty();
    if (ok) PrintConvergence(label, grids, all[i]);
  }
  std::printf(
      "\nsmall-Ca law on the finest grid: D^3 / Ca, local exponent d ln D / d ln Ca, membrane\n"
      "stretch at the end (mean, min, max) and (mean - 1) / (3 D^2 / 4) (perimeter excess of the\n"
      "ellipse of the same area)\n");
  for (std::size_t i = 0; i < all.size(); ++i) {
    const RunResult& r = all[i].back();
    std::printf("  Ca = %-7g D = %.5f  D^3/Ca = %.3f  lambda %.4f [%.4f, %.4f] ratio %.3f", o.ca[i],
                r.dxy, r.dxy * r.dxy * r.dxy / o.ca[i], r.stretch_mean, r.stretch_min,
                r.stretch_max, (r.stretch_mean - 1.0) / (0.75 * r.dxy * r.dxy));
    if (i > 0) {
      const RunResult& q = all[i - 1].back();
      std::printf("  exponent %.3f", std::log(r.dxy / q.dxy) / std::log(o.ca[i] / o.ca[i - 1]));
    }
    std::printf("\n");
  }
}

void SweepScene(const Options& o, const std::string& title, const std::string& scene,
                const std::vector<std::pair<std::string, std::vector<std::string>>>& cases,
                double t_max, bool need_steady) {
  std::printf("%s\n", title.c_str());
  PrintHeader();
  for (double g : o.grids) {
    const int n = static_cast<int>(g);
    for (const auto& c : cases) {
      std::vector<std::string> ov = GridOverrides(o, n);
      ov.insert(ov.end(), c.second.begin(), c.second.end());
      PrintRow(c.first, n, static_cast<int>(std::lround(o.m_per_n * n)),
               Run(scene, ov, t_max, o.tol, need_steady));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (argc < 2) {
    std::fprintf(stderr, "usage: fsi_validation_bench ca|bending|biconcave|viscosity [options]\n");
    return 2;
  }
  o.mode = argv[1];
  o.grids = {32, 64, 128};
  o.ca = {0.0125, 0.025, 0.05, 0.1, 0.2, 0.4};
  bool grids_given = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "option %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--grids") {
      o.grids = ParseList(value());
      grids_given = true;
    } else if (a == "--ca") {
      o.ca = ParseList(value());
    } else if (a == "--tol") {
      o.tol = std::atof(value().c_str());
    } else if (a == "--t-max") {
      o.t_max = std::atof(value().c_str());
    } else if (a == "--m-per-n") {
      o.m_per_n = std::atof(value().c_str());
    } else if (a == "--set") {
      o.sets.push_back(value());
    } else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (o.mode == "ca") {
    SweepCa(o);
  } else if (o.mode == "bending") {
    if (!grids_given) o.grids = {64, 128};
    std::vector<std::pair<std::string, std::vector<std::string>>> cases;
    for (const char* ca : {"0.04", "0.125"}) {
      for (const char* eb : {"0", "0.05", "0.1", "0.2", "0.5"}) {
        cases.push_back(
            {std::string(ca) + "/" + eb, {std::string("Ca=") + ca, std::string("E_b=") + eb}});
      }
    }
    SweepScene(o, "Bending (capsule_shear, case = Ca/E_b, E_b = E_B / (a^2 E_s))", "capsule_shear",
               cases, o.t_max, true);
  } else if (o.mode == "biconcave") {
    if (!grids_given) o.grids = {64};
    std::vector<std::pair<std::string, std::vector<std::string>>> cases;
    for (const char* eb : {"0", "0.001", "0.005", "0.01", "0.05"}) {
      cases.push_back({std::string("Eb") + eb, {std::string("E_b=") + eb}});
    }
    SweepScene(o, "Biconcave capsule, Ca = 0.0125 (biconcave_shear), fixed run length t_max",
               "biconcave_shear", cases, o.t_max, false);
  } else if (o.mode == "viscosity") {
    if (!grids_given) o.grids = {64, 128};
    std::vector<std::pair<std::string, std::vector<std::string>>> cases;
    for (const char* v : {"0.5", "1", "5"})
      cases.push_back({std::string("V=") + v, {std::string("V=") + v}});
    SweepScene(o, "Viscosity ratio, circle, Ca = 0.0125 (viscosity_ratio)", "viscosity_ratio",
               cases, o.t_max, true);
  } else {
    std::fprintf(stderr, "unknown mode %s (ca|bending|biconcave|viscosity)\n", o.mode.c_str());
    return 2;
  }
  return 0;
}
