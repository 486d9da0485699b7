// The measures shown for a scene (coupling/shown_measures.h).
#include "ehd_capsule/coupling/shown_measures.h"

#include <cmath>
#include <cstdio>

namespace ehd {

ShownMeasures MeasuresOf(const Scene& scene) {
  ShownMeasures m;
  if (scene.dimension == 3) {
    m.shear_plane = scene.has_shear();
    m.field_axis = scene.electric_field || !scene.has_shear();
    m.volume = true;
  }
  return m;
}

std::string FormatMeasures(const SimulationState& s, const ShownMeasures& m,
                           const char* separator) {
  std::string text;
  char item[64];
  const auto add = [&](const char* format, double value) {
    std::snprintf(item, sizeof item, format, value);
    text += (text.empty() ? "" : separator) + std::string(item);
  };
  if (m.shear_plane) {
    add("D_xy = %.5f", s.dxy);
    add("theta/pi = %.4f", s.inclination / M_PI);
  }
  if (m.field_axis) add("D_z = %.5f", s.d_field);
  add(m.volume ? "volume drift = %.2e" : "area drift = %.2e", s.area_drift);
  return text;
}

}  // namespace ehd
