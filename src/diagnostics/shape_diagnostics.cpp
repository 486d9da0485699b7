// Equivalent-ellipse shape measures, song2019 sec. 4.1 eq. (151); see shape_diagnostics.h.
#include "ehd_capsule/diagnostics/shape_diagnostics.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "ehd_capsule/geometry/curve_segments.h"
#include "ehd_capsule/geometry/gauss_legendre.h"

namespace ehd {
ShapeDiagnostics MeasureShape(const ClosedCurve& c) {
  ShapeDiagnostics d;
  const int m = c.size();
  CurveSegments seg;  // segment-local evaluation, no knot search
  seg.Update(c);
  // Moments about a reference point (the first marker) to limit cancellation; integrals along
  // the spline parameter; the sign of the area fixes the orientation.
  const Eigen::Vector2d ref = c.markers().col(0);
  double a2 = 0.0, mx = 0.0, my = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int k = 0; k < m; ++k) {
    const double hk = seg.segment_parameter_length(k);
    for (int q = 0; q < 5; ++q) {
      const SplineDerivatives p = seg.Evaluate(k, kGaussNode[q] * hk);
      const double w = kGaussWeight[q] * hk;
      const double x = p.x - ref.x(), y = p.y - ref.y();
      const double dx = p.dx, dy = p.dy;
      a2 += w * (x * dy - y * dx);
      mx += w * x * x * dy;             // 2 int x dA
      my -= w * y * y * dx;             // 2 int y dA
      sxx += w * x * x * x * dy / 3.0;  // int x^2 dA
      syy -= w * y * y * y * dx / 3.0;  // int y^2 dA
      sxy += w * x * x * y * dy / 2.0;  // int x y dA
    }
  }
  const double area = 0.5 * a2;  // signed: > 0 counter-clockwise
  const double cx = 0.5 * mx / area, cy = 0.5 * my / area;
  // Central moments (parallel axis theorem); the orientation sign cancels in the ratios.
  const double ixx = sxx / area - cx * cx;
  const double iyy = syy / area - cy * cy;
  const double ixy = sxy / area - cx * cy;
  d.area = std::abs(area);
  d.centroid = ref + Eigen::Vector2d(cx, cy);
  d.length = 0.0;
  for (int k = 0; k < m; ++k) d.length += seg.SegmentArcLength(k);
  const double mean = 0.5 * (ixx + iyy);
  const double radius = std::hypot(0.5 * (ixx - iyy), ixy);
  const double l1 = mean + radius, l2 = std::max(mean - radius, 0.0);
  const double r1 = std::sqrt(l1), r2 = std::sqrt(l2);
  d.dxy = (r1 - r2) / (r1 + r2);
  d.inclination = 0.5 * std::atan2(2.0 * ixy, ixx - iyy);
  if (d.inclination <= -0.5 * M_PI) d.inclination += M_PI;  // keep (-pi/2, pi/2]
  // Per unit area the ellipse moments are a^2/4 and b^2/4.
  d.major_axis = 4.0 * r1;
  d.minor_axis = 4.0 * r2;
  return d;
}

double RelativeAreaDrift(double area, double initial_area) {
  if (!(initial_area > 0.0)) {
    throw std::invalid_argument("RelativeAreaDrift: initial_area must be > 0, got " +
                                std::to_string(initial_area));
  }
  return (area - initial_area) / initial_area;
}

}  // namespace ehd
