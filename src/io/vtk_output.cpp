#include "ehd_capsule/io/vtk_output.h"

#include <cmath>
#include <cstdint>
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

// Appended raw binary VTK arrays (3D frames): each block is a UInt64 byte count and the bytes.
class AppendedData {
 public:
  // Registers a block and returns the offset attribute for its DataArray.
  template <typename T>
  std::size_t Add(const std::vector<T>& values) {
    const std::size_t offset = bytes_.size();
    const std::uint64_t n = values.size() * sizeof(T);
    const char* head = reinterpret_cast<const char*>(&n);
    bytes_.insert(bytes_.end(), head, head + sizeof n);
    const char* data = reinterpret_cast<const char*>(values.data());
    bytes_.insert(bytes_.end(), data, data + n);
    return offset;
  }
  void Write(std::ofstream& out) const {
    out << "<AppendedData encoding=\"raw\">\n_";
    out.write(bytes_.data(), static_cast<std::streamsize>(bytes_.size()));
    out << "\n</AppendedData>\n";
  }

 private:
  std::vector<char> bytes_;
};

const char* kBinaryHeader =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"%s\" version=\"1.0\" "
    "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";

std::ofstream OpenBinary(const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  out.precision(9);
  return out;
}

void Header(std::ofstream& out, const char* type) {
  char text[256];
  std::snprintf(text, sizeof text, kBinaryHeader, type);
  out << text;
}

}  // namespace

void VtkSeries::WriteFrame3D(const Simulation& sim) {
  const SimulationState& s = sim.state();
  const Grid3D& g = sim.grid3d();
  const double a = sim.units().radius;
  {
    // Fluid velocity (Float32: a 100^3 frame is 12 MB) in units of the wall speed scale k a.
    const std::string path = directory_ + "/" + FrameName("fluid", s.step, "vti");
    std::ofstream out = OpenBinary(path);
    Header(out, "ImageData");
    const auto& ux = sim.ux();
    const auto& uy = sim.uy();
    const auto& uz = sim.uz();
    std::vector<float> velocity(3 * ux.size()), speed(ux.size());
    for (std::size_t i = 0; i < ux.size(); ++i) {
      velocity[3 * i] = static_cast<float>(ux[i]);
      velocity[3 * i + 1] = static_cast<float>(uy[i]);
      velocity[3 * i + 2] = static_cast<float>(uz[i]);
      speed[i] = static_cast<float>(std::sqrt(ux[i] * ux[i] + uy[i] * uy[i] + uz[i] * uz[i]));
    }
    AppendedData data;
    const std::size_t v_offset = data.Add(velocity), s_offset = data.Add(speed);
    out << "<ImageData WholeExtent=\"0 " << g.nx - 1 << " 0 " << g.ny - 1 << " 0 " << g.nz - 1
        << "\" Origin=\"" << g.x(0) / a << " " << g.y(0) / a << " " << g.z(0) / a << "\" Spacing=\""
        << g.h / a << " " << g.h / a << " " << g.h / a << "\">\n<Piece Extent=\"0 " << g.nx - 1
        << " 0 " << g.ny - 1 << " 0 " << g.nz - 1 << "\">\n"
        << "<PointData Vectors=\"velocity\" Scalars=\"speed\">\n"
        << "<DataArray type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\" "
           "format=\"appended\" offset=\""
        << v_offset << "\"/>\n"
        << "<DataArray type=\"Float32\" Name=\"speed\" format=\"appended\" offset=\"" << s_offset
        << "\"/>\n</PointData>\n</Piece>\n</ImageData>\n";
    data.Write(out);
    out << "</VTKFile>\n";
    if (!out) throw std::runtime_error("writing " + path + " failed");
  }
  {
    // Membrane surface: vertices (units of a) and triangles.
    const std::string path = directory_ + "/" + FrameName("membrane", s.step, "vtp");
    std::ofstream out = OpenBinary(path);
    Header(out, "PolyData");
    const long nv = s.markers.cols();
    const auto& triangles = sim.triangles();
    std::vector<double> points(3 * nv);
    for (long k = 0; k < nv; ++k) {
      for (int c = 0; c < 3; ++c) points[3 * k + c] = s.markers(c, k) / a;
    }
    std::vector<std::int64_t> connectivity, offsets;
    connectivity.reserve(3 * triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      for (int c = 0; c < 3; ++c) connectivity.push_back(triangles[t][c]);
      offsets.push_back(static_cast<std::int64_t>(3 * (t + 1)));
    }
    AppendedData data;
    const std::size_t p_offset = data.Add(points), c_offset = data.Add(connectivity),
                      o_offset = data.Add(offsets);
    out << "<PolyData>\n<Piece NumberOfPoints=\"" << nv << "\" NumberOfPolys=\"" << triangles.size()
        << "\">\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
           "format=\"appended\" offset=\""
        << p_offset << "\"/>\n</Points>\n<Polys>\n"
        << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\""
        << c_offset << "\"/>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" "
        << "offset=\"" << o_offset << "\"/>\n</Polys>\n</Piece>\n</PolyData>\n";
    data.Write(out);
    out << "</VTKFile>\n";
    if (!out) throw std::runtime_error("writing " + path + " failed");
  }
  times_.push_back(s.time);
  steps_.push_back(s.step);
  WriteCollection("fluid", "vti");
  WriteCollection("membrane", "vtp");
}

VtkSeries::VtkSeries(const std::string& directory) : directory_(directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (!std::filesystem::is_directory(directory_)) {
    throw std::runtime_error("--vtk: cannot create directory " + directory_);
  }
}

void VtkSeries::WriteFrame(const Simulation& sim) {
  if (sim.dimension() == 3) {
    WriteFrame3D(sim);
    return;
  }
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
