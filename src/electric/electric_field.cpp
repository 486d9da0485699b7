// Grid electric field and Maxwell interfacial force (see electric_field.h).
#include "ehd_capsule/electric/electric_field.h"

#include <stdexcept>
#include <string>

namespace ehd {

void ComputeGridField(const InterfaceClassification& classes, const std::vector<double>& phi,
                      const std::vector<double>& band_jump, std::vector<double>& ex,
                      std::vector<double>& ey) {
  const Grid2D& g = classes.grid();
  if (phi.size() != g.size()) {
    throw std::invalid_argument("ComputeGridField: phi has " + std::to_string(phi.size()) +
                                " values, grid has " + std::to_string(g.size()));
  }
  ex.resize(g.size());
  ey.resize(g.size());
  const double h = g.h;
  // Value at neighbour nb as seen from the side of centre c (same-side extension).
  auto extended = [&](std::size_t c, std::size_t nb) {
    const int sc = classes.side(c), sn = classes.side(nb);
    if (sc == sn) return phi[nb];
    return phi[nb] - sn * band_jump[classes.band_slot(nb)];
  };
  // Derivative along one axis at c from neighbours lo/hi (-1 = outside the grid).
  auto derivative = [&](std::size_t c, long lo, long hi) {
    const bool has_lo = lo >= 0, has_hi = hi >= 0;
    const bool lo_same = has_lo && classes.side(lo) == classes.side(c);
    const bool hi_same = has_hi && classes.side(hi) == classes.side(c);
    if (lo_same && hi_same) return (phi[hi] - phi[lo]) / (2.0 * h);
    if (lo_same && !has_hi) return (phi[c] - phi[lo]) / h;
    if (hi_same && !has_lo) return (phi[hi] - phi[c]) / h;
    if (lo_same) return (phi[c] - phi[lo]) / h;  // hi across the curve
    if (hi_same) return (phi[hi] - phi[c]) / h;  // lo across the curve
    if (has_lo && has_hi) return (extended(c, hi) - extended(c, lo)) / (2.0 * h);
    if (has_lo) return (phi[c] - extended(c, lo)) / h;
    if (has_hi) return (extended(c, hi) - phi[c]) / h;
    return 0.0;
  };
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t c = g.index(i, j);
      const long w = i > 0 ? static_cast<long>(g.index(i - 1, j)) : -1;
      const long e = i < g.nx - 1 ? static_cast<long>(g.index(i + 1, j)) : -1;
      const long s = j > 0 ? static_cast<long>(g.index(i, j - 1)) : -1;
      const long n = j < g.ny - 1 ? static_cast<long>(g.index(i, j + 1)) : -1;
      ex[c] = -derivative(c, w, e);
      ey[c] = -derivative(c, s, n);
    }
  }
}

Eigen::Matrix2Xd MaxwellForce(const ClosedCurve& curve, double eps_minus, double eps_plus,
                              const std::vector<double>& en_minus,
                              const std::vector<double>& en_plus,
                              const std::vector<double>& et_minus,
                              const std::vector<double>& et_plus) {
  const int m = curve.size();
  if (static_cast<int>(en_minus.size()) != m || static_cast<int>(en_plus.size()) != m ||
      static_cast<int>(et_minus.size()) != m || static_cast<int>(et_plus.size()) != m) {
    throw std::invalid_argument("MaxwellForce: field components must have one value per marker (" +
                                std::to_string(m) + ")");
  }
  Eigen::Matrix2Xd force(2, m);
  for (int k = 0; k < m; ++k) {
    const CurvePoint c = curve.AtMarker(k);
    const double normal =
        0.5 * (eps_plus * (en_plus[k] * en_plus[k] - et_plus[k] * et_plus[k]) -
               eps_minus * (en_minus[k] * en_minus[k] - et_minus[k] * et_minus[k]));
    const double tangential =
        eps_plus * en_plus[k] * et_plus[k] - eps_minus * en_minus[k] * et_minus[k];
    force.col(k) = normal * c.normal + tangential * c.tangent;
  }
  return force;
}

}  // namespace ehd
