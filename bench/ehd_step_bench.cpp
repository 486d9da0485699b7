// Where the time of one coupled EHD step goes (song2019 sec. 3.6, the step of
// coupling/simulation.cpp): the same five stages assembled from the component libraries, each
// timed with steady_clock over S steps after W warm-up steps:
//   electric  LeakyDielectricSolver::Solve(curve, step) (fast IIM + GMRES, warm-started from the
//             extrapolation of the last two solutions, as the simulation does) and F_E
//   membrane  MembraneModel::ComputeForce and the arc elements dl
//   spread    F dl to the grid (eq. (106))
//   lbm       one D2Q9 MRT step
//   interp    u^{n+1} at the markers (eq. (104)), forward Euler move, curve update, diagnostics
// and, inside the electric solve, on the final curve: the interface classification (sides,
// band, closest points), the WLS fit set-up and one fast Poisson solve (a Solve makes
// iterations + 2 of them: b = R(0), one per GMRES iteration, the final potential).
// Times are process CPU time (CLOCK_PROCESS_CPUTIME_ID; run with OMP_NUM_THREADS=1): on a shared
// machine wall time mostly measures the other users' load. It then times ehd::Simulation::Step with
// the field off (Ca_E = 0, no solve) and on, and with numerics.electric_every = 1, 2, 5, 10.
//
// For a 3D scene (dimension: 3) it prints the split of Simulation::Step over its own stages
// (Simulation::StageTimes) instead, as it does at the end for 2D.
//
// usage: ehd_step_bench [SCENE] [--steps S] [--warmup W] [--set key=value ...]
//   (default shear_field, S = 2000, W = 500; run with OMP_NUM_THREADS=1 on a shared machine)
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/diagnostics/shape_diagnostics.h"
#include "ehd_capsule/electric/fast_poisson_solver.h"
#include "ehd_capsule/electric/interface_classification.h"
#include "ehd_capsule/electric/leaky_dielectric_solver.h"
#include "ehd_capsule/electric/normal_derivative_fit.h"
#include "ehd_capsule/geometry/initial_shapes.h"
#include "ehd_capsule/ib/immersed_boundary.h"
#include "ehd_capsule/ib/marker_update.h"
#include "ehd_capsule/lbm/lattice_boltzmann.h"
#include "ehd_capsule/lbm/openmp_wait.h"
#include "ehd_capsule/membrane/membrane_model.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace {

// Process CPU time in ms.
double CpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// ms per Simulation::Step over `steps` steps after `warmup`.
double SimulationMsPerStep(const ehd::Scene& scene, long warmup, long steps, double* gmres) {
  ehd::Simulation sim(scene);
  for (long i = 0; i < warmup; ++i) sim.Step();
  long iterations = 0;
  const double t0 = CpuMs();
  for (long i = 0; i < steps; ++i) {
    sim.Step();
    iterations += sim.state().gmres_iterations;
  }
  const double ms = (CpuMs() - t0) / steps;
  if (gmres) *gmres = static_cast<double>(iterations) / steps;
  return ms;
}

// The split of ehd::Simulation::Step over its own stages (Simulation::StageTimes, wall time);
// the only table for 3D scenes, whose stages are not reassembled here.
int StageSplit(const ehd::Scene& scene, long warmup, long steps) {
  ehd::Simulation sim(scene);
  std::printf("scene %s (%dD): N = %d, %ld points, %ld steps after %ld warm-up\n",
              scene.name.c_str(), scene.dimension, scene.N,
              static_cast<long>(sim.state().markers.cols()), steps, warmup);
  for (long i = 0; i < warmup; ++i) sim.Step();
  sim.ResetStageTimes();
  const double t0 = CpuMs();
  for (long i = 0; i < steps; ++i) sim.Step();
  const double cpu = (CpuMs() - t0) / steps;
  double total = 0;
  for (const auto& t : sim.StageTimes()) total += t.seconds;
  std::printf("Simulation::Step by stage (wall ms per step):\n%-12s %10s %8s\n", "stage", "ms/step",
              "share");
  for (const auto& t : sim.StageTimes()) {
    std::printf("%-12s %10.4f %7.1f%%\n", t.name.c_str(), 1e3 * t.seconds / steps,
                100.0 * t.seconds / total);
  }
  std::printf("%-12s %10.4f   (process CPU %.4f ms/step)\n", "total", 1e3 * total / steps, cpu);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  ehd::RestartWithPassiveOpenMpWait(argv);  // lbm/openmp_wait.h
  std::string scene_name = "shear_field";
  std::vector<std::string> overrides;
  long steps = 2000, warmup = 500;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--steps" && i + 1 < argc) {
      steps = std::atol(argv[++i]);
    } else if (a == "--warmup" && i + 1 < argc) {
      warmup = std::atol(argv[++i]);
    } else if (a == "--set" && i + 1 < argc) {
      overrides.push_back(argv[++i]);
    } else if (!a.empty() && a[0] != '-') {
      scene_name = a;
    } else {
      std::fprintf(stderr, "usage: ehd_step_bench [SCENE] [--steps S] [--warmup W] [--set k=v]\n");
      return 2;
    }
  }
  if (steps < 1 || warmup < 0) {
    std::fprintf(stderr, "ehd_step_bench: --steps must be >= 1 and --warmup >= 0\n");
    return 2;
  }
  const ehd::Scene scene = ehd::LoadScene(scene_name, overrides);
  if (scene.dimension == 3) return StageSplit(scene, warmup, steps);
  const ehd::LatticeUnits units = ehd::DeriveLatticeUnits(scene);
  std::printf("scene %s: N = %d, M = %d, Ca_E = %g, %ld steps after %ld warm-up\n",
              scene.name.c_str(), scene.N, scene.M, scene.Ca_E, steps, warmup);

  // --- Stage timing on the assembled components (forward Euler, field solved every step).
  ehd::LbmParameters lp;
  lp.nx = lp.ny = scene.N;
  lp.viscosity = units.viscosity;
  lp.threads = scene.numerics.threads;
  lp.boundary =
      scene.has_shear() ? ehd::FluidBoundary::kShearWalls : ehd::FluidBoundary::kClosedBox;
  ehd::LatticeBoltzmann2D fluid(lp);
  const ehd::Grid2D grid = fluid.grid();
  if (scene.has_shear())
    fluid.InitializeShear(units.shear_rate);
  else
    fluid.InitializeAtRest();
  ehd::ImmersedBoundary ib(grid, scene.has_shear(), false);
  Eigen::Matrix2Xd X = ehd::CircleMarkers(scene.M, units.radius);
  ehd::ClosedCurve curve(X);
  ehd::MembraneParameters mp;
  if (scene.membrane == ehd::MembraneKind::kDrop) {
    mp.tension = units.tension;
  } else {
    mp.shear_modulus = units.tension;
    mp.membrane_viscosity = units.membrane_viscosity;
    mp.bending_modulus = units.bending_modulus;
  }
  ehd::MembraneModel membrane(mp, curve);
  ehd::LeakyDielectricSolver<2> electric(grid, units.sigma_minus, units.sigma_plus, units.eps_minus,
                                         units.eps_plus);
  electric.SetAppliedField(units.field);
  Eigen::Matrix2Xd density, force(2, scene.M), U;
  std::vector<double> dl;
  double t_electric = 0, t_membrane = 0, t_spread = 0, t_lbm = 0, t_interp = 0;
  long iterations = 0;
  for (long n = 0; n < warmup + steps; ++n) {
    const bool timed = n >= warmup;
    const double t0 = CpuMs();
    const ehd::InterfaceSolveReport& report = electric.Solve(curve, static_cast<double>(n));
    const Eigen::Matrix2Xd& fe = electric.force();
    const double t1 = CpuMs();
    membrane.ComputeForce(curve, 1.0, density);
    ehd::MarkerArcElements(curve, dl);
    for (int k = 0; k < scene.M; ++k) force.col(k) = (density.col(k) + fe.col(k)) * dl[k];
    const double t2 = CpuMs();
    fluid.ClearForce();
    ib.Spread(X, force, fluid.force_x(), fluid.force_y());
    const double t3 = CpuMs();
    fluid.Step();
    const double t4 = CpuMs();
    ib.Interpolate(fluid.ux(), fluid.uy(), X, U);
    X += U;
    if (scene.has_shear()) ehd::WrapCurveIntoDomain(grid, X);
    curve.Update(X);
    const ehd::ShapeDiagnostics d = ehd::MeasureShape(curve);
    const double t5 = CpuMs();
    if (timed) {
      t_electric += (t1 - t0);
      t_membrane += (t2 - t1);
      t_spread += (t3 - t2);
      t_lbm += (t4 - t3);
      t_interp += (t5 - t4);
      iterations += report.iterations;
    }
    if (n + 1 == warmup + steps) std::printf("final D_xy = %.5f\n", d.dxy);
  }
  const double total = t_electric + t_membrane + t_spread + t_lbm + t_interp;
  std::printf(
      "\nstage timing (CPU ms per step, field solved every step, warm-started GMRES: %.2f "
      "iterations per step):\n",
      static_cast<double>(iterations) / steps);
  std::printf("%-10s %10s %8s\n", "stage", "ms/step", "share");
  const struct {
    const char* name;
    double ms;
  } rows[] = {{"electric", t_electric},
              {"membrane", t_membrane},
              {"spread", t_spread},
              {"lbm", t_lbm},
              {"interp", t_interp}};
  for (const auto& r : rows)
    std::printf("%-10s %10.4f %7.1f%%\n", r.name, r.ms / steps, 100.0 * r.ms / total);
  std::printf("%-10s %10.4f\n", "total", total / steps);

  // --- Inside the electric solve, on the final curve (defaults of FastIimOptions).
  {
    const int repeats = 200;
    ehd::InterfaceClassification classes;
    ehd::NormalDerivativeFit fit;
    ehd::FastPoissonSolver poisson(
        grid, ehd::PoissonBoundaries{ehd::BoundaryKind::kNeumann, ehd::BoundaryKind::kNeumann,
                                     ehd::BoundaryKind::kDirichlet, ehd::BoundaryKind::kDirichlet});
    std::vector<double> rhs(grid.size(), 1e-3), phi(grid.size());
    double t_class = 0, t_fit = 0, t_poisson = 0, t_solve = 0;
    int iters = 0;
    for (int r = 0; r < repeats; ++r) {
      const double a = CpuMs();
      classes.Update(grid, curve, 3.5 * grid.h);
      const double b = CpuMs();
      fit.Update(curve, classes, 3.0 * grid.h);
      const double c = CpuMs();
      poisson.Solve(rhs, phi);
      const double d = CpuMs();
      iters += electric.Solve(curve).iterations;
      const double e = CpuMs();
      t_class += b - a;
      t_fit += c - b;
      t_poisson += d - c;
      t_solve += e - d;
    }
    const double per_solve = t_solve / repeats;
    const double poisson_count = static_cast<double>(iters) / repeats + 2.0;
    std::printf("\ninside one electric Solve (same curve, warm start, CPU ms; %d band points):\n",
                classes.band_size());
    std::printf("%-34s %10.4f\n", "LeakyDielectricSolver::Solve", per_solve);
    std::printf("%-34s %10.4f\n", "  interface classification", t_class / repeats);
    std::printf("%-34s %10.4f\n", "  WLS fit set-up", t_fit / repeats);
    std::printf("  fast Poisson solves: %.2f x %.4f = %.4f\n", poisson_count, t_poisson / repeats,
                poisson_count * t_poisson / repeats);
    std::printf("%-34s %10.4f\n", "  rest (band J set-up, field, F_E)",
                per_solve - (t_class + t_fit) / repeats - poisson_count * t_poisson / repeats);
  }

  // --- The real Simulation::Step, field off and on, and with sub-stepping.
  std::printf("\nehd::Simulation::Step (CPU ms per step):\n%-32s %10s %12s %8s\n", "configuration",
              "ms/step", "GMRES/step", "ratio");
  std::vector<std::string> off = overrides;
  off.push_back("Ca_E=0");
  const double ms_off =
      SimulationMsPerStep(ehd::LoadScene(scene_name, off), warmup, steps, nullptr);
  std::printf("%-32s %10.4f %12s %8.2f\n", "Ca_E = 0 (no solve)", ms_off, "-", 1.0);
  for (int every : {1, 2, 5, 10}) {
    std::vector<std::string> on = overrides;
    on.push_back("numerics.electric_every=" + std::to_string(every));
    double gmres = 0;
    const double ms = SimulationMsPerStep(ehd::LoadScene(scene_name, on), warmup, steps, &gmres);
    char label[64];
    std::snprintf(label, sizeof label, "Ca_E = %g, electric_every = %d", scene.Ca_E, every);
    std::printf("%-32s %10.4f %12.2f %8.2f\n", label, ms, gmres, ms / ms_off);
  }
  std::printf("\n");
  StageSplit(scene, warmup, steps);
  return 0;
}
