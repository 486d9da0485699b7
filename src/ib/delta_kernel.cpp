// The kernels' values and Fourier transforms; see delta_kernel.h.
#include "ehd_capsule/ib/delta_kernel.h"

#include <algorithm>
#include <stdexcept>

namespace ehd {

DeltaKernel ParseDeltaKernel(const std::string& name) {
  if (name == "cosine") return DeltaKernel::kCosine4;
  if (name == "roma3") return DeltaKernel::kRoma3;
  throw std::invalid_argument("unknown immersed-boundary kernel '" + name +
                              "' (expected cosine or roma3)");
}

const char* DeltaKernelName(DeltaKernel kernel) {
  return kernel == DeltaKernel::kRoma3 ? "roma3" : "cosine";
}

double DeltaKernelValue(DeltaKernel kernel, double r_over_h) {
  if (kernel == DeltaKernel::kCosine4) return CosineDelta(r_over_h);
  const double r = std::abs(r_over_h);
  if (r <= 0.5) return (1.0 + std::sqrt(1.0 - 3.0 * r * r)) / 3.0;
  if (r <= 1.5) {
    return (5.0 - 3.0 * r - std::sqrt(std::max(0.0, 1.0 - 3.0 * (1.0 - r) * (1.0 - r)))) / 6.0;
  }
  return 0.0;
}

double Roma3DeltaTransform(double xi) {
  // roma3: 2 int_0^{3/2} phi(r) cos(xi r) dr by 16-point Gauss-Legendre on [0, 1/2] and
  // [1/2, 3/2], where phi is smooth (the square roots vanish only outside, at r = 0.577 and
  // 1.577); exact to ~1e-14 for the xi <= 2 pi the stability estimate samples.
  static const double kNodes[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                                   0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                                   0.9445750230732326, 0.9894009349916499};
  static const double kWeights[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                                     0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                                     0.0622535239386479, 0.0271524594117541};
  double sum = 0.0;
  const double pieces[2][2] = {{0.0, 0.5}, {0.5, 1.5}};
  for (const auto& p : pieces) {
    const double mid = 0.5 * (p[0] + p[1]), half = 0.5 * (p[1] - p[0]);
    for (int i = 0; i < 8; ++i) {
      for (const double sign : {-1.0, 1.0}) {
        const double r = mid + sign * half * kNodes[i];
        sum += half * kWeights[i] * DeltaKernelValue(DeltaKernel::kRoma3, r) * std::cos(xi * r);
      }
    }
  }
  return 2.0 * sum;
}

}  // namespace ehd
