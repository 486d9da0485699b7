// Viscosity contrast across the membrane, song2019 eqs. (117)-(118) (= (153)-(154)):
//   H(d) = 0                                        d <= -2h
//          (1 + d/(2h) + sin(pi d / (2h)) / pi) / 2  |d| < 2h
//          1                                        d >= 2h
//   nu(x) = nu_inside + (nu_outside - nu_inside) H(d(x)),
// with d the signed distance to the membrane spline (< 0 inside). The reference finds the sign
// from the nearest marker's normal; here nodes farther than the band (2h + one marker spacing)
// from every marker take H = 0 or 1 from a scanline fill of the marker polygon, and nodes in the
// band use the spline's exact signed distance (ClosedCurve::SignedDistance). Buffers are kept
// between updates (no allocation per step once sized).
#pragma once

#include <vector>

#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"

namespace ehd {

double SmoothedHeaviside(double d, double h);

class ViscosityField {
 public:
  ViscosityField(const Grid2D& grid, bool periodic_x);
  // Fills nu (grid.size()) for the curve. Markers may be unwrapped in x when periodic_x.
  void Update(const ClosedCurve& curve, double nu_inside, double nu_outside,
              std::vector<double>& nu);

 private:
  Grid2D grid_;
  bool periodic_x_;
  std::vector<double> heaviside_;
  std::vector<char> in_band_;
  std::vector<int> band_nodes_;
  std::vector<double> crossings_;
};

}  // namespace ehd
