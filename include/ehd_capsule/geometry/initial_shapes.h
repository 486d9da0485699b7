// Initial marker sets for capsules, drops and red blood cells, counter-clockwise.
//
// Circle and ellipse (semi-axes a along the rotated x axis, b along y), and the biconcave
// red-blood-cell profile of song2019 eq. (152) (after Pozrikidis):
//   x = a alpha sin(chi),
//   y = (a alpha / 2) (c0 + c1 sin^2 chi + c2 sin^4 chi) cos(chi),
//   alpha = 1.3858, c0 = 0.207, c1 = 2.003, c2 = -1.123 (sec. 5.3).
// Its enclosed area is exactly  A = (pi a^2 alpha^2 / 2) (c0 + c1/4 + c2/8) = 0.5448 pi a^2,
// i.e. the area-equivalent radius is 0.738 a and the equivalent diameter 1.48 a, which is the
// characteristic length quoted in sec. 5.3 (so "a" in eq. (152) is not the equivalent radius).
// The text runs chi from -3pi/4 to 5pi/4, which is clockwise; here chi = pi/2 - t with t
// increasing, so marker 0 is the right-most point (a alpha, 0) and the markers run
// counter-clockwise. Markers are placed at equal arc length by default (sec. 4.1: "each segment
// is of equal length"), or at equal parameter steps.
#pragma once

#include <Eigen/Core>

namespace ehd {

enum class MarkerSpacing { kEqualArcLength, kUniformParameter };

struct BiconcaveParameters {
  double radius = 1.0;  // a in eq. (152)
  double alpha = 1.3858;
  double c0 = 0.207;
  double c1 = 2.003;
  double c2 = -1.123;
};

// M markers on a circle, marker k at angle 2 pi k / M from the +x axis.
Eigen::Matrix2Xd CircleMarkers(int markers, double radius,
                               const Eigen::Vector2d& centre = Eigen::Vector2d::Zero());

// Ellipse (a cos t, b sin t) rotated by `angle` (radians, counter-clockwise) about its centre.
Eigen::Matrix2Xd EllipseMarkers(int markers, double semi_axis_a, double semi_axis_b,
                                const Eigen::Vector2d& centre = Eigen::Vector2d::Zero(),
                                double angle = 0.0,
                                MarkerSpacing spacing = MarkerSpacing::kEqualArcLength);

// Biconcave profile of eq. (152), long axis along the rotated x axis.
Eigen::Matrix2Xd BiconcaveMarkers(int markers, const BiconcaveParameters& p = {},
                                  const Eigen::Vector2d& centre = Eigen::Vector2d::Zero(),
                                  double angle = 0.0,
                                  MarkerSpacing spacing = MarkerSpacing::kEqualArcLength);

// Exact enclosed area of the eq. (152) profile (see above).
double BiconcaveArea(const BiconcaveParameters& p = {});

}  // namespace ehd
