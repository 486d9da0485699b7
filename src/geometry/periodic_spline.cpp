#include "ehd_capsule/geometry/periodic_spline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "ehd_capsule/geometry/gauss_legendre.h"

namespace ehd {
namespace {

// Solves the cyclic tridiagonal system a_k x_{k-1} + b_k x_k + c_k x_{k+1} = r_k (indices mod n)
// by Sherman-Morrison on top of the Thomas algorithm. Needs n >= 3.
std::vector<double> SolveCyclicTridiagonal(const std::vector<double>& a, std::vector<double> b,
                                           const std::vector<double>& c,
                                           const std::vector<double>& r) {
  const int n = static_cast<int>(b.size());
  const double alpha = c[n - 1];  // corner (n-1, 0)
  const double beta = a[0];       // corner (0, n-1)
  const double gamma = -b[0];
  b[0] -= gamma;
  b[n - 1] -= alpha * beta / gamma;

  auto thomas = [&](const std::vector<double>& rhs) {
    std::vector<double> cp(n), dp(n), x(n);
    cp[0] = c[0] / b[0];
    dp[0] = rhs[0] / b[0];
    for (int k = 1; k < n; ++k) {
      const double m = b[k] - a[k] * cp[k - 1];
      cp[k] = c[k] / m;
      dp[k] = (rhs[k] - a[k] * dp[k - 1]) / m;
    }
    x[n - 1] = dp[n - 1];
    for (int k = n - 2; k >= 0; --k) x[k] = dp[k] - cp[k] * x[k + 1];
    return x;
  };

  std::vector<double> x = thomas(r);
  std::vector<double> u(n, 0.0);
  u[0] = gamma;
  u[n - 1] = alpha;
  std::vector<double> z = thomas(u);
  const double fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0] + beta * z[n - 1] / gamma);
  for (int k = 0; k < n; ++k) x[k] -= fact * z[k];
  return x;
}

}  // namespace

void PeriodicCubicSpline::Fit(const std::vector<double>& knots, double period,
                              const std::vector<double>& values) {
  const int n = static_cast<int>(knots.size());
  if (n < 3 || values.size() != knots.size()) {
    throw std::invalid_argument(
        "PeriodicCubicSpline: need at least 3 knots and one value each (got " + std::to_string(n) +
        " knots, " + std::to_string(values.size()) + " values)");
  }
  if (!(period > knots.back())) {
    throw std::invalid_argument("PeriodicCubicSpline: period must exceed the last knot");
  }
  for (int k = 1; k < n; ++k) {
    if (!(knots[k] > knots[k - 1])) {
      throw std::invalid_argument("PeriodicCubicSpline: knots must be strictly increasing (knot " +
                                  std::to_string(k) + ")");
    }
  }
  knots_ = knots;
  values_ = values;
  period_ = period;

  std::vector<double> hk(n);
  for (int k = 0; k < n; ++k) hk[k] = (k + 1 < n ? knots[k + 1] : period) - knots[k];
  std::vector<double> a(n), b(n), c(n), r(n);
  for (int k = 0; k < n; ++k) {
    const int km = (k + n - 1) % n;
    const int kp = (k + 1) % n;
    a[k] = hk[km];
    b[k] = 2.0 * (hk[km] + hk[k]);
    c[k] = hk[k];
    r[k] = 6.0 * ((values[kp] - values[k]) / hk[k] - (values[k] - values[km]) / hk[km]);
  }
  second_ = SolveCyclicTridiagonal(a, b, c, r);
}

std::vector<double> PeriodicCubicSpline::IntegralWeights(const std::vector<double>& knots,
                                                         double period,
                                                         const std::vector<double>& rho_at_nodes) {
  const int n = static_cast<int>(knots.size());
  if (n < 3 || rho_at_nodes.size() != static_cast<std::size_t>(n) * kGaussPoints) {
    throw std::invalid_argument("PeriodicCubicSpline::IntegralWeights: need >= 3 knots and " +
                                std::to_string(kGaussPoints) + " node values per segment");
  }
  std::vector<double> hk(n), alpha(n, 0.0), beta(n, 0.0);
  for (int k = 0; k < n; ++k) hk[k] = (k + 1 < n ? knots[k + 1] : period) - knots[k];
  for (int k = 0; k < n; ++k) {
    const int kp = (k + 1) % n;
    const double h = hk[k];
    for (int q = 0; q < kGaussPoints; ++q) {
      const double t = kGaussNode[q] * h;
      const double w = kGaussWeight[q] * h * rho_at_nodes[k * kGaussPoints + q];
      // S = y_k (1 - t/h) + y_k+1 t/h + M_k (-h t/3 + t^2/2 - t^3/(6h)) + M_k+1 (-h t/6 + t^3/(6h))
      alpha[k] += w * (1.0 - t / h);
      alpha[kp] += w * (t / h);
      beta[k] += w * (-h * t / 3.0 + 0.5 * t * t - t * t * t / (6.0 * h));
      beta[kp] += w * (-h * t / 6.0 + t * t * t / (6.0 * h));
    }
  }
  std::vector<double> a(n), b(n), c(n);
  for (int k = 0; k < n; ++k) {
    const int km = (k + n - 1) % n;
    a[k] = hk[km];
    b[k] = 2.0 * (hk[km] + hk[k]);
    c[k] = hk[k];
  }
  const std::vector<double> z = SolveCyclicTridiagonal(a, b, c, beta);  // T^-1 beta
  std::vector<double> w(n);
  for (int k = 0; k < n; ++k) {
    const int km = (k + n - 1) % n;
    const int kp = (k + 1) % n;
    // (R z)_k = 6 [(z_k+1 - z_k) / h_k - (z_k - z_k-1) / h_k-1]
    w[k] = alpha[k] + 6.0 * ((z[kp] - z[k]) / hk[k] - (z[k] - z[km]) / hk[km]);
  }
  return w;
}

double PeriodicCubicSpline::Wrap(double s) const {
  double w = std::fmod(s, period_);
  if (w < 0.0) w += period_;
  return w;
}

int PeriodicCubicSpline::Locate(double s, double* t) const {
  const double w = Wrap(s);
  auto it = std::upper_bound(knots_.begin(), knots_.end(), w);
  int k = static_cast<int>(it - knots_.begin()) - 1;
  if (k < 0) k = 0;
  *t = w - knots_[k];
  return k;
}

PeriodicCubicSpline::Segment PeriodicCubicSpline::SegmentAt(double s) const {
  Segment seg;
  const int k = Locate(s, &seg.t);
  const int n = size();
  const int kp = (k + 1) % n;
  const double h = (k + 1 < n ? knots_[k + 1] : period_) - knots_[k];
  seg.a = values_[k];
  seg.b = (values_[kp] - values_[k]) / h - h * (2.0 * second_[k] + second_[kp]) / 6.0;
  seg.c = 0.5 * second_[k];
  seg.d = (second_[kp] - second_[k]) / (6.0 * h);
  return seg;
}

double PeriodicCubicSpline::Value(double s) const {
  const Segment g = SegmentAt(s);
  return g.a + g.t * (g.b + g.t * (g.c + g.t * g.d));
}

double PeriodicCubicSpline::Derivative(double s) const {
  const Segment g = SegmentAt(s);
  return g.b + g.t * (2.0 * g.c + 3.0 * g.d * g.t);
}

double PeriodicCubicSpline::SecondDerivative(double s) const {
  const Segment g = SegmentAt(s);
  return 2.0 * g.c + 6.0 * g.d * g.t;
}

double PeriodicCubicSpline::DerivativeAtKnot(int k) const {
  const int n = size();
  const int kp = (k + 1) % n;
  const double h = (k + 1 < n ? knots_[k + 1] : period_) - knots_[k];
  return (values_[kp] - values_[k]) / h - h * (2.0 * second_[k] + second_[kp]) / 6.0;
}

}  // namespace ehd
