// Binary 3D VTK frames (io/vtk_output.h): the appended raw blocks decode to the simulation's
// velocity field and surface, with the sizes and offsets the XML header announces.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ehd_capsule/io/vtk_output.h"
#include "support/tiny_scene.h"

namespace ehd {
namespace {

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The bytes of the appended block at `offset` (after the '_' marker), checking its header.
std::string Block(const std::string& file, std::size_t offset) {
  const std::size_t start = file.find("<AppendedData encoding=\"raw\">");
  EXPECT_NE(start, std::string::npos);
  const std::size_t data = file.find('_', start) + 1;
  std::uint64_t n = 0;
  std::memcpy(&n, file.data() + data + offset, sizeof n);
  return file.substr(data + offset + sizeof n, n);
}

std::size_t OffsetOf(const std::string& file, const std::string& name) {
  const std::size_t at = file.find("Name=\"" + name + "\"");
  EXPECT_NE(at, std::string::npos) << name;
  const std::size_t o = file.find("offset=\"", at) + 8;
  return std::stoul(file.substr(o));
}

TEST(Vtk3D, AppendedBlocksDecodeToTheSimulationState) {
  Simulation sim(test::TinyScene(3)
                     .Grid(16)
                     .With("mesh_subdivisions", 2)
                     .With("geometry.half_width", 2)
                     .Build());
  for (int i = 0; i < 3; ++i) sim.Step();
  const std::string dir = ::testing::TempDir() + "/ehd_vtk3d";
  std::filesystem::remove_all(dir);
  VtkSeries vtk(dir);
  vtk.WriteFrame(sim);
  const std::string fluid = ReadFile(dir + "/fluid_000000003.vti");
  EXPECT_NE(fluid.find("WholeExtent=\"0 15 0 15 0 15\""), std::string::npos);
  const std::string velocity = Block(fluid, OffsetOf(fluid, "velocity"));
  ASSERT_EQ(velocity.size(), 16u * 16 * 16 * 3 * sizeof(float));
  for (std::size_t node : {0ul, 1000ul, 4095ul}) {
    float v[3];
    std::memcpy(v, velocity.data() + 3 * node * sizeof(float), sizeof v);
    EXPECT_EQ(v[0], static_cast<float>(sim.ux()[node]));
    EXPECT_EQ(v[1], static_cast<float>(sim.uy()[node]));
    EXPECT_EQ(v[2], static_cast<float>(sim.uz()[node]));
  }
  const std::string surface = ReadFile(dir + "/membrane_000000003.vtp");
  EXPECT_NE(surface.find("NumberOfPoints=\"162\" NumberOfPolys=\"320\""), std::string::npos);
  const std::string points = Block(surface, 0);
  ASSERT_EQ(points.size(), 162u * 3 * sizeof(double));
  double p[3];
  std::memcpy(p, points.data() + 3 * 7 * sizeof(double), sizeof p);
  EXPECT_DOUBLE_EQ(p[1], sim.state().markers(1, 7) / sim.units().radius);
  const std::string connectivity = Block(surface, OffsetOf(surface, "connectivity"));
  ASSERT_EQ(connectivity.size(), 320u * 3 * sizeof(std::int64_t));
  std::int64_t c[3];
  std::memcpy(c, connectivity.data() + 3 * 5 * sizeof(std::int64_t), sizeof c);
  EXPECT_EQ(c[0], sim.triangles()[5][0]);
  EXPECT_EQ(c[2], sim.triangles()[5][2]);
  EXPECT_NE(ReadFile(dir + "/fluid.pvd").find("fluid_000000003.vti"), std::string::npos);
}

}  // namespace
}  // namespace ehd
