// ehd_sim run: headless run of one scene with a CSV time series, VTK frames and checkpoints.
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>

#include "command.h"
#include "ehd_capsule/coupling/shown_measures.h"
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
    "                  [--restart FILE] [--sections FILE --sections-every N]\n"
    "                  [--summary-json FILE]\n\n"
    "Runs SCENE (a name in config/scenes or a path to a .yaml file). Prints the scene, the\n"
    "derived lattice values and the assembled pipeline, then a progress line.\n"
    "  --set key=value   override a scene key (nested: geometry.shape=ellipse); repeatable\n"
    "  --steps N         stop after N steps (1 to 1e12)\n"
    "  --until T         stop at time T in (0, 1e6] (units of 1/k with shear, else the scene's\n"
    "                    time unit)\n"
    "  --until-steady TOL  stop when, over the last unit of time, D_xy changed by less than\n"
    "                    TOL relative (TOL max(D_xy, 1e-3)) and theta by less than TOL pi\n"
    "                    (TOL in (0, 1]; default end: numerics.t_end)\n"
    "  --csv FILE        time series: step,t,dxy,inclination,area,tt_phase,... (every step,\n"
    "                    or every --csv-every N steps)\n"
    "  --vtk DIR         ParaView frames (fluid .vti, membrane .vtp, .pvd) every --vtk-every N\n"
    "  --checkpoint FILE --checkpoint-every N   write a checkpoint every N steps (and at the end)\n"
    "  --restart FILE    continue bit-for-bit from a checkpoint of the same scene\n"
    "  --sections FILE   the membrane's section in the shear plane every --sections-every N\n"
    "                    steps (default 100) as step,t,point,x,y in units of a about the\n"
    "                    centroid: the markers in 2D, the cut z = z_centroid of the mesh in 3D\n"
    "  --summary-json FILE  at the end (also after an error or an invalid scene), one JSON\n"
    "                    object: status (completed, steady, not_steady, step_cap,\n"
    "                    simulation_error, invalid_scene), reason, exit_status, the final\n"
    "                    state's values, steps, wall and CPU seconds, seconds per stage;\n"
    "                    written to FILE.tmp and renamed, so FILE exists only when complete\n"
    "Exit status 0 on success, 1 if the simulation stopped on an error (the message names the\n"
    "step and the quantity) or at the step cap numerics.max_steps before its end time, 2 on a\n"
    "usage error.\n";

// The most steps one run may take (numerics.max_steps' maximum) and the latest --until (the
// range of numerics.t_end): a horizon beyond them would not end.
constexpr long kMaxRunSteps = 1000000000000L;
constexpr double kMaxUntil = 1e6;

struct RunOptions {
  std::string scene_name, csv_path, vtk_dir, checkpoint_path, restart_path, sections_path,
      summary_path;
  std::vector<std::string> overrides;
  long steps = -1, csv_every = 1, vtk_every = 0, checkpoint_every = 0, sections_every = 100;
  double until = -1.0, steady_tol = -1.0, progress_s = 2.0;
  bool quiet = false;
};

RunOptions ParseRunOptions(const std::vector<std::string>& args) {
  RunOptions o;
  std::string &scene_name = o.scene_name, &csv_path = o.csv_path, &vtk_dir = o.vtk_dir,
              &checkpoint_path = o.checkpoint_path, &restart_path = o.restart_path,
              &sections_path = o.sections_path;
  std::vector<std::string>& overrides = o.overrides;
  long &steps = o.steps, &csv_every = o.csv_every, &vtk_every = o.vtk_every,
       &checkpoint_every = o.checkpoint_every, &sections_every = o.sections_every;
  double &until = o.until, &steady_tol = o.steady_tol, &progress_s = o.progress_s;
  bool& quiet = o.quiet;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--set")
      overrides.push_back(OptionValue(args, i));
    else if (a == "--steps")
      steps = ParseLongIn(a, OptionValue(args, i), 1, kMaxRunSteps);
    else if (a == "--until")
      until = ParseDoubleIn(a, OptionValue(args, i), 0.0, kMaxUntil, true, "a time",
                            " (as numerics.t_end)");
    else if (a == "--until-steady")
      steady_tol = ParseDoubleIn(a, OptionValue(args, i), 0.0, 1.0, true, "a relative tolerance");
    else if (a == "--csv")
      csv_path = PathValue(args, i);
    else if (a == "--csv-every")
      csv_every = ParseLong(a, OptionValue(args, i));
    else if (a == "--progress")
      progress_s = ParseDoubleIn(a, OptionValue(args, i), 0.0, 1e9, false, "a number of seconds");
    else if (a == "--quiet")
      quiet = true;
    else if (a == "--vtk")
      vtk_dir = PathValue(args, i);
    else if (a == "--vtk-every")
      vtk_every = ParseLong(a, OptionValue(args, i));
    else if (a == "--checkpoint")
      checkpoint_path = PathValue(args, i);
    else if (a == "--checkpoint-every")
      checkpoint_every = ParseLong(a, OptionValue(args, i));
    else if (a == "--restart")
      restart_path = PathValue(args, i);
    else if (a == "--sections")
      sections_path = PathValue(args, i);
    else if (a == "--sections-every")
      sections_every = ParseLong(a, OptionValue(args, i));
    else if (a == "--summary-json")
      o.summary_path = PathValue(args, i);
    else if (!a.empty() && a[0] == '-')
      throw UsageError("unknown option '" + a + "'");
    else if (scene_name.empty())
      scene_name = a;
    else
      throw UsageError("more than one scene given ('" + scene_name + "', '" + a + "')");
  }
  if (scene_name.empty()) throw UsageError("no scene given");
  // Given values are > 0 (checked above); -1 is "not given".
  if ((steps > 0) + (until > 0) + (steady_tol > 0) > 1) {
    throw UsageError("give at most one of --steps, --until, --until-steady");
  }
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

  return o;
}

std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string JsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

// Output files written only during or after the run (--summary-json, --checkpoint) are checked
// before it, as --csv is: `probe` (the file itself, or FILE.tmp) is opened for appending and
// removed again if it was not there.
void CheckWritable(const std::string& option, const std::string& path, const std::string& probe) {
  if (path.empty()) return;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw std::runtime_error(option + ": '" + path + "' is a directory, not a file");
  }
  const bool existed = std::filesystem::exists(probe, ec);
  {
    std::ofstream out(probe, std::ios::app);
    if (!out) {
      throw std::runtime_error(option + ": cannot write '" + probe + "': " + std::strerror(errno));
    }
  }
  if (!existed) std::filesystem::remove(probe, ec);
}

// How a run ended, for --summary-json.
struct RunEnd {
  std::string status;  // completed, steady, not_steady, step_cap, simulation_error, invalid_scene
  std::string reason;  // the error or the stop, in words
  int exit_status = 0;
};

// Writes the summary to path.tmp, then renames it to path: a reader never sees a partial file.
// sim is null when the scene could not be built.
void WriteSummaryJson(const RunOptions& o, const Simulation* sim, const RunEnd& end, double wall_s,
                      double cpu_s, long steps_taken) {
  if (o.summary_path.empty()) return;
  std::ostringstream j;
  j << "{\n  \"scene\": " << JsonString(o.scene_name) << ",\n  \"overrides\": [";
  for (std::size_t i = 0; i < o.overrides.size(); ++i) {
    j << (i ? ", " : "") << JsonString(o.overrides[i]);
  }
  j << "],\n  \"status\": " << JsonString(end.status)
    << ",\n  \"reason\": " << JsonString(end.reason) << ",\n  \"exit_status\": " << end.exit_status;
  if (sim != nullptr) {
    const SimulationState& s = sim->state();
    const std::pair<const char*, double> values[] = {{"t", s.time},
                                                     {"dxy", s.dxy},
                                                     {"inclination_over_pi", s.inclination / M_PI},
                                                     {"area", s.area},
                                                     {"area_drift", s.area_drift},
                                                     {"surface_drift", s.surface_drift},
                                                     {"d_field", s.d_field},
                                                     {"surface_flow", s.surface_flow},
                                                     {"volume_corrected", s.volume_corrected},
                                                     {"tt_phase", s.tt_phase},
                                                     {"stresslet_xy", s.stresslet_xy},
                                                     {"ca", s.ca},
                                                     {"ca_e", s.ca_e},
                                                     {"max_mach", s.max_mach},
                                                     {"gmres_residual", s.gmres_residual}};
    j << ",\n  \"dimension\": " << s.dimension << ",\n  \"step\": " << s.step
      << ",\n  \"gmres_iterations\": " << s.gmres_iterations;
    for (const auto& [key, value] : values) j << ",\n  \"" << key << "\": " << JsonNumber(value);
    j << ",\n  \"time_unit\": "
      << JsonString(sim->scene().has_shear() ? "1/k" : sim->units().time_unit);
    j << ",\n  \"stage_seconds\": {";
    const auto stages = sim->StageTimes();
    for (std::size_t i = 0; i < stages.size(); ++i) {
      j << (i ? ", " : "") << JsonString(stages[i].name) << ": " << JsonNumber(stages[i].seconds);
    }
    j << "}";
  }
  j << ",\n  \"steps_taken\": " << steps_taken << ",\n  \"wall_seconds\": " << JsonNumber(wall_s)
    << ",\n  \"cpu_seconds\": " << JsonNumber(cpu_s) << "\n}\n";
  const std::string tmp = o.summary_path + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.str();
    if (!out) throw std::runtime_error("--summary-json: cannot write '" + tmp + "'");
  }
  if (std::rename(tmp.c_str(), o.summary_path.c_str()) != 0) {
    throw std::runtime_error("--summary-json: cannot rename '" + tmp + "' to '" + o.summary_path +
                             "'");
  }
}

// The membrane's section in the shear plane about the centroid, in units of a (--sections): the
// markers in 2D, the cut z = z_centroid of the mesh in 3D.
class SectionWriter {
 public:
  SectionWriter(const std::string& path, bool append) {
    if (path.empty()) return;
    file_ = std::fopen(path.c_str(), append ? "a" : "w");
    if (file_ == nullptr) throw UsageError("--sections: cannot write '" + path + "'");
    if (!append) std::fprintf(file_, "step,t,point,x,y\n");
  }
  ~SectionWriter() { Close(); }
  bool open() const { return file_ != nullptr; }
  void Close() {
    if (file_ != nullptr) std::fclose(file_);
    file_ = nullptr;
  }
  void Write(const Simulation& sim) {
    if (file_ == nullptr) return;
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
      std::fprintf(file_, "%ld,%.10g,%zu,%.8g,%.8g\n", s.step, s.time, k, points[k].x() / a,
                   points[k].y() / a);
    }
    std::fflush(file_);
  }

 private:
  std::FILE* file_ = nullptr;
};

// Where the time went, stage by stage (wall time of each stage's part of the step).
void PrintStageShares(const Simulation& sim) {
  double total = 0.0;
  for (const auto& t : sim.StageTimes()) total += t.seconds;
  if (total <= 0.0) return;
  std::printf("time per stage:");
  for (const auto& t : sim.StageTimes()) {
    std::printf(" %s %.1f%%", t.name.c_str(), 100.0 * t.seconds / total);
  }
  std::printf("\n");
}

// How a run that did not fail ended (--summary-json's status and reason, the exit status).
RunEnd DecideRunEnd(const RunOptions& o, const Simulation& sim, double t_end, long max_steps,
                    bool steady, bool capped) {
  RunEnd end{"completed", "reached the end", 0};
  if (o.steps > 0) {
    end.reason = "reached " + std::to_string(o.steps) + " steps";
  } else if (steady) {
    end = {"steady", "D_xy and theta steady to " + FormatValue(o.steady_tol), 0};
  } else if (!capped) {
    end.reason = "reached t = " + FormatValue(t_end);
  }
  if (!capped && o.steady_tol > 0 && !steady) {
    end = {
        "not_steady",
        "not steady to " + FormatValue(o.steady_tol) + " by t = " + FormatValue(sim.state().time),
        0};
  }
  if (capped) {
    std::ostringstream why;
    why << "stopped at the step cap numerics.max_steps = " << max_steps
        << " at t = " << sim.state().time << " before t = " << t_end
        << " (raise numerics.max_steps, or give --until T)";
    std::cerr << "ehd_sim run: " << why.str() << '\n';
    end = {"step_cap", why.str(), 1};
  }
  return end;
}

int RunScene(const std::vector<std::string>& args) {
  const RunOptions o = ParseRunOptions(args);
  CheckWritable("--summary-json", o.summary_path, o.summary_path + ".tmp");
  CheckWritable("--checkpoint", o.checkpoint_path, o.checkpoint_path);
  std::error_code ec;
  if (std::filesystem::is_directory(o.restart_path, ec)) {
    throw std::runtime_error("--restart: '" + o.restart_path +
                             "' is a directory, not a checkpoint");
  }
  const std::string &csv_path = o.csv_path, &vtk_dir = o.vtk_dir,
                    &checkpoint_path = o.checkpoint_path, &restart_path = o.restart_path,
                    &sections_path = o.sections_path;
  const long steps = o.steps, csv_every = o.csv_every, checkpoint_every = o.checkpoint_every,
             sections_every = o.sections_every;
  long vtk_every = o.vtk_every;
  const double until = o.until, steady_tol = o.steady_tol, progress_s = o.progress_s;
  const bool quiet = o.quiet;
  const std::clock_t cpu_start = std::clock();
  const auto wall_start = std::chrono::steady_clock::now();
  auto seconds = [&]() {
    return std::pair<double, double>(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count(),
        static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
  };
  std::unique_ptr<Simulation> built;
  try {
    built = std::make_unique<Simulation>(LoadScene(o.scene_name, o.overrides));
  } catch (const std::exception& e) {
    const auto [wall_s, cpu_s] = seconds();
    WriteSummaryJson(o, nullptr, {"invalid_scene", e.what(), 1}, wall_s, cpu_s, 0);
    throw;  // main prints it and exits 1
  }
  Simulation& sim = *built;
  const Scene& scene = sim.scene();
  if (!quiet) {
    std::cout << DescribeScene(scene) << DescribeUnits(scene, sim.units()) << sim.Pipeline();
  }
  if (!restart_path.empty()) {
    sim.Restore(restart_path);
    std::cout << "restarted from " << restart_path << " at step " << sim.state().step
              << ", t = " << sim.state().time << '\n';
  }
  const double t_end = until > 0 ? until : scene.numerics.t_end;
  if (until > 0) {
    const double needed = (until - sim.state().time) / sim.units().dt;
    if (!(needed <= kMaxRunSteps)) {
      throw UsageError("--until " + FormatValue(until) + " needs " + FormatValue(needed) +
                       " steps of dt = " + FormatValue(sim.units().dt) + ", more than the " +
                       std::to_string(kMaxRunSteps) + " steps a run may take");
    }
  }
  // An explicit --until T is not capped; the scene's t_end and --until-steady are capped by
  // numerics.max_steps, and reaching the cap before t_end is reported as a failure.
  const long max_steps = steps > 0   ? sim.state().step + steps
                         : until > 0 ? std::numeric_limits<long>::max()
                                     : scene.numerics.max_steps;
  const char* unit = scene.has_shear() ? "1/k" : sim.units().time_unit.c_str();
  if (!quiet) {
    if (steps > 0)
      std::cout << "running " << steps << " steps\n";
    else
      std::cout << "running to t = " << t_end << " (" << unit << ")"
                << (steady_tol > 0 ? ", or until steady to " + std::to_string(steady_tol) : "")
                << (until > 0 ? std::string() : ", at most " + std::to_string(max_steps) + " steps")
                << '\n';
  }

  std::unique_ptr<TimeSeriesCsv> csv;
  if (!csv_path.empty()) {
    csv = std::make_unique<TimeSeriesCsv>(csv_path, sim, !restart_path.empty());
    if (restart_path.empty()) csv->Write(sim);
  }
  SectionWriter sections(sections_path, !restart_path.empty());
  auto write_section = [&]() { sections.Write(sim); };
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
        "%sstep %ld  t = %.4g  %s  Mach = %.3g%s  "
        "(%.1f steps/s)\n",
        prefix, s.step, s.time, FormatMeasures(s, MeasuresOf(sim.scene()), "  ").c_str(),
        s.max_mach,
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
    sections.Close();
    const auto [wall_s, cpu_s] = seconds();
    WriteSummaryJson(o, &sim, {"simulation_error", e.what(), 1}, wall_s, cpu_s,
                     sim.state().step - first_step);
    return 1;
  }
  if (csv && sim.state().step % csv_every != 0) csv->Write(sim);
  if (!checkpoint_path.empty()) sim.Save(checkpoint_path);
  if (sections.open() && sim.state().step % sections_every != 0) write_section();
  sections.Close();
  progress("final: ");
  const bool capped = steps <= 0 && !steady && sim.state().time < t_end - 1e-12;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long taken = sim.state().step - first_step;
  std::printf("%ld steps in %.2f s (%.3g ms/step)\n", taken, wall,
              taken > 0 ? 1e3 * wall / taken : 0.0);
  if (!quiet && taken > 0) PrintStageShares(sim);
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
  const RunEnd end = DecideRunEnd(o, sim, t_end, max_steps, steady, capped);
  const auto [wall_s, cpu_s] = seconds();
  WriteSummaryJson(o, &sim, end, wall_s, cpu_s, taken);
  return end.exit_status;
}

const CommandRegistration kRun({"run", "run a scene headless (CSV time series, VTK, checkpoints)",
                                kUsage, RunScene});

}  // namespace
}  // namespace ehd::cli
