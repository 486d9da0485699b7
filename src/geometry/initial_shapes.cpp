// Circle, ellipse and song2019 eq. (152) biconcave marker sets; see initial_shapes.h.
// Equal-arc-length placement: the arc length s(t) of the analytic parametrisation is tabulated
// with 3-point Gauss-Legendre on a fine uniform t grid (error ~ (2 pi / n)^6), and s(t_k) = k L / M
// is inverted by linear interpolation in the table followed by Newton steps on the exact |X'(t)|.
#include "ehd_capsule/geometry/initial_shapes.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ehd {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// A closed curve X(t), t in [0, 2 pi), and its derivative.
struct Parametric {
  std::function<Eigen::Vector2d(double)> point;
  std::function<Eigen::Vector2d(double)> derivative;
};

void CheckCount(int markers) {
  if (markers < 3) {
    throw std::invalid_argument("initial shape: markers must be >= 3, got " +
                                std::to_string(markers));
  }
}

double ArcLength(const Parametric& c, double t0, double t1) {
  // 3-point Gauss-Legendre on [t0, t1].
  const double mid = 0.5 * (t0 + t1), half = 0.5 * (t1 - t0);
  const double node = 0.7745966692414834;
  return half * (5.0 / 9.0 * c.derivative(mid - half * node).norm() +
                 8.0 / 9.0 * c.derivative(mid).norm() +
                 5.0 / 9.0 * c.derivative(mid + half * node).norm());
}

Eigen::Matrix2Xd Sample(const Parametric& c, int markers, MarkerSpacing spacing) {
  CheckCount(markers);
  Eigen::Matrix2Xd x(2, markers);
  if (spacing == MarkerSpacing::kUniformParameter) {
    for (int k = 0; k < markers; ++k) x.col(k) = c.point(kTwoPi * k / markers);
    return x;
  }
  const int n = std::max(4096, 64 * markers);
  const double dt = kTwoPi / n;
  std::vector<double> table(n + 1, 0.0);
  for (int i = 0; i < n; ++i) table[i + 1] = table[i] + ArcLength(c, i * dt, (i + 1) * dt);
  const double total = table[n];
  for (int k = 0; k < markers; ++k) {
    const double target = total * k / markers;
    const int i = std::clamp(
        static_cast<int>(std::upper_bound(table.begin(), table.end(), target) - table.begin()) - 1,
        0, n - 1);
    double t = (i + (target - table[i]) / (table[i + 1] - table[i])) * dt;
    for (int it = 0; it < 3; ++it) {
      const double s = table[i] + ArcLength(c, i * dt, t);
      t -= (s - target) / c.derivative(t).norm();
    }
    x.col(k) = c.point(t);
  }
  return x;
}

Eigen::Matrix2Xd Place(Eigen::Matrix2Xd x, const Eigen::Vector2d& centre, double angle) {
  const double ca = std::cos(angle), sa = std::sin(angle);
  Eigen::Matrix2d rot;
  rot << ca, -sa, sa, ca;
  x = rot * x;
  x.colwise() += centre;
  return x;
}

}  // namespace

Eigen::Matrix2Xd CircleMarkers(int markers, double radius, const Eigen::Vector2d& centre) {
  CheckCount(markers);
  if (!(radius > 0.0)) {
    throw std::invalid_argument("CircleMarkers: radius must be > 0, got " + std::to_string(radius));
  }
  Eigen::Matrix2Xd x(2, markers);
  for (int k = 0; k < markers; ++k) {
    const double t = kTwoPi * k / markers;
    x.col(k) = centre + radius * Eigen::Vector2d(std::cos(t), std::sin(t));
  }
  return x;
}

Eigen::Matrix2Xd EllipseMarkers(int markers, double a, double b, const Eigen::Vector2d& centre,
                                double angle, MarkerSpacing spacing) {
  if (!(a > 0.0) || !(b > 0.0)) {
    throw std::invalid_argument("EllipseMarkers: semi-axes must be > 0, got a=" +
                                std::to_string(a) + ", b=" + std::to_string(b));
  }
  const Parametric c{
      [a, b](double t) { return Eigen::Vector2d(a * std::cos(t), b * std::sin(t)); },
      [a, b](double t) { return Eigen::Vector2d(-a * std::sin(t), b * std::cos(t)); }};
  return Place(Sample(c, markers, spacing), centre, angle);
}

Eigen::Matrix2Xd BiconcaveMarkers(int markers, const BiconcaveParameters& p,
                                  const Eigen::Vector2d& centre, double angle,
                                  MarkerSpacing spacing) {
  if (!(p.radius > 0.0) || !(p.alpha > 0.0)) {
    throw std::invalid_argument("BiconcaveMarkers: radius and alpha must be > 0, got radius=" +
                                std::to_string(p.radius) + ", alpha=" + std::to_string(p.alpha));
  }
  const double ra = p.radius * p.alpha;
  // chi = pi/2 - t: counter-clockwise, marker 0 at (a alpha, 0).
  const Parametric c{[ra, p](double t) {
                       const double s = std::cos(t), co = std::sin(t);  // sin chi, cos chi
                       const double s2 = s * s;
                       return Eigen::Vector2d(ra * s,
                                              0.5 * ra * (p.c0 + p.c1 * s2 + p.c2 * s2 * s2) * co);
                     },
                     [ra, p](double t) {
                       // d/dt = -d/dchi; d(sin chi)/dchi = cos chi, d(cos chi)/dchi = -sin chi.
                       const double s = std::cos(t), co = std::sin(t);
                       const double s2 = s * s;
                       const double g = p.c0 + p.c1 * s2 + p.c2 * s2 * s2;
                       const double dg = (2.0 * p.c1 * s + 4.0 * p.c2 * s2 * s) * co;  // dg/dchi
                       const double dx = ra * co;
                       const double dy = 0.5 * ra * (dg * co - g * s);
                       return Eigen::Vector2d(-dx, -dy);
                     }};
  return Place(Sample(c, markers, spacing), centre, angle);
}

double BiconcaveArea(const BiconcaveParameters& p) {
  // A = |oint y dx| = (a alpha)^2 / 2 int_0^{2pi} (c0 + c1 s^2 + c2 s^4) cos^2 chi dchi with
  // int cos^2 = pi, int sin^2 cos^2 = pi/4, int sin^4 cos^2 = pi/8.
  const double ra = p.radius * p.alpha;
  return 0.5 * ra * ra * M_PI * (p.c0 + 0.25 * p.c1 + 0.125 * p.c2);
}

}  // namespace ehd
