// ehd_sim run: headless run of one scene with a CSV time series, VTK frames and checkpoints.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>

#include "command.h"
#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/coupling/steady_state.h"
#include "ehd_capsule/geometry/triangle_mesh.h"
#include "ehd_capsule/io/time_series.h"
#include "ehd_capsule/io/vtk_output.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd::cli {
namespace {

const char* kUsage =
    "usage: ehd_sim run SCENE [--set key=value ...] [--steps N | --until T | --until-steady TOL]\n"
    "                  [--csv FILE] [--csv-every N] [--progress SECONDS] [--quiet]\n"
    "                  [--vtk DIR --vtk-every N] [--checkpoint-every N --checkpoint FILE]\n"
    "                  [--restart FILE] [--sections FILE --sections-every N]\n\n"
    "Runs SCENE (a name in config/scenes or a path to a .yaml file). Prints the scene, the\n"
    "derived lattice values and the assembled pipeline, then a progress line.\n"
    "  --set key=value   override a scene key (nested: geometry.shape=ellipse); repeatable\n"
    "  --steps N         stop after N steps\n"
    "  --until T         stop at time T (units of 1/k with shear, else the scene's time unit)\n"
    "  --until-steady TOL  stop when, over the last unit of time, D_xy changed by less than\n"
    "                    TOL relative (TOL max(D_xy, 1e-3)) and theta by less than TOL pi\n"
    "                    (default end: numerics.t_end)\n"
    "  --csv FILE        time series: step,t,dxy,inclination,area,tt_phase,... (every step,\n"
    "                    or every --csv-every N steps)\n"
    "  --vtk DIR         ParaView frames (fluid .vti, membrane .vtp, .pvd) every --vtk-every N\n"
    "  --checkpoint FILE --checkpoint-every N   write a checkpoint every N steps (and at the end)\n"
    "  --restart FILE    continue bit-for-bit from a checkpoint of the same scene\n"
    "  --sections FILE   the membrane's section in the shear plane every --sections-every N\n"
    "                    steps (default 100) as step,t,point,x,y in units of a about the\n"
    "                    centroid: the markers in 2D, the cut z = z_centroid of the mesh in 3D\n"
    "Exit status 0 on success, 1 if the simulation stopped on an error (the message names the\n"
    "step and the quantity) or at the step cap numerics.max_steps before its end time, 2 on a\n"
    "usage error.\n";

int RunScene(const std::vector<std::string>& args) {
  std::string scene_name, csv_path, vtk_dir, checkpoint_path, restart_path, sections_path;
  std::vector<std::string> overrides;
  long steps = -1, csv_every = 1, vtk_every = 0, checkpoint_every = 0, sections_every = 100;
  double until = -1.0, steady_tol = -1.0, progress_s = 2.0;
  bool quiet = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--set")
      overrides.push_back(OptionValue(args, i));
    else if (a == "--steps")
      steps = ParseLong(a, OptionValue(args, i));
    else if (a == "--until")
      until = ParseDouble(a, OptionValue(args, i));
    else if (a == "--until-steady")
      steady_tol = ParseDouble(a, OptionValue(args, i));
    else if (a == "--csv")
      csv_path = OptionValue(args, i);
    else if (a == "--csv-every")
      csv_every = ParseLong(a, OptionValue(args, i));
    else if (a == "--progress")
      progress_s = ParseDouble(a, OptionValue(args, i));
    else if (a == "--quiet")
      quiet = true;
    else if (a == "--vtk")
      vtk_dir = OptionValue(args, i);
    else if (a == "--vtk-every")
      vtk_every = ParseLong(a, OptionValue(args, i));
    else if (a == "--checkpoint")
      checkpoint_path = OptionValue(args, i);
    else if (a == "--checkpoint-every")
      checkpoint_every = ParseLong(a, OptionValue(args, i));
    else if (a == "--restart")
      restart_path = OptionValue(args, i);
    else if (a == "--sections")
      sections_path = OptionValue(args, i);
    else if (a == "--sections-every")
      sections_every = ParseLong(a, OptionValue(args, i));
    else if (!a.empty() && a[0] == '-')
      throw UsageError("unknown option '" + a + "'");
    else if (scene_name.empty())
      scene_name = a;
    else
      throw UsageError("more than one scene given ('" + scene_name + "', '" + a + "')");
  }
  if (scene_name.empty()) throw UsageError("no scene given");
  if ((steps >= 0) + (until >= 0) + (steady_tol >= 0) > 1) {
    throw UsageError("give at most one of --steps, --until, --until-steady");
  }
  if (steps == 0 || steps < -1) throw UsageError("--steps must be >= 1");
  if (csv_every < 1) throw UsageError("--csv-every must be >= 1");
  if (sections_every < 1) throw UsageError("--sections-every must be >= 1");
  if (vtk_every < 0 || (!vtk_dir.empty() && vtk_every == 0)) {
    if (!vtk_dir.empty() && vtk_every == 0)
      vtk_every = 100;
    else
      throw UsageError("--vtk-every must be >= 1");
  }
  if (checkpoint_every < 0) throw UsageError("--checkpoint-every must be >= 1");
  if (checkpoint_every > 0 && checkpoint_path.empty()) {
    throw UsageError("--checkpoint-every needs --checkpoint FILE");
  }
  if (steady_tol == 0.0) throw UsageError("--until-steady needs a tolerance > 0");

  const Scene scene = LoadScene(scene_name, overrides);
  Simulation sim(scene);
  if (!quiet) {
    std::cout << DescribeScene(scene) << DescribeUnits(scene, sim.units()) << sim.Pipeline();
  }
  if (!restart_path.empty()) {
    sim.Restore(restart_path);
    std::cout << "restarted from " << restart_path << " at step " << sim.state().step
              << ", t = " << sim.state().time << '\n';
  }
  const double t_end = until >= 0 ? until : scene.numerics.t_end;
  // An explicit --until T is not capped; the scene's t_end and --until-steady are capped by
  // numerics.max_steps, and reaching the cap before t_end is reported as a failure.
  const long max_steps = steps > 0    ? sim.state().step + steps
                         : until >= 0 ? std::numeric_limits<long>::max()
                                      : scene.numerics.max_steps;
  const char* unit = scene.has_shear() ? "1/k" : sim.units().time_unit.c_str();
  if (!quiet) {
    if (steps > 0)
      std::cout << "running " << steps << " steps\n";
    else
      std::cout << "running to t = " << t_end << " (" << unit << ")"
                << (steady_tol > 0 ? ", or until steady to " + std::to_string(steady_tol) : "")
                << (until >= 0 ? std::string()
                               : ", at most " + std::to_string(max_steps) + " steps")
                << '\n';
  }

  std::unique_ptr<TimeSeriesCsv> csv;
  if (!csv_path.empty()) {
    csv = std::make_unique<TimeSeriesCsv>(csv_path, sim, !restart_path.empty());
    if (restart_path.empty()) csv->Write(sim);
  }
  std::FILE* sections = nullptr;
  if (!sections_path.empty()) {
    sections = std::fopen(sections_path.c_str(), restart_path.empty() ? "w" : "a");
    if (sections == nullptr) throw UsageError("--sections: cannot write '" + sections_path + "'");
    if (restart_path.empty()) std::fprintf(sections, "step,t,point,x,y\n");
  }
  // The shear-plane section about the centroid, in units of a.
  auto write_section = [&]() {
    if (sections == nullptr) return;
    const SimulationState& s = sim.state();
    const Eigen::Vector3d c = s.markers.rowwise().mean();
    const double a = sim.units().radius;
    std::vector<Eigen::Vector2d> points;
    if (sim.dimension() == 3) {
      std::vector<TriangleMesh::Triangle> triangles;
      for (const auto& t : sim.triangles()) triangles.push_back({t[0], t[1], t[2]});
      const TriangleMesh mesh(s.markers, triangles);
      const Eigen::Vector3d centroid = Centroid(mesh);
      points = CrossSectionZ(mesh, centroid.z());
      for (auto& p : points) p -= centroid.head<2>();
    } else {
      for (int k = 0; k < s.markers.cols(); ++k)
        points.push_back(s.markers.col(k).head<2>() - c.head<2>());
    }
    for (std::size_t k = 0; k < points.size(); ++k) {
      std::fprintf(sections, "%ld,%.10g,%zu,%.8g,%.8g\n", s.step, s.time, k, points[k].x() / a,
                   points[k].y() / a);
    }
    std::fflush(sections);
  };
  if (restart_path.empty()) write_section();
  std::unique_ptr<VtkSeries> vtk;
  if (!vtk_dir.empty()) {
    vtk = std::make_unique<VtkSeries>(vtk_dir);
    vtk->WriteFrame(sim);
  }

  SteadyStateMonitor monitor(steady_tol > 0 ? steady_tol : 1.0);
  const auto start = std::chrono::steady_clock::now();
  auto last_print = start;
  const long first_step = sim.state().step;
  bool steady = false;
  auto progress = [&](const char* prefix) {
    const SimulationState& s = sim.state();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf(
        "%sstep %ld  t = %.4g  D_xy = %.5f  theta/pi = %.4f  area drift = %.2e  Mach = %.3g%s  "
        "(%.1f steps/s)\n",
        prefix, s.step, s.time, s.dxy, s.inclination / M_PI, s.area_drift, s.max_mach,
        sim.has_electric_field() ? ("  GMRES " + std::to_string(s.gmres_iterations)).c_str() : "",
        wall > 0 ? (s.step - first_step) / wall : 0.0);
    std::fflush(stdout);
  };

  try {
    while (true) {
      const SimulationState& s = sim.state();
      if (steps > 0 ? s.step >= max_steps : (s.time >= t_end - 1e-12 || s.step >= max_steps)) {
        break;
      }
      sim.Step();
      if (csv && s.step % csv_every == 0) csv->Write(sim);
      if (vtk && s.step % vtk_every == 0) vtk->WriteFrame(sim);
      if (s.step % sections_every == 0) write_section();
      if (checkpoint_every > 0 && s.step % checkpoint_every == 0) sim.Save(checkpoint_path);
      if (steady_tol > 0 && monitor.Update(s.time, s.dxy, s.inclination)) {
        steady = true;
        break;
      }
      const auto now = std::chrono::steady_clock::now();
      if (!quiet && std::chrono::duration<double>(now - last_print).count() >= progress_s) {
        last_print = now;
        progress("");
      }
    }
  } catch (const SimulationError& e) {
    progress("last state: ");
    std::cerr << "ehd_sim run: simulation stopped: " << e.what() << '\n';
    if (csv) csv->Write(sim);
    write_section();
    if (sections != nullptr) std::fclose(sections);
    return 1;
  }
  if (csv && sim.state().step % csv_every != 0) csv->Write(sim);
  if (!checkpoint_path.empty()) sim.Save(checkpoint_path);
  if (sections != nullptr) {
    if (sim.state().step % sections_every != 0) write_section();
    std::fclose(sections);
  }
  progress("final: ");
  const bool capped = steps <= 0 && !steady && sim.state().time < t_end - 1e-12;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long taken = sim.state().step - first_step;
  std::printf("%ld steps in %.2f s (%.3g ms/step)\n", taken, wall,
              taken > 0 ? 1e3 * wall / taken : 0.0);
  if (!quiet && taken > 0) {
    // Where the time went, stage by stage (wall time of each stage's part of the step).
    double total = 0.0;
    for (const auto& t : sim.StageTimes()) total += t.seconds;
    if (total > 0.0) {
      std::printf("time per stage:");
      for (const auto& t : sim.StageTimes()) {
        std::printf(" %s %.1f%%", t.name.c_str(), 100.0 * t.seconds / total);
      }
      std::printf("\n");
    }
  }
  if (steady_tol > 0) {
    if (steady) {
      std::printf(
          "steady: D_xy and theta changed by less than %g over the last unit of time "
          "(t = %.4g): D_xy = %.6f, theta/pi = %.5f\n",
          steady_tol, sim.state().time, sim.state().dxy, sim.state().inclination / M_PI);
    } else {
      std::printf("NOT steady to %g by t = %.4g\n", steady_tol, sim.state().time);
    }
  }
  if (csv) std::cout << "time series: " << csv->path() << '\n';
  if (vtk)
    std::cout << "VTK: " << vtk_dir << "/fluid.pvd, " << vtk_dir << "/membrane.pvd ("
              << vtk->frames() << " frames)\n";
  if (!checkpoint_path.empty()) std::cout << "checkpoint: " << checkpoint_path << '\n';
  if (capped) {
    std::cerr << "ehd_sim run: stopped at the step cap numerics.max_steps = " << max_steps
              << " at t = " << sim.state().time << " before t = " << t_end
              << " (raise numerics.max_steps, or give --until T)\n";
    return 1;
  }
  return 0;
}

const CommandRegistration kRun({"run", "run a scene headless (CSV time series, VTK, checkpoints)",
                                kUsage, RunScene});

}  // namespace
}  // namespace ehd::cli
