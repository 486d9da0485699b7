#include "ehd_capsule/io/vtk_output.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace ehd {
namespace {

std::ofstream Open(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out.precision(9);
  return out;
}

std::string FrameName(const std::string& stem, long step, const char* ext) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%09ld.%s", stem.c_str(), step, ext);
  return name;
}

}  // namespace

VtkSeries::VtkSeries(const std::string& directory) : directory_(directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (!std::filesystem::is_directory(directory_)) {
    throw std::runtime_error("--vtk: cannot create directory " + directory_);
  }
}

void VtkSeries::WriteFrame(const Simulation& sim) {
  const SimulationState& s = sim.state();
  const Grid2D& g = sim.grid();
  const double a = sim.units().radius;
  const double force_scale = sim.units().tension / a;  // force density in units of T / a
  {
    std::ofstream out = Open(directory_ + "/" + FrameName("fluid", s.step, "vti"));
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\">\n"
        << "<ImageData WholeExtent=\"0 " << g.nx - 1 << " 0 " << g.ny - 1 << " 0 0\" Origin=\""
        << g.x(0) / a << " " << g.y(0) / a << " 0\" Spacing=\"" << g.h / a << " " << g.h / a
        << " 1\">\n<Piece Extent=\"0 " << g.nx - 1 << " 0 " << g.ny - 1 << " 0 0\">\n"
        << "<PointData Vectors=\"velocity\">\n"
        << "<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" "
           "format=\"ascii\">\n";
    const auto& ux = sim.ux();
    const auto& uy = sim.uy();
    for (std::size_t i = 0; i < ux.size(); ++i) out << ux[i] << ' ' << uy[i] << " 0\n";
    out << "</DataArray>\n";
    const auto& phi = sim.potential();
    if (!phi.empty()) {
      out << "<DataArray type=\"Float64\" Name=\"potential\" format=\"ascii\">\n";
      for (double v : phi) out << v << '\n';
      out << "</DataArray>\n";
    }
    out << "</PointData>\n</Piece>\n</ImageData>\n</VTKFile>\n";
  }
  {
    std::ofstream out = Open(directory_ + "/" + FrameName("membrane", s.step, "vtp"));
    const long m = s.markers.cols();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\">\n<PolyData>\n"
        << "<Piece NumberOfPoints=\"" << m << "\" NumberOfLines=\"1\">\n<Points>\n"
        << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (long k = 0; k < m; ++k) {
      out << s.markers(0, k) / a << ' ' << s.markers(1, k) / a << " 0\n";
    }
    out << "</DataArray>\n</Points>\n<Lines>\n"
        << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (long k = 0; k <= m; ++k) out << (k % m) << ' ';
    out << "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n"
        << m + 1 << "\n</DataArray>\n</Lines>\n";
    if (s.electric_force.cols() == m) {
      out << "<PointData Vectors=\"electric_force\">\n"
          << "<DataArray type=\"Float64\" Name=\"electric_force\" NumberOfComponents=\"3\" "
             "format=\"ascii\">\n";
      for (long k = 0; k < m; ++k) {
        out << s.electric_force(0, k) / force_scale << ' ' << s.electric_force(1, k) / force_scale
            << " 0\n";
      }
      out << "</DataArray>\n</PointData>\n";
    }
    out << "</Piece>\n</PolyData>\n</VTKFile>\n";
  }
  times_.push_back(s.time);
  steps_.push_back(s.step);
  WriteCollection("fluid", "vti");
  WriteCollection("membrane", "vtp");
}

void VtkSeries::WriteCollection(const std::string& name, const std::string& extension) const {
  std::ofstream out = Open(directory_ + "/" + name + ".pvd");
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (std::size_t i = 0; i < times_.size(); ++i) {
    out << "<DataSet timestep=\"" << times_[i] << "\" file=\""
        << FrameName(name, steps_[i], extension.c_str()) << "\"/>\n";
  }
  out << "</Collection>\n</VTKFile>\n";
}

}  // namespace ehd
