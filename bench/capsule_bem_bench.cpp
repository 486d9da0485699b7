// Boundary-element (boundary-integral) reference for the 2D capsule in shear (issue #4): the
// same membrane model as the LBM-IB runs of docs/validation_fsi.md (core MembraneModel: Hookean
// tau = E_s (lambda - 1), song2019 eq. (113), optional prestress tau_p = prestress E_s and
// bending E_B = E_b a^2 E_s, eq. (115)), viscosity ratio 1, unbounded simple shear u = (k y, 0),
// Re = 0, solved by the Stokes single layer of bench/stokes_bie.h (method of Breyiannis &
// Pozrikidis 2000 for V = 1). Units mu = k = a = 1, so E_s = 1 / Ca (Ca = mu k a / E_s, eq. (119)).
//
// Per run: steady D_xy and theta (diagnostics/shape_diagnostics.h on the marker spline, the same
// code the LBM table uses; the spectral second moments of stokes_bie.h as a cross-check),
// steady = range of D_xy and theta over the last unit of 1/k below --tol (default 1e-5), else the
// value at --t-max; t_2% = time after which D stays within 2% of its final value; tank-treading
// f = 4 pi / (k T) with T = sum_k dl_k / |u_t,k| on the steady shape (as fsi_validation_bench);
// stretch range; max |A/A0 - 1|; steps, wall seconds. dt = cfl / sigma_max, sigma_max the
// fastest Stokes relaxation rate of the membrane modes resolved by the markers
// (membrane_stability.h without the IB kernel): elastic S pi / (4 mu dl), S = 1.5 E_s + tau_p
// (stretch up to 1.5), bending E_B pi^3 / (4 mu dl^3), dl = 2 pi a / M; Heun is stable to
// dt sigma = 2.
//
// Usage (from the repository root):
//   capsule_bem_bench ca [--ca 0.0125,0.025,...] [--markers 128,256] [--prestress P] [--eb E_b]
//                        [--cfl 1] [--t-max 40] [--tol 1e-5]
//   capsule_bem_bench selfcheck      (uniform-tension circle, drop Taylor limit, dt and M
//                                     convergence at Ca = 0.05)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/diagnostics/shape_diagnostics.h"
#include "ehd_capsule/diagnostics/tank_treading.h"
#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/reference/stokes_bie.h"

namespace {

const double kPi = std::acos(-1.0);

struct RunConfig {
  double ca = 0.05;
  int markers = 128;
  double prestress = 0.0;  // tau_p / E_s
  double eb = 0.0;         // E_B / (a^2 E_s)
  double cfl = 1.0;
  double t_max = 40.0;
  double tol = 1e-5;
  double sample = 0.05;  // diagnostics interval (1/k)
};

struct RunResult {
  double dxy = NAN, theta = NAN, dxy_spectral = NAN, theta_spectral = NAN;
  double time = 0, t2 = NAN, f = NAN, dt = 0;
  double stretch_min = NAN, stretch_max = NAN, max_drift = 0, wall = 0;
  long steps = 0;
  bool steady = false;
  std::string error;
};

double TimeStep(const RunConfig& c) {
  const double es = 1.0 / c.ca, dl = 2.0 * kPi / c.markers;
  const double elastic = 1.5 * es + c.prestress * es;
  double sigma = elastic * kPi / (4.0 * dl);
  const double eb = c.eb * es;
  if (eb > 0.0) sigma = std::max(sigma, eb * kPi * kPi * kPi / (4.0 * dl * dl * dl));
  return c.cfl / sigma;
}

RunResult Run(const RunConfig& c) {
  RunResult r;
  const auto start = std::chrono::steady_clock::now();
  ehd::MembraneParameters p;
  p.shear_modulus = 1.0 / c.ca;
  p.tension = c.prestress / c.ca;
  p.bending_modulus = c.eb / c.ca;
  ehd::bie::CapsuleBem bem(p, ehd::CircleMarkers(c.markers, 1.0), 1.0, 1.0);
  r.dt = TimeStep(c);
  const double area0 = ehd::MeasureShape(bem.curve()).area;
  struct Sample {
    double t, d, theta;
  };
  std::vector<Sample> history;
  std::deque<Sample> window;  // last unit of time
  const int steps_per_sample = std::max(1, static_cast<int>(std::lround(c.sample / r.dt)));
  try {
    while (bem.time() < c.t_max - 1e-12) {
      for (int i = 0; i < steps_per_sample; ++i) bem.Step(r.dt);
      r.steps += steps_per_sample;
      const ehd::ShapeDiagnostics d = ehd::MeasureShape(bem.curve());
      if (!std::isfinite(d.dxy) || std::abs(d.area / area0 - 1.0) > 0.05) {
        r.error = "diverged at t = " + std::to_string(bem.time());
        break;
      }
      r.max_drift = std::max(r.max_drift, std::abs(d.area / area0 - 1.0));
      const Sample s{bem.time(), d.dxy, d.inclination};
      history.push_back(s);
      window.push_back(s);
      while (window.front().t < s.t - 1.0 - 1e-9) window.pop_front();
      if (s.t >= 2.0) {
        double dmin = s.d, dmax = s.d, tmin = s.theta, tmax = s.theta;
        for (const Sample& w : window) {
          dmin = std::min(dmin, w.d);
          dmax = std::max(dmax, w.d);
          tmin = std::min(tmin, w.theta);
          tmax = std::max(tmax, w.theta);
        }
        if (dmax - dmin < c.tol && tmax - tmin < c.tol) {
          r.steady = true;
          break;
        }
      }
    }
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  r.time = bem.time();
  const ehd::ShapeDiagnostics d = ehd::MeasureShape(bem.curve());
  r.dxy = d.dxy;
  r.theta = d.inclination;
  const ehd::bie::SpectralShape s = ehd::bie::MeasureSpectralShape(bem.layer(), bem.markers());
  r.dxy_spectral = s.dxy;
  r.theta_spectral = s.inclination;
  for (auto it = history.rbegin(); it != history.rend(); ++it) {
    if (std::abs(it->d - r.dxy) > 0.02 * r.dxy) {
      r.t2 = it->t;
      break;
    }
  }
  // Tank-treading period on the final shape: T = sum dl_k / |u_t,k|, u relative to the centroid
  // velocity (zero here by symmetry), t the unit tangent.
  Eigen::Matrix2Xd u;
  bem.Evaluate(bem.markers(), u);
  const ehd::ClosedCurve& curve = bem.curve();
  double period = 0.0;
  for (int k = 0; k < curve.size(); ++k) {
    const double dl = 0.5 * (curve.SegmentArcLength((k - 1 + curve.size()) % curve.size()) +
                             curve.SegmentArcLength(k));
    const Eigen::Vector2d t = curve.AtMarker(k).tangent;
    period += dl / std::abs(u.col(k).dot(t));
  }
  r.f = 4.0 * kPi / period;
  const std::vector<double>& stretch = bem.membrane().stretch();
  r.stretch_min = *std::min_element(stretch.begin(), stretch.end());
  r.stretch_max = *std::max_element(stretch.begin(), stretch.end());
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<double> ParseList(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) v.push_back(std::stod(item));
  return v;
}

void PrintHeader() {
  std::printf(
      "| Ca | prestress | E_b | M | dt | D_xy | theta/pi | D_xy (spectral) | theta/pi (spectral) "
      "| t (steady) | t_2%% | f | lambda range | max abs(dA) | steps | wall s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
}

void PrintRow(const RunConfig& c, const RunResult& r) {
  char t_steady[64];
  if (r.steady)
    std::snprintf(t_steady, sizeof t_steady, "%.2f", r.time);
  else
    std::snprintf(t_steady, sizeof t_steady, "%.0f (not steady)", r.time);
  std::printf(
      "| %g | %g | %g | %d | %.2e | %.6f | %.6f | %.6f | %.6f | %s | %.2f | %.3f | [%.3f, %.3f] "
      "| %.1e | %ld | %.1f |%s%s\n",
      c.ca, c.prestress, c.eb, c.markers, r.dt, r.dxy, r.theta / kPi, r.dxy_spectral,
      r.theta_spectral / kPi, t_steady, r.t2, r.f, r.stretch_min, r.stretch_max, r.max_drift,
      r.steps, r.wall, r.error.empty() ? "" : " ", r.error.c_str());
  std::fflush(stdout);
}

int RunCa(const std::vector<std::string>& args) {
  std::vector<double> cas = {0.0125, 0.025, 0.05, 0.1, 0.2};
  std::vector<double> markers = {128, 256};
  RunConfig base;
  for (std::size_t i = 0; i + 1 < args.size(); i += 2) {
    const std::string& k = args[i];
    const std::string& v = args[i + 1];
    if (k == "--ca") {
      cas = ParseList(v);
    } else if (k == "--markers") {
      markers = ParseList(v);
    } else if (k == "--prestress") {
      base.prestress = std::stod(v);
    } else if (k == "--eb") {
      base.eb = std::stod(v);
    } else if (k == "--cfl") {
      base.cfl = std::stod(v);
    } else if (k == "--t-max") {
      base.t_max = std::stod(v);
    } else if (k == "--tol") {
      base.tol = std::stod(v);
    } else {
      throw std::invalid_argument("unknown option " + k);
    }
  }
  if (args.size() % 2 != 0) throw std::invalid_argument("option without value: " + args.back());
  PrintHeader();
  std::vector<std::vector<RunResult>> all;
  for (double ca : cas) {
    all.emplace_back();
    for (double m : markers) {
      RunConfig c = base;
      c.ca = ca;
      c.markers = static_cast<int>(m);
      all.back().push_back(Run(c));
      PrintRow(c, all.back().back());
    }
  }
  if (markers.size() >= 2) {
    std::printf("\nM-convergence (M = %g vs finest M = %g):\n\n", markers[markers.size() - 2],
                markers.back());
    std::printf("| Ca | abs(D - D_fine) / D_fine | abs(theta/pi - fine) | abs(f - f_fine) |\n");
    std::printf("|---|---|---|---|\n");
    for (std::size_t i = 0; i < cas.size(); ++i) {
      const RunResult& a = all[i][markers.size() - 2];
      const RunResult& b = all[i].back();
      std::printf("| %g | %.1e | %.1e | %.1e |\n", cas[i], std::abs(a.dxy - b.dxy) / b.dxy,
                  std::abs(a.theta - b.theta) / kPi, std::abs(a.f - b.f));
    }
  }
  return 0;
}

int RunSelfCheck() {
  // (1) Uniformly stretched circle (Hookean, radius 1.2 on reference 1; tau = 0.2 E_s) and a
  // drop (gamma = 1): exact velocity 0.
  std::printf("Self-check 1: circle under uniform tension, max |u| (exact 0; force O(1))\n");
  for (int m : {64, 128, 256}) {
    ehd::MembraneParameters hook;
    hook.shear_modulus = 5.0;
    ehd::bie::CapsuleBem bem(hook, ehd::CircleMarkers(m, 1.0), 1.0, 0.0);
    Eigen::Matrix2Xd u;
    bem.Evaluate(1.2 * ehd::CircleMarkers(m, 1.0), u);
    ehd::MembraneParameters drop;
    drop.tension = 1.0;
    ehd::bie::CapsuleBem bem2(drop, ehd::CircleMarkers(m, 1.0), 1.0, 0.0);
    Eigen::Matrix2Xd u2;
    bem2.Evaluate(ehd::CircleMarkers(m, 1.0), u2);
    std::printf("  M = %3d: stretched Hookean circle %.1e, drop %.1e\n", m, u.cwiseAbs().maxCoeff(),
                u2.cwiseAbs().maxCoeff());
  }
  // (2) Drop, gamma = 1/Ca: D = Ca / sqrt(1 + 4 Ca^2), theta = pi/4 - atan(2 Ca)/2 (small
  // deformation, test/membrane/stokes_bie_test.cpp), t = 0.5.
  std::printf(
      "\nSelf-check 2: drop in shear at small Ca (theory D = Ca/sqrt(1+4Ca^2), "
      "theta = pi/4 - atan(2Ca)/2), t = 0.5\n");
  for (int m : {64, 128}) {
    for (double ca : {0.04, 0.02, 0.01}) {
      ehd::MembraneParameters p;
      p.tension = 1.0 / ca;
      ehd::bie::CapsuleBem bem(p, ehd::CircleMarkers(m, 1.0), 1.0, 1.0);
      const double dt = 0.4 * (2 * kPi / m) * ca;
      while (bem.time() < 0.5 - 1e-12) bem.Step(dt);
      const ehd::bie::SpectralShape s = ehd::bie::MeasureSpectralShape(bem.layer(), bem.markers());
      std::printf("  M = %3d Ca = %.2f: D/Ca = %.5f (theory %.5f), theta/pi = %.5f (theory %.5f)\n",
                  m, ca, s.dxy / ca, 1.0 / std::sqrt(1 + 4 * ca * ca), s.inclination / kPi,
                  0.25 - 0.5 * std::atan(2 * ca) / kPi);
    }
  }
  // (3) dt and M convergence of the capsule at Ca = 0.05 (t = 6, fixed end time).
  std::printf("\nSelf-check 3: capsule Ca = 0.05, state at t = 6 (fixed time)\n");
  PrintHeader();
  for (int m : {64, 128, 256}) {
    for (double cfl : {1.0, 0.5}) {
      if (m != 128 && cfl != 1.0) continue;
      RunConfig c;
      c.ca = 0.05;
      c.markers = m;
      c.cfl = cfl;
      c.t_max = 6.0;
      c.tol = 0.0;  // run to t_max
      PrintRow(c, Run(c));
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (!args.empty() && args[0] == "ca") return RunCa({args.begin() + 1, args.end()});
    if (!args.empty() && args[0] == "selfcheck") return RunSelfCheck();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "capsule_bem_bench: %s\n", e.what());
    return 2;
  }
  std::fprintf(stderr,
               "usage: capsule_bem_bench ca [--ca LIST] [--markers LIST] [--prestress P] "
               "[--eb E_b] [--cfl C] [--t-max T] [--tol TOL]\n"
               "       capsule_bem_bench selfcheck\n");
  return 2;
}
