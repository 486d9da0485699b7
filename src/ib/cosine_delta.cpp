// song2019 eq. (103): phi(r) = (1/4)(1 + cos(pi r / 2)) for |r| <= 2. See cosine_delta.h.
#include "ehd_capsule/ib/cosine_delta.h"

namespace ehd {

double CosineDelta(double r_over_h) {
  constexpr double kHalfPi = 1.5707963267948966;
  const double r = std::abs(r_over_h);
  if (r >= 2.0) return 0.0;
  return 0.25 * (1.0 + std::cos(kHalfPi * r));
}

}  // namespace ehd
