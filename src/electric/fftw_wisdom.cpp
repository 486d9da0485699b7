// The FFTW wisdom file of the fast Poisson solvers; see poisson_axis.h.
#include <fftw3.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
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
  // Write beside it and rename, so a concurrent reader never sees half a file.
  const std::string temporary = path + "." + std::to_string(::getpid()) + ".tmp";
  if (fftw_export_wisdom_to_filename(temporary.c_str()) == 0) return;  // not writable: no cache
  std::filesystem::rename(temporary, target, error);
  if (error) std::filesystem::remove(temporary, error);
}

}  // namespace ehd::poisson_detail
