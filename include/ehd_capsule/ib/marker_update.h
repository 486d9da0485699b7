// Lagrangian marker bookkeeping for the immersed boundary: arc elements, time integration of
// the marker positions, and periodic wrap of the whole curve.
//
// song2019 eq. (105) advances the markers by forward Euler, X^{n+1} = X^n + dt U(X^n).
// kAdamsBashforth2 is the second-order option  X^{n+1} = X^n + dt (3/2 U^n - 1/2 U^{n-1}),
// started by one Euler step (no previous velocity). Both use only velocities already
// interpolated, so one Interpolate per step either way.
//
// Periodic wrap: markers are stored UNWRAPPED (the curve stays continuous; ImmersedBoundary wraps
// node indices). WrapCurveIntoDomain shifts all markers of a curve by the same multiple of the
// domain width so that their mean x lies in [x0, x0 + width); call it at most once per step,
// never marker by marker.
#pragma once

#include <Eigen/Core>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"

namespace ehd {

// Arc element of each marker, dl_k = (l_{k-1} + l_k) / 2 with l_k = SegmentArcLength(k): the
// length that turns a force density at marker k into the force P(X_k) spread by eq. (106).
std::vector<double> MarkerArcElements(const ClosedCurve& c);
// Same without allocating (dl resized only if its size differs).
void MarkerArcElements(const ClosedCurve& c, std::vector<double>& dl);
// From already computed segment lengths l_k (e.g. MembraneModel::segment_length()).
void MarkerArcElementsFromSegments(const std::vector<double>& segment_length,
                                   std::vector<double>& dl);

enum class MarkerIntegrator { kForwardEuler, kAdamsBashforth2 };

// Advances Lagrangian points (2D markers or 3D vertices: D rows) with the interpolated velocity.
template <int D>
class PointAdvector {
 public:
  using Points = Eigen::Matrix<double, D, Eigen::Dynamic>;
  explicit PointAdvector(MarkerIntegrator scheme = MarkerIntegrator::kForwardEuler)
      : scheme_(scheme) {}
  MarkerIntegrator scheme() const { return scheme_; }
  // X += dt * (scheme's combination of U and the previous call's U). Throws if sizes differ.
  void Advance(const Points& velocity, double dt, Points& X) {
    if (velocity.cols() != X.cols()) {
      throw std::invalid_argument("PointAdvector: " + std::to_string(velocity.cols()) +
                                  " velocities for " + std::to_string(X.cols()) + " points");
    }
    if (!(dt > 0.0)) {
      throw std::invalid_argument("PointAdvector: dt must be > 0, got " + std::to_string(dt));
    }
    const bool ab2 = scheme_ == MarkerIntegrator::kAdamsBashforth2 && has_previous_ &&
                     previous_velocity_.cols() == velocity.cols();
    if (ab2) {
      X += dt * (1.5 * velocity - 0.5 * previous_velocity_);
    } else {
      X += dt * velocity;
    }
    if (scheme_ == MarkerIntegrator::kAdamsBashforth2) {
      previous_velocity_ = velocity;  // same size after the first step: no allocation
      has_previous_ = true;
    }
  }
  // Forgets the previous velocity (e.g. after remeshing); the next step is Euler.
  void Reset() { has_previous_ = false; }

  // The previous velocity AB2 combines with the next one (checkpoints, re-spacing of markers).
  bool has_previous_velocity() const { return has_previous_; }
  const Points& previous_velocity() const { return previous_velocity_; }
  // nullptr when there is none; the caller may resample it in place (same point count).
  Points* mutable_previous_velocity() { return has_previous_ ? &previous_velocity_ : nullptr; }
  void SetPreviousVelocity(const Points& velocity, bool has_previous) {
    previous_velocity_ = velocity;
    has_previous_ = has_previous;
  }

 private:
  MarkerIntegrator scheme_;
  bool has_previous_ = false;
  Points previous_velocity_;
};

using MarkerAdvector = PointAdvector<2>;

// Shifts X by an integer number of domain widths so that mean(X.row(0)) is in [x0, x0 + width).
// Returns the shift applied (0 if none).
double WrapCurveIntoDomain(const Grid2D& grid, Eigen::Matrix2Xd& X);
// 3D: the same for each periodic axis flagged (x and z for the shear walls), by the mean of the
// vertices along that axis.
void WrapSurfaceIntoDomain(const Grid3D& grid, const std::array<bool, 3>& periodic,
                           Eigen::Matrix3Xd& X);

}  // namespace ehd
