// In-plane tension laws of the 2D membrane, each adding to the tension tau of every segment
// (tau is linear in the laws, song2019 eq. (111): tau = tau_e + tau_v, plus gamma for a drop).
//
//   InterfacialTension   tau = gamma                         (drop, sec. 4.3)
//   HookeanTension       tau_e = E_s (lambda - 1)            eq. (113), lambda = l / l_0 eq. (112)
//   KelvinVoigtTension   tau_v = mu_s (1/lambda) dlambda/dt  eq. (114)
// lambda is the stretch of a segment (spline arc length between two markers over its reference
// length). dlambda/dt is supplied by the caller (MembraneModel: one-sided second-order
// difference of the stored stretch history, as in the text).
#pragma once

#include <vector>

namespace ehd {

struct InterfacialTension {
  double gamma = 0.0;
  void Add(std::vector<double>& tau) const {
    for (double& t : tau) t += gamma;
  }
};

struct HookeanTension {
  double shear_modulus = 0.0;  // E_s
  void Add(const std::vector<double>& stretch, std::vector<double>& tau) const {
    for (std::size_t k = 0; k < tau.size(); ++k) tau[k] += shear_modulus * (stretch[k] - 1.0);
  }
};

struct KelvinVoigtTension {
  double membrane_viscosity = 0.0;  // mu_s
  void Add(const std::vector<double>& stretch, const std::vector<double>& stretch_rate,
           std::vector<double>& tau) const {
    for (std::size_t k = 0; k < tau.size(); ++k) {
      tau[k] += membrane_viscosity * stretch_rate[k] / stretch[k];
    }
  }
};

}  // namespace ehd
