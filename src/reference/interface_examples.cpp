// Manufactured interface problems (song2019 sec. 2.3.5 and 2.5, plus an ellipse and a star);
// see interface_examples.h for each exact solution and where the text's f or jump was corrected.
#include "ehd_capsule/reference/interface_examples.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

namespace ehd {
namespace {

using Vec = Eigen::Vector2d;

// r = 0.5 + amplitude sin(5 t) about (0.02, 0.01): the "star" examples.
std::function<Vec(double)> FivePetalStar(double amplitude) {
  return [amplitude](double t) {
    const double r = 0.5 + amplitude * std::sin(5 * t);
    return Vec(0.02 + r * std::cos(t), 0.01 + r * std::sin(t));
  };
}

std::function<Vec(double)> Circle(Vec centre, double radius) {
  return [=](double t) { return Vec(centre + radius * Vec(std::cos(t), std::sin(t))); };
}

void SetZeroOutside(InterfaceExample& e) {
  e.phi_plus = [](const Vec&) { return 0.0; };
  e.grad_plus = [](const Vec&) { return Vec(0, 0); };
  e.laplace_plus = [](const Vec&) { return 0.0; };
}

// phi^- = sin(2x) cos(3y) + 1, phi^+ = x y + exp((x - y)/2): smooth, non-polynomial, non-zero
// source on both sides, and a jump that varies along the curve.
void SetSmoothPair(InterfaceExample& e) {
  e.phi_minus = [](const Vec& p) { return std::sin(2 * p.x()) * std::cos(3 * p.y()) + 1.0; };
  e.grad_minus = [](const Vec& p) {
    return Vec(2 * std::cos(2 * p.x()) * std::cos(3 * p.y()),
               -3 * std::sin(2 * p.x()) * std::sin(3 * p.y()));
  };
  e.laplace_minus = [](const Vec& p) { return -13.0 * std::sin(2 * p.x()) * std::cos(3 * p.y()); };
  e.phi_plus = [](const Vec& p) { return p.x() * p.y() + std::exp(0.5 * (p.x() - p.y())); };
  e.grad_plus = [](const Vec& p) {
    const double ex = 0.5 * std::exp(0.5 * (p.x() - p.y()));
    return Vec(p.y() + ex, p.x() - ex);
  };
  e.laplace_plus = [](const Vec& p) { return 0.5 * std::exp(0.5 * (p.x() - p.y())); };
}

// Example 3's phi depends on the sigmas.
void BindExample3(InterfaceExample& e) {
  const double sm = e.sigma_minus, sp = e.sigma_plus, r0 = 0.5;
  const double c = r0 * r0 / sm - r0 * r0 * r0 * r0 / sp;
  e.phi_minus = [sm](const Vec& p) { return p.squaredNorm() / sm; };
  e.grad_minus = [sm](const Vec& p) { return Vec(2.0 * p / sm); };
  e.laplace_minus = [sm](const Vec&) { return 4.0 / sm; };
  e.phi_plus = [sp, c](const Vec& p) {
    const double r2 = p.squaredNorm();
    return (r2 * r2 - 0.1 * std::log(2.0 * std::sqrt(r2))) / sp + c;
  };
  e.grad_plus = [sp](const Vec& p) {
    const double r2 = p.squaredNorm();
    return Vec((4.0 * r2 - 0.1 / r2) * p / sp);
  };
  e.laplace_plus = [sp](const Vec& p) { return 16.0 * p.squaredNorm() / sp; };
}

bool IsExample3(const std::string& name) { return name == "3" || name == "3a" || name == "3b"; }

}  // namespace

std::vector<std::string> InterfaceExampleNames() {
  return {"1",    "2",       "3",    "3a",         "3b",         "4",        "cfm1",
          "cfm2", "ellipse", "star", "star_tight", "star_sharp", "biconcave"};
}

InterfaceExample MakeInterfaceExample(const std::string& name) {
  InterfaceExample e;
  e.name = name;
  if (name == "1" || name == "cfm1") {
    e.description = "circle r=1/2, phi-=1, phi+=1+log(2r) (sec. 2.5 ex. 1 / sec. 2.3.5 ex. 1)";
    e.curve = Circle(Vec(0, 0), 0.5);
    e.phi_minus = [](const Vec&) { return 1.0; };
    e.grad_minus = [](const Vec&) { return Vec(0, 0); };
    e.laplace_minus = [](const Vec&) { return 0.0; };
    e.phi_plus = [](const Vec& p) { return 1.0 + std::log(2.0 * p.norm()); };
    e.grad_plus = [](const Vec& p) { return Vec(p / p.squaredNorm()); };
    e.laplace_plus = [](const Vec&) { return 0.0; };
  } else if (name == "2") {
    e.description = "circle (1/2,1/2) r=1/4, phi-=exp(-r^2), phi+=0 (sec. 2.5 ex. 2)";
    e.sigma_minus = 1.0;
    e.sigma_plus = 2.0;
    e.curve = Circle(Vec(0.5, 0.5), 0.25);
    e.phi_minus = [](const Vec& p) { return std::exp(-p.squaredNorm()); };
    e.grad_minus = [](const Vec& p) { return Vec(-2.0 * p * std::exp(-p.squaredNorm())); };
    e.laplace_minus = [](const Vec& p) {
      return (4.0 * p.squaredNorm() - 4.0) * std::exp(-p.squaredNorm());
    };
    SetZeroOutside(e);
  } else if (IsExample3(name)) {
    e.description = "circle r=1/2, phi-=r^2/s-, phi+=(r^4-0.1log(2r))/s+ + c (sec. 2.5 ex. 3)";
    e.sigma_minus = 1.0;
    e.sigma_plus = (name == "3b") ? 100.0 : 10.0;
    e.curve = Circle(Vec(0, 0), 0.5);
    BindExample3(e);
  } else if (name == "4") {
    e.description = "circle r=1/2, phi-=e^x cos y, phi+=0 (sec. 2.5 ex. 4)";
    e.curve = Circle(Vec(0, 0), 0.5);
    e.phi_minus = [](const Vec& p) { return std::exp(p.x()) * std::cos(p.y()); };
    e.grad_minus = [](const Vec& p) {
      return Vec(std::exp(p.x()) * std::cos(p.y()), -std::exp(p.x()) * std::sin(p.y()));
    };
    e.laplace_minus = [](const Vec&) { return 0.0; };
    SetZeroOutside(e);
  } else if (name == "cfm2") {
    e.description = "circle r=1/2, phi-=x^2-y^2, phi+=0 (sec. 2.3.5 ex. 2)";
    e.curve = Circle(Vec(0, 0), 0.5);
    e.phi_minus = [](const Vec& p) { return p.x() * p.x() - p.y() * p.y(); };
    e.grad_minus = [](const Vec& p) { return Vec(2 * p.x(), -2 * p.y()); };
    e.laplace_minus = [](const Vec&) { return 0.0; };
    SetZeroOutside(e);
  } else if (name == "ellipse") {
    e.description = "ellipse 0.6x0.35 rotated 0.3 rad at (0.05,-0.03), smooth phi+- (ours)";
    e.curve = [](double t) {
      const double c = std::cos(0.3), s = std::sin(0.3);
      const Vec q(0.6 * std::cos(t), 0.35 * std::sin(t));
      return Vec(0.05 + c * q.x() - s * q.y(), -0.03 + s * q.x() + c * q.y());
    };
    SetSmoothPair(e);
  } else if (name == "star") {
    e.description = "five-petal star r=0.5+0.1 sin(5t) at (0.02,0.01), smooth phi+- (ours)";
    e.curve = FivePetalStar(0.1);
    SetSmoothPair(e);
  } else if (name == "star_tight") {
    e.description =
        "five-petal star r=0.5+0.18 sin(5t) at (0.02,0.01), troughs of curvature radius 0.0245 "
        "(h at N = 82), smooth phi+- (ours)";
    e.curve = FivePetalStar(0.18);
    SetSmoothPair(e);
  } else if (name == "star_sharp") {
    e.description =
        "five-petal star r=0.5+0.2 sin(5t) at (0.02,0.01), petal amplitude 0.4 of the mean radius, "
        "troughs of curvature radius 0.0191 (2 h at N = 209), smooth phi+- (ours)";
    e.curve = FivePetalStar(0.2);
    SetSmoothPair(e);
  } else if (name == "biconcave") {
    e.description = "biconcave (Evans-Fung profile, R=0.7, dimple 0.1 thick) at (0.02,0.01) (ours)";
    e.curve = [](double t) {
      const double radius = 0.7, c = std::cos(t);
      return Vec(0.02 + radius * c, 0.01 + 0.5 * radius * std::sin(t) *
                                               (0.207 + 2.003 * c * c - 1.123 * c * c * c * c));
    };
    SetSmoothPair(e);
  } else {
    std::string known;
    for (const auto& n : InterfaceExampleNames()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("interface example '" + name + "' is unknown; known: " + known);
  }
  return e;
}

InterfaceExample MakeInterfaceExample(const std::string& name, double sigma_minus,
                                      double sigma_plus) {
  if (!(sigma_minus > 0.0) || !(sigma_plus > 0.0)) {
    throw std::invalid_argument("interface example: sigma_minus and sigma_plus must be > 0, got " +
                                std::to_string(sigma_minus) + " and " + std::to_string(sigma_plus));
  }
  InterfaceExample e = MakeInterfaceExample(name);
  e.sigma_minus = sigma_minus;
  e.sigma_plus = sigma_plus;
  if (IsExample3(name)) BindExample3(e);
  return e;
}

Eigen::Matrix2Xd InterfaceExample::Markers(int count) const {
  if (count < 8) {
    throw std::invalid_argument("InterfaceExample::Markers: count must be >= 8, got " +
                                std::to_string(count));
  }
  Eigen::Matrix2Xd m(2, count);
  for (int k = 0; k < count; ++k) m.col(k) = curve(2.0 * M_PI * k / count);
  return m;
}

int InterfaceExample::DefaultMarkers(int n) const {
  double perimeter = 0.0;
  const int samples = 2000;
  for (int k = 0; k < samples; ++k) {
    perimeter += (curve(2.0 * M_PI * (k + 1) / samples) - curve(2.0 * M_PI * k / samples)).norm();
  }
  // Marker spacing ~2h: every mode of G on the markers is then resolved by the grid, which
  // keeps the Schur system well conditioned for sigma^- > sigma^+ (see fast_iim_solver.h).
  const double h = (box_max - box_min) / n;
  return std::max(16, static_cast<int>(std::lround(perimeter / (2.0 * h))));
}

Grid2D InterfaceExample::MakeGrid(int n) const {
  return Grid2D{n, n, (box_max - box_min) / n, box_min, box_min};
}

InterfaceProblem SampleInterfaceProblem(const InterfaceExample& e, const Grid2D& grid,
                                        const ClosedCurve& curve, const PoissonBoundaries& bc) {
  InterfaceProblem p;
  p.sigma_minus = e.sigma_minus;
  p.sigma_plus = e.sigma_plus;
  p.f.resize(grid.size());
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const Vec x(grid.x(i), grid.y(j));
      p.f[grid.index(i, j)] =
          curve.Contains(x) ? e.sigma_minus * e.laplace_minus(x) : e.sigma_plus * e.laplace_plus(x);
    }
  }
  const int m = curve.size();
  p.w.resize(m);
  p.v.resize(m);
  for (int k = 0; k < m; ++k) {
    const CurvePoint c = curve.AtMarker(k);
    const Vec& x = c.position;
    p.w[k] = e.phi_plus(x) - e.phi_minus(x);
    p.v[k] =
        e.sigma_plus * e.grad_plus(x).dot(c.normal) - e.sigma_minus * e.grad_minus(x).dot(c.normal);
  }
  auto value = [&](double x, double y) {
    const Vec q(x, y);
    return curve.Contains(q) ? e.phi_minus(q) : e.phi_plus(q);
  };
  auto gradient = [&](double x, double y) {
    const Vec q(x, y);
    return curve.Contains(q) ? e.grad_minus(q) : e.grad_plus(q);
  };
  p.boundary = SampleBoundaryData(grid, bc, value, gradient);
  return p;
}

std::vector<double> ExactSolution(const InterfaceExample& e, const Grid2D& grid,
                                  const ClosedCurve& curve) {
  std::vector<double> u(grid.size());
  for (int j = 0; j < grid.ny; ++j) {
    for (int i = 0; i < grid.nx; ++i) {
      const Vec x(grid.x(i), grid.y(j));
      u[grid.index(i, j)] = curve.Contains(x) ? e.phi_minus(x) : e.phi_plus(x);
    }
  }
  return u;
}

double JumpNormalDerivativeError(const InterfaceExample& example, const ClosedCurve& curve,
                                 const std::vector<double>& g) {
  double scale = 0.0, error = 0.0;
  for (int k = 0; k < curve.size(); ++k) {
    const Eigen::Vector2d x = curve.markers().col(k), n = curve.AtMarker(k).normal;
    const double minus = example.grad_minus(x).dot(n), plus = example.grad_plus(x).dot(n);
    scale = std::max({scale, std::abs(plus - minus), std::abs(minus), std::abs(plus)});
    error = std::max(error, std::abs(g[k] - (plus - minus)));
  }
  return scale > 0 ? error / scale : error;
}

}  // namespace ehd
