// The kernels' values and Fourier transforms; see delta_kernel.h.
#include "ehd_capsule/ib/delta_kernel.h"

#include <algorithm>
#include <stdexcept>

namespace ehd {

DeltaKernel ParseDeltaKernel(const std::string& name) {
  if (name == "cosine") return DeltaKernel::kCosine4;
  if (name == "roma3") return DeltaKernel::kRoma3;
  if (name == "trapezoid3") return DeltaKernel::kTrapezoid3;
  if (name == "roma3_even_odd") return DeltaKernel::kRoma3EvenOdd;
  throw std::invalid_argument("unknown immersed-boundary kernel '" + name +
                              "' (expected cosine, roma3, trapezoid3 or roma3_even_odd)");
}

double DeltaKernelValue(DeltaKernel kernel, double r_over_h) {
  if (kernel == DeltaKernel::kCosine4) return CosineDelta(r_over_h);
  const double r = std::abs(r_over_h);
  if (kernel == DeltaKernel::kTrapezoid3) return r <= 0.5 ? 0.5 : r <= 1.5 ? 0.75 - 0.5 * r : 0.0;
  if (r <= 0.5) return (1.0 + std::sqrt(1.0 - 3.0 * r * r)) / 3.0;
  if (r <= 1.5) {
    return (5.0 - 3.0 * r - std::sqrt(std::max(0.0, 1.0 - 3.0 * (1.0 - r) * (1.0 - r)))) / 6.0;
  }
  return 0.0;
}

double Roma3DeltaTransform(double xi) {
  // 2 int_0^{3/2} phi(r) cos(xi r) dr by 16-point Gauss-Legendre on four quarters of each of
  // [0, 1/2] and [1/2, 3/2], where phi is analytic. Its square roots branch just outside them
  // (at r = 0.577 and 0.423), which holds one panel per piece to 3e-11; four give 1e-15.
  static const double kNodes[8] = {0.095012509837637454, 0.28160355077925892, 0.45801677765722737,
                                   0.61787624440264377,  0.755404408355003,   0.86563120238783176,
                                   0.9445750230732326,   0.98940093499164994};
  static const double kWeights[8] = {
      0.18945061045506859, 0.18260341504492361,  0.16915651939500262,  0.14959598881657676,
      0.12462897125553403, 0.095158511682492591, 0.062253523938647706, 0.027152459411754037};
  double sum = 0.0;
  const double pieces[2][2] = {{0.0, 0.5}, {0.5, 1.5}};
  constexpr int kPanels = 4;
  for (const auto& p : pieces) {
    const double half = 0.5 * (p[1] - p[0]) / kPanels;
    for (int panel = 0; panel < kPanels; ++panel) {
      const double mid = p[0] + (2 * panel + 1) * half;
      for (int i = 0; i < 8; ++i) {
        for (const double sign : {-1.0, 1.0}) {
          const double r = mid + sign * half * kNodes[i];
          sum += half * kWeights[i] * DeltaKernelValue(DeltaKernel::kRoma3, r) * std::cos(xi * r);
        }
      }
    }
  }
  return 2.0 * sum;
}

double Trapezoid3DeltaTransform(double xi) {
  auto sinc = [](double x) { return std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x; };
  return sinc(0.5 * xi) * sinc(xi);
}

}  // namespace ehd
