// Segment-local evaluation of a ClosedCurve's splines; see curve_segments.h.
#include "ehd_capsule/geometry/curve_segments.h"

#include <cmath>

#include "ehd_capsule/geometry/gauss_legendre.h"

namespace ehd {
void CurveSegments::Update(const ClosedCurve& c) {
  const int m = c.size();
  h_.resize(m);
  x_.resize(m);
  y_.resize(m);
  mx_.resize(m);
  my_.resize(m);
  for (int k = 0; k < m; ++k) {
    h_[k] = ((k + 1 < m) ? c.knot(k + 1) : c.period()) - c.knot(k);
    x_[k] = c.markers()(0, k);
    y_[k] = c.markers()(1, k);
    mx_[k] = c.x_spline().SecondDerivativeAtKnot(k);
    my_[k] = c.y_spline().SecondDerivativeAtKnot(k);
  }
  orientation_ = c.orientation();
}

SplineDerivatives CurveSegments::Evaluate(int k, double t) const {
  const int m = size();
  const int kp = (k + 1 == m) ? 0 : k + 1;
  const double h = h_[k], u = h - t, inv6h = 1.0 / (6.0 * h);
  SplineDerivatives p;
  {
    const double a = x_[k] / h - mx_[k] * h / 6.0, b = x_[kp] / h - mx_[kp] * h / 6.0;
    p.x = (mx_[k] * u * u * u + mx_[kp] * t * t * t) * inv6h + a * u + b * t;
    p.dx = 3.0 * (mx_[kp] * t * t - mx_[k] * u * u) * inv6h - a + b;
    p.ddx = (mx_[k] * u + mx_[kp] * t) / h;
  }
  {
    const double a = y_[k] / h - my_[k] * h / 6.0, b = y_[kp] / h - my_[kp] * h / 6.0;
    p.y = (my_[k] * u * u * u + my_[kp] * t * t * t) * inv6h + a * u + b * t;
    p.dy = 3.0 * (my_[kp] * t * t - my_[k] * u * u) * inv6h - a + b;
    p.ddy = (my_[k] * u + my_[kp] * t) / h;
  }
  return p;
}

double CurveSegments::SegmentArcLength(int k) const {
  const double h = h_[k];
  double len = 0.0;
  for (int q = 0; q < 5; ++q) {
    const SplineDerivatives p = Evaluate(k, kGaussNode[q] * h);
    len += kGaussWeight[q] * std::hypot(p.dx, p.dy);
  }
  return len * h;
}

CurvePoint CurveSegments::AtMarker(int k) const {
  const SplineDerivatives d = Evaluate(k, 0.0);
  CurvePoint p;
  p.position = {d.x, d.y};
  p.speed = std::hypot(d.dx, d.dy);
  p.tangent = orientation_ * Eigen::Vector2d(d.dx, d.dy) / p.speed;
  p.normal = {p.tangent.y(), -p.tangent.x()};
  p.curvature = orientation_ * (d.dx * d.ddy - d.dy * d.ddx) / (p.speed * p.speed * p.speed);
  return p;
}

}  // namespace ehd
