// High-order smoothing of a closed chain of Lagrangian markers against the sawtooth (odd-even)
// instability, after the five-point formula of Longuet-Higgins & Cokelet (1976, eq. (4.1)) used
// for the same purpose in boundary-integral capsule codes:
//   X <- X - (-1)^p D^(2p) X / 4^p,   D^2 X_k = X_{k-1} - 2 X_k + X_{k+1}   (indices mod M),
// p = 2 being Longuet-Higgins & Cokelet's (-1, 4, 10, 4, -1) / 16. Its gain on a Fourier mode of
// wavenumber theta (radians per marker) is
//   H(theta) = 1 - ((1 - cos theta) / 2)^p,
// so the zigzag (theta = pi) is removed exactly, modes near it are damped strongly, and a smooth
// mode loses only (theta / 2)^(2p). The default p = 4 (nine points) keeps the shape modes: one
// application shrinks a circle of 64 markers by 3e-11 (p = 2: 6e-6, which over 10^4 applications
// in a long run would lose ~10% of the area of a strongly deformed capsule).
//
// Why it is needed (not in song2019): a zigzag of markers spaced < 2 h is in the near-null space
// of the immersed-boundary coupling. The 4-point delta of eq. (103) passes a force pattern of
// wavelength 2 markers to the grid with a gain of a few percent, and interpolates it back with the
// same gain, so the membrane's restoring force on a zigzag barely moves the markers, while any
// marker-scale error (non-variational membrane forces, the electric force at marker-scale
// curvature) feeds it. Left alone it grows over tens of time units into marker-scale wrinkles, a
// local compression and, with the field, a blow-up (docs/coupling.md, "Long runs").
#pragma once

#include <Eigen/Core>

namespace ehd {

class SawtoothFilter {
 public:
  explicit SawtoothFilter(int order = 8);  // p >= 1
  int order() const { return order_; }
  // Smooths X (2 x M, M >= 2p + 1) in place; no allocation once sized.
  void Apply(Eigen::Matrix2Xd& X);
  // Gain of one application on the mode of wavenumber theta (radians per marker).
  double Gain(double theta) const;

 private:
  int order_;
  Eigen::Matrix2Xd diff_, work_;
};

}  // namespace ehd
