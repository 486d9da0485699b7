// Binary checkpoint streams for Simulation::Save/Restore: raw little-endian values as stored in
// memory, each array preceded by its length, and named sections (one per step stage) so that a
// checkpoint of a differently built pipeline is refused naming the stage instead of being read
// as garbage.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace ehd {

class CheckpointWriter {
 public:
  explicit CheckpointWriter(const std::string& path);
  template <typename T>
  void Pod(const T& v) {
    out_.write(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void Doubles(const double* p, std::size_t n);
  void Vec(const std::vector<double>& v) { Doubles(v.data(), v.size()); }
  template <int Rows>
  void Mat(const Eigen::Matrix<double, Rows, Eigen::Dynamic>& m) {
    Pod<std::int32_t>(Rows);
    Doubles(m.data(), static_cast<std::size_t>(m.size()));
  }
  void Text(const std::string& s);
  void Section(const std::string& name) { Text(name); }
  void Finish();  // flushes; throws if any write failed

 private:
  std::ofstream out_;
  std::string path_;
};

class CheckpointReader {
 public:
  explicit CheckpointReader(const std::string& path);
  template <typename T>
  T Pod() {
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof(T));
    Check();
    return v;
  }
  std::vector<double> Vec();
  template <int Rows>
  Eigen::Matrix<double, Rows, Eigen::Dynamic> Mat() {
    const auto rows = Pod<std::int32_t>();
    if (rows != Rows)
      Fail("a matrix of " + std::to_string(rows) + " rows where " + std::to_string(Rows) +
           " were expected");
    const std::vector<double> v = Vec();
    Eigen::Matrix<double, Rows, Eigen::Dynamic> m(Rows, static_cast<Eigen::Index>(v.size() / Rows));
    for (std::size_t i = 0; i < v.size(); ++i) m.data()[i] = v[i];
    return m;
  }
  std::string Text();
  // Reads a section name and throws unless it is `name` (the pipeline differs).
  void ExpectSection(const std::string& name);
  [[noreturn]] void Fail(const std::string& what) const;
  const std::string& path() const { return path_; }

 private:
  void Check();
  std::ifstream in_;
  std::string path_;
};

}  // namespace ehd
