// Boundary-integral (boundary-element) solver for a 2D capsule or drop with viscosity ratio 1 in
// unbounded simple shear at Re = 0: the independent reference for the LBM-IB capsule (issue #4).
//
// Stokes single layer (Pozrikidis 1992, sec. 2.6 and 5.3; equal viscosities, no double layer):
//   u(x) = u_inf(x) + (1/(4 pi mu)) oint G(x - y) . f(y) dl(y),   u_inf = (k y, 0),
//   G_ij(r) = -delta_ij ln|r| + r_i r_j / |r|^2   (2D Stokeslet: a point force F on the fluid
//   gives the velocity G . F / (4 pi mu)).
// f is the force density the membrane exerts ON THE FLUID (the code's convention,
// membrane_force.h); Pozrikidis writes -Delta f with Delta f = -f the traction jump
// sigma_out.n - sigma_in.n, so the sign here is +. Check: a relaxing ellipse under tension
// (f = -gamma kappa n) returns to a circle, and a uniformly stretched circle does not move
// (oint G . n dl = 0 for a closed curve because G is divergence-free).
//
// Discretisation: the M markers are the nodes t_k = 2 pi k / M of the material (Lagrangian)
// parametrisation. x'(t) by the spectral (trigonometric) differentiation matrix
//   D_ik = (1/2) (-1)^(i-k) cot((t_i - t_k)/2)   (M even, Trefethen, Spectral Methods, ch. 3),
// speed s = |x'|, density phi = f s. The log part uses Kress' product quadrature
// (Kress, Linear Integral Equations, sec. 12.3): with M = 2n,
//   int ln(4 sin^2((t - tau)/2)) phi(tau) dtau ~ sum_k R_k(t) phi_k,
//   R_k(t) = -(2 pi / n) sum_{m=1}^{n-1} cos(m (t - t_k)) / m - (pi / n^2) cos(n (t - t_k)),
// and ln|x(t) - x(tau)| - (1/2) ln(4 sin^2((t - tau)/2)) is smooth (trapezoidal rule, limit
// ln s(t) on the diagonal); r r^T / r^2 is smooth with limit t t^T (unit tangent). Spectrally
// accurate for a smooth curve and density; the membrane force itself (reused from the core,
// MembraneModel: 5-point arc-length differences on the spline) is the accuracy limit.
// Time: Heun (explicit trapezoidal RK2), fixed dt. O(M^2) per velocity evaluation, no
// allocation per step.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/membrane/membrane_model.h"

namespace ehd::bie {

// Velocity at the nodes of a closed curve from a force density on it (single layer above).
class StokesSingleLayer2D {
 public:
  explicit StokesSingleLayer2D(int markers) : m_(markers) {
    if (markers < 8 || markers % 2 != 0) {
      throw std::invalid_argument("StokesSingleLayer2D: markers must be even and >= 8, got " +
                                  std::to_string(markers));
    }
    const int n = m_ / 2;
    const double pi = std::acos(-1.0);
    kress_.assign(m_, 0.0);
    log_sin_.assign(m_, 0.0);
    diff_.assign(m_, 0.0);
    for (int d = 0; d < m_; ++d) {
      const double t = 2.0 * pi * d / m_;
      double r = 0.0;
      for (int j = 1; j < n; ++j) r += std::cos(j * t) / j;
      kress_[d] = -(2.0 * pi / n) * r - (pi / (double(n) * n)) * std::cos(n * t);
      if (d > 0) {
        const double s = std::sin(0.5 * t);
        log_sin_[d] = 0.5 * std::log(4.0 * s * s);
        diff_[d] = 0.5 * ((d % 2) ? -1.0 : 1.0) / std::tan(0.5 * t);
      }
    }
    derivative_.resize(2, m_);
    speed_.assign(m_, 0.0);
    density_.resize(2, m_);
  }

  int size() const { return m_; }

  // dx/dt at the nodes (2 x M) by the trigonometric differentiation matrix, t_k = 2 pi k / M.
  void Derivative(const Eigen::Matrix2Xd& x, Eigen::Matrix2Xd& dx) const {
    dx.resize(2, m_);
    for (int i = 0; i < m_; ++i) {
      double sx = 0.0, sy = 0.0;
      for (int k = 0; k < m_; ++k) {
        const double c = diff_[(i - k + m_) % m_];
        sx += c * x(0, k);
        sy += c * x(1, k);
      }
      dx(0, i) = sx;
      dx(1, i) = sy;
    }
  }

  // u (2 x M) = shear_rate (y, 0) + single layer of force_density (2 x M, per unit length) at the
  // markers x (2 x M), fluid viscosity mu.
  void Velocity(const Eigen::Matrix2Xd& x, const Eigen::Matrix2Xd& force_density, double mu,
                double shear_rate, Eigen::Matrix2Xd& u) {
    if (x.cols() != m_ || force_density.cols() != m_) {
      throw std::invalid_argument("StokesSingleLayer2D::Velocity: expected " + std::to_string(m_) +
                                  " markers, got " + std::to_string(x.cols()));
    }
    const double pi = std::acos(-1.0);
    const double w = 2.0 * pi / m_;
    Derivative(x, derivative_);
    for (int i = 0; i < m_; ++i) {
      speed_[i] = std::hypot(derivative_(0, i), derivative_(1, i));
      density_.col(i) = force_density.col(i) * speed_[i];
    }
    u.resize(2, m_);
    const double scale = 1.0 / (4.0 * pi * mu);
    for (int i = 0; i < m_; ++i) {
      const double xi = x(0, i), yi = x(1, i);
      // Diagonal: log part (1/2) R_0 + w ln s_i; rational part t t^T.
      const double tx = derivative_(0, i) / speed_[i], ty = derivative_(1, i) / speed_[i];
      const double px = density_(0, i), py = density_(1, i);
      const double log_w = 0.5 * kress_[0] + w * std::log(speed_[i]);
      const double tp = tx * px + ty * py;
      double ux = -log_w * px + w * tx * tp;
      double uy = -log_w * py + w * ty * tp;
      for (int k = 0; k < m_; ++k) {
        if (k == i) continue;
        const int d = (i - k + m_) % m_;
        const double rx = xi - x(0, k), ry = yi - x(1, k);
        const double r2 = rx * rx + ry * ry;
        const double qx = density_(0, k), qy = density_(1, k);
        const double lw = 0.5 * kress_[d] + w * (0.5 * std::log(r2) - log_sin_[d]);
        const double rq = w * (rx * qx + ry * qy) / r2;
        ux += -lw * qx + rx * rq;
        uy += -lw * qy + ry * rq;
      }
      u(0, i) = shear_rate * yi + scale * ux;
      u(1, i) = scale * uy;
    }
  }

 private:
  int m_;
  std::vector<double> kress_, log_sin_, diff_, speed_;
  Eigen::Matrix2Xd derivative_, density_;
};

// Taylor deformation D_xy, inclination theta and area of the region enclosed by the trigonometric
// interpolant of the markers (same second-moment definition as diagnostics/shape_diagnostics.h,
// song2019 eq. (151); Green's theorem int x^2 dA = oint x^3/3 dy etc. by the trapezoidal rule in
// the material parameter, spectrally accurate even for non-uniform marker spacing).
struct SpectralShape {
  double dxy = 0.0, inclination = 0.0, area = 0.0;
};
inline SpectralShape MeasureSpectralShape(const StokesSingleLayer2D& layer,
                                          const Eigen::Matrix2Xd& x) {
  Eigen::Matrix2Xd dx;
  layer.Derivative(x, dx);
  const int m = static_cast<int>(x.cols());
  double area = 0, mx = 0, my = 0;
  for (int k = 0; k < m; ++k) {
    area += 0.5 * (x(0, k) * dx(1, k) - x(1, k) * dx(0, k));
    mx += 0.5 * x(0, k) * x(0, k) * dx(1, k);   // int x dA = oint x^2/2 dy
    my += -0.5 * x(1, k) * x(1, k) * dx(0, k);  // int y dA = -oint y^2/2 dx
  }
  const double cx = mx / area, cy = my / area;
  double ixx = 0, iyy = 0, ixy = 0;
  for (int k = 0; k < m; ++k) {
    const double X = x(0, k) - cx, Y = x(1, k) - cy;
    ixx += X * X * X / 3.0 * dx(1, k);
    iyy += -Y * Y * Y / 3.0 * dx(0, k);
    ixy += 0.5 * X * X * Y * dx(1, k);
  }
  const double w = 2.0 * std::acos(-1.0) / m;
  area *= w;
  ixx *= w;
  iyy *= w;
  ixy *= w;
  const double mean = 0.5 * (ixx + iyy), dev = std::hypot(0.5 * (ixx - iyy), ixy);
  const double l1 = std::sqrt(mean + dev), l2 = std::sqrt(std::max(mean - dev, 0.0));
  return {(l1 - l2) / (l1 + l2), 0.5 * std::atan2(2.0 * ixy, ixx - iyy), area};
}

// A capsule/drop whose markers move with the single-layer velocity of its own membrane force
// (the core MembraneModel, the same code the LBM-IB coupling calls), Heun time stepping.
// Units are the caller's; the bench uses mu = k = a = 1 (E_s = 1 / Ca).
class CapsuleBem {
 public:
  CapsuleBem(const MembraneParameters& membrane, const Eigen::Matrix2Xd& initial_markers,
             double viscosity, double shear_rate)
      : layer_(static_cast<int>(initial_markers.cols())),
        membrane_(membrane, ClosedCurve(initial_markers)),
        x_(initial_markers),
        mu_(viscosity),
        shear_rate_(shear_rate) {
    if (membrane.membrane_viscosity > 0.0) {
      throw std::invalid_argument(
          "CapsuleBem: membrane_viscosity must be 0 (Heun evaluates the force twice per step, "
          "which would advance the Kelvin-Voigt stretch history twice), got " +
          std::to_string(membrane.membrane_viscosity));
    }
    if (!(viscosity > 0.0)) {
      throw std::invalid_argument("CapsuleBem: viscosity must be > 0, got " +
                                  std::to_string(viscosity));
    }
    curve_.Update(x_);
  }

  // One Heun step: X* = X + dt u(X), X^{n+1} = X + dt (u(X) + u(X*)) / 2.
  void Step(double dt) {
    Evaluate(x_, u0_);
    predictor_ = x_ + dt * u0_;
    Evaluate(predictor_, u1_);
    x_ += (0.5 * dt) * (u0_ + u1_);
    curve_.Update(x_);
    time_ += dt;
  }

  // Velocity of the markers x (membrane force evaluated on x).
  void Evaluate(const Eigen::Matrix2Xd& x, Eigen::Matrix2Xd& u) {
    work_curve_.Update(x);
    membrane_.ComputeForce(work_curve_, 1.0, force_);
    layer_.Velocity(x, force_, mu_, shear_rate_, u);
  }

  const Eigen::Matrix2Xd& markers() const { return x_; }
  const ClosedCurve& curve() const { return curve_; }
  const MembraneModel& membrane() const { return membrane_; }
  const StokesSingleLayer2D& layer() const { return layer_; }
  double time() const { return time_; }

 private:
  StokesSingleLayer2D layer_;
  MembraneModel membrane_;
  Eigen::Matrix2Xd x_, predictor_, u0_, u1_, force_;
  ClosedCurve curve_, work_curve_;
  double mu_, shear_rate_;
  double time_ = 0.0;
};

}  // namespace ehd::bie
