#include "ehd_capsule/geometry/closed_curve.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "ehd_capsule/geometry/gauss_legendre.h"

namespace ehd {
void ClosedCurve::Update(const Eigen::Matrix2Xd& markers) {
  const int m = static_cast<int>(markers.cols());
  if (m < 3) throw std::invalid_argument("ClosedCurve: need at least 3 markers");
  if (!markers.allFinite())
    throw std::invalid_argument("ClosedCurve: marker position is not finite");
  markers_ = markers;
  knots_.assign(m, 0.0);
  max_chord_ = 0.0;
  double polygon_area2 = 0.0;
  for (int k = 0; k < m; ++k) {
    const int kp = (k + 1) % m;
    const double chord = (markers.col(kp) - markers.col(k)).norm();
    if (!(chord > 0.0)) {
      throw std::invalid_argument("ClosedCurve: markers " + std::to_string(k) + " and " +
                                  std::to_string(kp) + " coincide");
    }
    max_chord_ = std::max(max_chord_, chord);
    if (kp != 0)
      knots_[kp] = knots_[k] + chord;
    else
      period_ = knots_[k] + chord;
    polygon_area2 += markers(0, k) * markers(1, kp) - markers(0, kp) * markers(1, k);
  }
  orientation_ = polygon_area2 >= 0.0 ? 1 : -1;
  std::vector<double> xs(m), ys(m);
  for (int k = 0; k < m; ++k) {
    xs[k] = markers(0, k);
    ys[k] = markers(1, k);
  }
  x_.Fit(knots_, period_, xs);
  y_.Fit(knots_, period_, ys);
}

CurvePoint ClosedCurve::At(double s) const {
  CurvePoint p;
  p.s = s;
  p.position = {x_.Value(s), y_.Value(s)};
  const Eigen::Vector2d d1(x_.Derivative(s), y_.Derivative(s));
  const Eigen::Vector2d d2(x_.SecondDerivative(s), y_.SecondDerivative(s));
  p.speed = d1.norm();
  p.tangent = orientation_ * d1 / p.speed;
  p.normal = {p.tangent.y(), -p.tangent.x()};
  p.curvature = orientation_ * (d1.x() * d2.y() - d1.y() * d2.x()) / (p.speed * p.speed * p.speed);
  return p;
}

double ClosedCurve::SegmentArcLength(int k) const {
  const int m = size();
  const double s0 = knots_[k];
  const double s1 = (k + 1 < m) ? knots_[k + 1] : period_;
  double len = 0.0;
  for (int q = 0; q < 5; ++q) {
    const double s = s0 + kGaussNode[q] * (s1 - s0);
    len += kGaussWeight[q] * std::hypot(x_.Derivative(s), y_.Derivative(s));
  }
  return len * (s1 - s0);
}

double ClosedCurve::ArcLength() const {
  double len = 0.0;
  for (int k = 0; k < size(); ++k) len += SegmentArcLength(k);
  return len;
}

double ClosedCurve::Area() const {
  const int m = size();
  double area2 = 0.0;
  for (int k = 0; k < m; ++k) {
    const double s0 = knots_[k];
    const double s1 = (k + 1 < m) ? knots_[k + 1] : period_;
    for (int q = 0; q < 5; ++q) {
      const double s = s0 + kGaussNode[q] * (s1 - s0);
      area2 += kGaussWeight[q] * (s1 - s0) *
               (x_.Value(s) * y_.Derivative(s) - y_.Value(s) * x_.Derivative(s));
    }
  }
  return 0.5 * std::abs(area2);
}

Eigen::Vector2d ClosedCurve::Centroid() const {
  // Green's theorem: A c_x = 1/2 \oint x^2 dy, A c_y = -1/2 \oint y^2 dx (counter-clockwise).
  const int m = size();
  double area2 = 0.0, mx = 0.0, my = 0.0;
  for (int k = 0; k < m; ++k) {
    const double s0 = knots_[k];
    const double s1 = (k + 1 < m) ? knots_[k + 1] : period_;
    for (int q = 0; q < 5; ++q) {
      const double s = s0 + kGaussNode[q] * (s1 - s0);
      const double w = kGaussWeight[q] * (s1 - s0);
      const double x = x_.Value(s), y = y_.Value(s);
      const double dx = x_.Derivative(s), dy = y_.Derivative(s);
      area2 += w * (x * dy - y * dx);
      mx += w * x * x * dy;
      my -= w * y * y * dx;
    }
  }
  return {mx / area2, my / area2};
}

double ClosedCurve::ClosestParameter(const Eigen::Vector2d& p) const {
  const int m = size();
  // Start from the closest point of the marker polygon, then Newton on g(s) = (X(s) - p).X'(s).
  double best_s = 0.0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < m; ++k) {
    const int kp = (k + 1) % m;
    const Eigen::Vector2d a = markers_.col(k), b = markers_.col(kp);
    const Eigen::Vector2d ab = b - a;
    double t = (p - a).dot(ab) / ab.squaredNorm();
    t = std::clamp(t, 0.0, 1.0);
    const double d2 = (a + t * ab - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      const double s1 = (kp != 0) ? knots_[kp] : period_;
      best_s = knots_[k] + t * (s1 - knots_[k]);
    }
  }
  double s = best_s;
  for (int it = 0; it < 20; ++it) {
    const Eigen::Vector2d x(x_.Value(s), y_.Value(s));
    const Eigen::Vector2d d1(x_.Derivative(s), y_.Derivative(s));
    const Eigen::Vector2d d2(x_.SecondDerivative(s), y_.SecondDerivative(s));
    const double g = (x - p).dot(d1);
    const double dg = d1.squaredNorm() + (x - p).dot(d2);
    if (!(dg > 0.0)) break;
    double step = g / dg;
    const double limit = 0.5 * max_chord_;
    step = std::clamp(step, -limit, limit);
    s -= step;
    if (std::abs(step) < 1e-14 * period_) break;
  }
  s = std::fmod(s, period_);
  if (s < 0.0) s += period_;
  return s;
}

double ClosedCurve::SignedDistance(const Eigen::Vector2d& p) const {
  const CurvePoint c = At(ClosestParameter(p));
  const Eigen::Vector2d d = p - c.position;
  const double dist = d.norm();
  return d.dot(c.normal) >= 0.0 ? dist : -dist;
}

bool ClosedCurve::PolygonContains(const Eigen::Vector2d& p) const {
  bool inside = false;
  const int m = size();
  for (int k = 0, km = m - 1; k < m; km = k++) {
    const double xi = markers_(0, k), yi = markers_(1, k);
    const double xj = markers_(0, km), yj = markers_(1, km);
    if (((yi > p.y()) != (yj > p.y())) && (p.x() < (xj - xi) * (p.y() - yi) / (yj - yi) + xi)) {
      inside = !inside;
    }
  }
  return inside;
}

bool ClosedCurve::Contains(const Eigen::Vector2d& p) const {
  // Distance to the polygon bounds the distance to the spline within O(chord^2 kappa); two
  // chords is a safe band for any curve resolved by its markers.
  const int m = size();
  double d2min = std::numeric_limits<double>::infinity();
  for (int k = 0; k < m; ++k) d2min = std::min(d2min, (markers_.col(k) - p).squaredNorm());
  if (d2min > 4.0 * max_chord_ * max_chord_) return PolygonContains(p);
  return SignedDistance(p) < 0.0;
}

PeriodicCubicSpline ClosedCurve::FitScalar(const std::vector<double>& values) const {
  PeriodicCubicSpline f;
  f.Fit(knots_, period_, values);
  return f;
}

void ClosedCurve::ArcLengthDerivatives(const PeriodicCubicSpline& f, double s, double* d1,
                                       double* d2) const {
  const Eigen::Vector2d r1(x_.Derivative(s), y_.Derivative(s));
  const Eigen::Vector2d r2(x_.SecondDerivative(s), y_.SecondDerivative(s));
  const double speed = r1.norm();
  const double fs = f.Derivative(s);
  const double fss = f.SecondDerivative(s);
  // d/dl = (1/|X'|) d/ds, and d|X'|/ds = X'.X''/|X'|. The sign follows the spline parameter;
  // multiply by orientation() to get derivatives along the counter-clockwise tangent.
  const double o = orientation_;
  *d1 = o * fs / speed;
  *d2 = (fss / speed - fs * r1.dot(r2) / (speed * speed * speed)) / speed;
}

}  // namespace ehd
