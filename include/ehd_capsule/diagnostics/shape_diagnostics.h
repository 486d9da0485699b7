// Shape measures of a capsule or drop: Taylor deformation, inclination, area, length, centroid.
//
// song2019 sec. 4.1, eq. (151), following Breyiannis & Pozrikidis: the shape is mapped to the
// ellipse with the same tensor of second moments of the enclosed region,
//   S = int_Omega (x - x_c)(x - x_c)^T dA,
// evaluated on the spline by Green's theorem (int x^2 dA = oint x^3/3 dy,
// int y^2 dA = -oint y^3/3 dx, int x y dA = oint x^2 y/2 dy, about the centroid). An ellipse
// with semi-axes a >= b has principal moments lambda_1 = pi a^3 b / 4, lambda_2 = pi a b^3 / 4, so
//   a / b = sqrt(lambda_1 / lambda_2),  a b = (16 lambda_1 lambda_2 / pi^2)^(1/4),
//   D_xy = (L - B)/(L + B) = (sqrt(lambda_1) - sqrt(lambda_2)) / (sqrt(lambda_1) + sqrt(lambda_2)),
// with L = 2a, B = 2b. The inclination theta is the angle of the major principal axis from +x,
//   theta = atan2(2 S_xy, S_xx - S_yy) / 2   in (-pi/2, pi/2]
// (0 for a circle, where it is undefined).
#pragma once

#include <Eigen/Core>

#include "ehd_capsule/geometry/closed_curve.h"

namespace ehd {

struct ShapeDiagnostics {
  double dxy = 0.0;          // Taylor deformation (L - B)/(L + B)
  double inclination = 0.0;  // theta, radians from +x, in (-pi/2, pi/2]
  double area = 0.0;         // enclosed area
  double length = 0.0;       // membrane (spline) length
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double major_axis = 0.0;  // L = 2a of the equivalent ellipse
  double minor_axis = 0.0;  // B = 2b
};

ShapeDiagnostics MeasureShape(const ClosedCurve& c);

// (area - initial_area) / initial_area; throws if initial_area <= 0.
double RelativeAreaDrift(double area, double initial_area);

}  // namespace ehd
