// Checkpoint byte streams; see checkpoint_io.h.
#include "ehd_capsule/coupling/checkpoint_io.h"

#include <stdexcept>

namespace ehd {

CheckpointWriter::CheckpointWriter(const std::string& path)
    : out_(path, std::ios::binary), path_(path) {
  if (!out_) throw std::runtime_error("checkpoint: cannot write " + path);
}

void CheckpointWriter::Doubles(const double* p, std::size_t n) {
  Pod<std::uint64_t>(n);
  out_.write(reinterpret_cast<const char*>(p), static_cast<std::streamsize>(n * sizeof(double)));
}

void CheckpointWriter::Text(const std::string& s) {
  Pod<std::uint64_t>(s.size());
  out_.write(s.data(), static_cast<std::streamsize>(s.size()));
}

void CheckpointWriter::Finish() {
  out_.flush();
  if (!out_) throw std::runtime_error("checkpoint: write to " + path_ + " failed");
}

CheckpointReader::CheckpointReader(const std::string& path)
    : in_(path, std::ios::binary), path_(path) {
  if (!in_) throw std::runtime_error("checkpoint: cannot read " + path);
}

std::vector<double> CheckpointReader::Vec() {
  const auto n = Pod<std::uint64_t>();
  if (n > (1ull << 34)) Fail("corrupt size");
  std::vector<double> v(n);
  in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(double)));
  Check();
  return v;
}

std::string CheckpointReader::Text() {
  const auto n = Pod<std::uint64_t>();
  if (n > (1ull << 30)) Fail("corrupt size");
  std::string s(n, '\0');
  in_.read(s.data(), static_cast<std::streamsize>(n));
  Check();
  return s;
}

void CheckpointReader::ExpectSection(const std::string& name) {
  const std::string found = Text();
  if (found != name) {
    Fail("section '" + found + "' where this build's pipeline has '" + name +
         "' (the checkpoint was written by a differently built simulation)");
  }
}

void CheckpointReader::Fail(const std::string& what) const {
  throw std::runtime_error("checkpoint " + path_ + ": " + what);
}

void CheckpointReader::Check() {
  if (!in_) Fail("truncated file");
}

}  // namespace ehd
