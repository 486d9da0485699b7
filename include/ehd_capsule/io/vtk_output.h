// VTK XML output for ParaView: the fluid on the grid as ImageData (.vti: velocity, speed,
// electric potential when there is a field) and the membrane as PolyData (.vtp: closed line with
// the electric force per marker), one pair per frame, listed with their times in a .pvd
// collection (fluid.pvd, membrane.pvd). Positions in units of the radius a (domain centred).
// 3D frames are binary (VTK XML "appended" raw data, little-endian, UInt64 block headers): the
// fluid velocity and speed as Float32 on the N^3 ImageData (12 MB per frame at 100^3 instead of
// ~100 MB of text), the membrane as PolyData triangles with Float64 vertices.
#pragma once

#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation.h"

namespace ehd {

class VtkSeries {
 public:
  // Creates the directory if needed. Throws std::runtime_error if it cannot be written.
  explicit VtkSeries(const std::string& directory);
  // Writes frame files for the current state and rewrites the .pvd collections.
  void WriteFrame(const Simulation& sim);
  int frames() const { return static_cast<int>(times_.size()); }

 private:
  void WriteFrame3D(const Simulation& sim);
  void WriteCollection(const std::string& name, const std::string& extension) const;
  std::string directory_;
  std::vector<double> times_;
  std::vector<long> steps_;
};

}  // namespace ehd
