// The FFTW wisdom file of the fast Poisson solvers; see poisson_axis.h.
#include <fftw3.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "poisson_axis.h"

namespace ehd::poisson_detail {

std::string WisdomPath() {
  if (const char* path = std::getenv("EHD_FFTW_WISDOM")) {
    const std::string p(path);
    return p == "off" ? std::string() : p;
  }
  std::string base;
  if (const char* cache = std::getenv("XDG_CACHE_HOME"); cache && *cache) {
    base = cache;
  } else if (const char* home = std::getenv("HOME"); home && *home) {
    base = std::string(home) + "/.cache";
  } else {
    return std::string();
  }
  return base + "/ehd_capsule/fftw_wisdom";
}

void ImportWisdom() {
  const std::string path = WisdomPath();
  if (path.empty()) return;
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return;
  fftw_import_wisdom_from_filename(path.c_str());  // a damaged file is ignored by FFTW: re-plan
}

void ExportWisdom() {
  const std::string path = WisdomPath();
  if (path.empty()) return;
  std::error_code error;
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path(), error);
  // Nothing new planned (the wisdom is the file's, e.g. a solver of a size planned before):
  // leave the file alone.
  char* wisdom = fftw_export_wisdom_to_string();
  if (wisdom == nullptr) return;
  const std::string text(wisdom);
  fftw_free(wisdom);
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      const std::string current((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
      if (current == text) return;
    }
  }
  // Write beside it and rename, so a concurrent reader never sees half a file.
  const std::string temporary = path + "." + std::to_string(::getpid()) + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return;  // not writable: no cache
    out << text;
    if (!out.flush()) {
      out.close();
      std::filesystem::remove(temporary, error);
      return;
    }
  }
  std::filesystem::rename(temporary, target, error);
  if (error) std::filesystem::remove(temporary, error);
}

}  // namespace ehd::poisson_detail
