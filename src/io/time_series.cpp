#include "ehd_capsule/io/time_series.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace ehd {

std::string TimeSeriesHeader(int dimension) {
  return std::string(
             "step,t,dxy,inclination,area,tt_phase,area_drift,ca,ca_e,fe_x,fe_y,"
             "gmres_iterations,max_mach,surface_drift") +
         (dimension == 3 ? ",fe_z,d_field,surface_flow,volume_corrected" : "");
}

TimeSeriesCsv::TimeSeriesCsv(const std::string& path, const Simulation& sim, bool append)
    : path_(path) {
  std::error_code ec;
  const bool has_rows =
      append && std::filesystem::exists(path, ec) && std::filesystem::file_size(path, ec) > 0;
  out_.open(path, append ? std::ios::app : std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write the time series " + path);
  if (!has_rows) out_ << TimeSeriesHeader(sim.state().dimension) << '\n';
}

void TimeSeriesCsv::Write(const Simulation& sim) {
  const SimulationState& s = sim.state();
  const double a = sim.units().radius;
  const double t_scale = sim.units().tension * a;
  // The area column: enclosed area / (pi a^2) in 2D, enclosed volume / (4/3 pi a^3) in 3D.
  const double size_scale = s.dimension == 3 ? 4.0 / 3.0 * M_PI * a * a * a : M_PI * a * a;
  char line[512];
  std::snprintf(line, sizeof line,
                "%ld,%.10g,%.10g,%.10g,%.10g,%.10g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.6g,%.6g", s.step,
                s.time, s.dxy, s.inclination, s.area / size_scale, s.tt_phase, s.area_drift, s.ca,
                s.ca_e, s.electric_force_total.x() / t_scale, s.electric_force_total.y() / t_scale,
                s.gmres_iterations, s.max_mach, s.surface_drift);
  out_ << line;
  if (s.dimension == 3) {
    std::snprintf(line, sizeof line, ",%.6g,%.10g,%.6g,%.6g", s.electric_force_total.z() / t_scale,
                  s.d_field, s.surface_flow, s.volume_corrected);
    out_ << line;
  }
  out_ << '\n';
  if (!out_) throw std::runtime_error("writing the time series " + path_ + " failed");
}

}  // namespace ehd
