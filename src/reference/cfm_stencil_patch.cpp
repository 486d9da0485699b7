// CFM integration region Omega_Sigma^ij (song2019 sec. 2.3.2) and interface quadrature; see the
// header for the construction and the one safeguard added to the text.
#include "ehd_capsule/reference/cfm_stencil_patch.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "ehd_capsule/geometry/gauss_legendre.h"

namespace ehd {
namespace {

// Bisection steps locating where the curve leaves the diamond or the patch: the bracket shrinks
// from the walking step h/4 to ~1e-5 h. The ends only bound the quadrature interval and the
// bounding box, so this precision is ample (exact data stay exact on any sub-interval).
constexpr int kBisections = 15;
// Smallest half side of a patch relative to its largest (see the header).
constexpr double kMinAspect = 0.25;

Eigen::Vector2d Position(const ClosedCurve& curve, double s) {
  return {curve.x_spline().Value(s), curve.y_spline().Value(s)};
}

// (p - X(s)).n at the closest point: > 0 outside (Omega^+), < 0 inside.
double SideValue(const ClosedCurve& curve, const Eigen::Vector2d& p, double* s_hint) {
  *s_hint = CfmLocalClosestParameter(curve, p, *s_hint);
  const CurvePoint c = curve.At(*s_hint);
  return (p - c.position).dot(c.normal);
}

// Walks along the curve from s_start (inside the region) in direction dir with steps `step`
// until `inside` fails, then bisects to the boundary. Returns the boundary parameter, or the
// parameter after max_steps if the region was never left.
template <typename Inside>
double WalkToBoundary(const ClosedCurve& curve, double s_start, double dir, double step,
                      int max_steps, const Inside& inside) {
  double s_in = s_start;
  for (int n = 0; n < max_steps; ++n) {
    const double s_next = s_in + dir * step;
    if (!inside(Position(curve, s_next))) {
      double s_out = s_next;
      for (int it = 0; it < kBisections; ++it) {
        const double mid = 0.5 * (s_in + s_out);
        (inside(Position(curve, mid)) ? s_in : s_out) = mid;
      }
      return s_in;
    }
    s_in = s_next;
  }
  return s_in;
}

}  // namespace

double CfmLocalClosestParameter(const ClosedCurve& curve, const Eigen::Vector2d& p, double s_hint) {
  const PeriodicCubicSpline& xs = curve.x_spline();
  const PeriodicCubicSpline& ys = curve.y_spline();
  const double limit = 0.5 * curve.period() / curve.size();
  double s = s_hint;
  for (int it = 0; it < 40; ++it) {
    const Eigen::Vector2d x(xs.Value(s), ys.Value(s));
    const Eigen::Vector2d d1(xs.Derivative(s), ys.Derivative(s));
    const Eigen::Vector2d d2(xs.SecondDerivative(s), ys.SecondDerivative(s));
    const double g = (x - p).dot(d1);
    double dg = d1.squaredNorm() + (x - p).dot(d2);
    if (!(dg > 0.25 * d1.squaredNorm())) dg = d1.squaredNorm();  // keep a descent step
    const double step = std::clamp(g / dg, -limit, limit);
    s -= step;
    if (std::abs(step) < 1e-13 * curve.period()) break;
  }
  return s;
}

bool BuildCfmStencilPatch(const ClosedCurve& curve, const Eigen::Vector2d& center, double h,
                          const Eigen::Vector2d* far_nodes, int n_far, double s_hint,
                          CfmStencilPatch* out) {
  if (n_far < 1 || n_far > 4) {
    throw std::invalid_argument("BuildCfmStencilPatch: n_far = " + std::to_string(n_far) +
                                " must be in [1, 4]");
  }
  // 1. A crossing of Sigma on an arm, by bisection of the side function.
  double s = s_hint;
  const double side_center = SideValue(curve, center, &s);
  double s_cross = 0.0;
  bool found = false;
  for (int k = 0; k < n_far && !found; ++k) {
    double s_far = s;
    const double side_far = SideValue(curve, far_nodes[k], &s_far);
    if ((side_center < 0.0) == (side_far < 0.0)) continue;
    // Illinois (modified regula falsi) on the side function along the arm x(t), t in [0, 1].
    double t_a = 0.0, f_a = side_center, t_b = 1.0, f_b = side_far;
    double s_mid = s;
    int last_kept = 0;
    for (int it = 0; it < 60; ++it) {
      const double t = (t_a * f_b - t_b * f_a) / (f_b - f_a);
      const double side = SideValue(curve, center + t * (far_nodes[k] - center), &s_mid);
      if (std::abs(side) <= 1e-10 * h || t_b - t_a <= 1e-12) break;
      if ((side < 0.0) == (f_a < 0.0)) {
        t_a = t;
        f_a = side;
        if (last_kept == -1) f_b *= 0.5;
        last_kept = -1;
      } else {
        t_b = t;
        f_b = side;
        if (last_kept == 1) f_a *= 0.5;
        last_kept = 1;
      }
    }
    s_cross = s_mid;
    found = true;
  }
  if (!found) return false;

  // 2. Sigma_ij: the piece through the crossing inside the stencil's diamond.
  const double step = 0.25 * h;
  const int max_steps = 32;
  const auto in_diamond = [&](const Eigen::Vector2d& x) {
    return std::abs(x.x() - center.x()) + std::abs(x.y() - center.y()) <= h * (1.0 + 1e-12);
  };
  const double s0 = WalkToBoundary(curve, s_cross, -1.0, step, max_steps, in_diamond);
  const double s1 = WalkToBoundary(curve, s_cross, +1.0, step, max_steps, in_diamond);

  // 3. Rotated frame: theta_r = theta_Sigma - pi/4.
  const Eigen::Vector2d t_mid = curve.At(0.5 * (s0 + s1)).tangent;
  const double theta_r = std::atan2(t_mid.y(), t_mid.x()) - 0.25 * M_PI;
  CfmPatch& patch = out->patch;
  patch.axis_p = {std::cos(theta_r), std::sin(theta_r)};
  patch.axis_q = {-std::sin(theta_r), std::cos(theta_r)};

  // 4. Bounding (p, q) rectangle of Sigma_ij (sampled) and the far nodes.
  double p_min = std::numeric_limits<double>::infinity(), p_max = -p_min;
  double q_min = p_min, q_max = -p_min;
  const auto include = [&](const Eigen::Vector2d& x) {
    const double p = x.dot(patch.axis_p), q = x.dot(patch.axis_q);
    p_min = std::min(p_min, p);
    p_max = std::max(p_max, p);
    q_min = std::min(q_min, q);
    q_max = std::max(q_max, q);
  };
  constexpr int kPieceSamples = 16;
  for (int k = 0; k <= kPieceSamples; ++k) {
    include(Position(curve, s0 + (s1 - s0) * k / kPieceSamples));
  }
  for (int k = 0; k < n_far; ++k) include(far_nodes[k]);
  patch.half_p = 0.5 * (p_max - p_min);
  patch.half_q = 0.5 * (q_max - q_min);
  const double min_half = std::max(kMinAspect * std::max(patch.half_p, patch.half_q), 1e-3 * h);
  patch.half_p = std::max(patch.half_p, min_half);
  patch.half_q = std::max(patch.half_q, min_half);
  patch.center = 0.5 * (p_min + p_max) * patch.axis_p + 0.5 * (q_min + q_max) * patch.axis_q;

  // 5. Sigma cap patch: extend Sigma_ij to the rectangle's edges.
  const auto in_patch = [&](const Eigen::Vector2d& x) {
    const Eigen::Vector2d local = patch.Local(x);
    return std::abs(local.x()) <= 1.0 + 1e-12 && std::abs(local.y()) <= 1.0 + 1e-12;
  };
  out->s_begin = WalkToBoundary(curve, s0, -1.0, step, 2 * max_steps, in_patch);
  out->s_end = WalkToBoundary(curve, s1, +1.0, step, 2 * max_steps, in_patch);
  out->s_hint = 0.5 * (s0 + s1);
  return out->s_end > out->s_begin;
}

int CfmInterfaceQuadrature(const ClosedCurve& curve, const CfmStencilPatch& stencil_patch,
                           int n_sub, CfmInterfaceSample* samples, double* sample_parameters) {
  if (n_sub < 1 || 4 * n_sub > CfmLocalCauchy::kMaxInterfaceSamples) {
    throw std::invalid_argument("CfmInterfaceQuadrature: n_sub = " + std::to_string(n_sub) +
                                " must be in [1, " +
                                std::to_string(CfmLocalCauchy::kMaxInterfaceSamples / 4) + "]");
  }
  const double ds = (stencil_patch.s_end - stencil_patch.s_begin) / n_sub;
  int n = 0;
  for (int sub = 0; sub < n_sub; ++sub) {
    const double mid = stencil_patch.s_begin + (sub + 0.5) * ds;
    for (int g = 0; g < 4; ++g) {
      const double s = mid + 0.5 * ds * kGauss4Node[g];
      const CurvePoint c = curve.At(s);
      samples[n].position = c.position;
      samples[n].normal = c.normal;
      samples[n].weight = 0.5 * ds * kGauss4Weight[g] * c.speed;
      sample_parameters[n] = s;
      ++n;
    }
  }
  return n;
}

}  // namespace ehd
