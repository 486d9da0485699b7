#include "ehd_capsule/reference/interface_examples_3d.h"

#include <cmath>
#include <stdexcept>

namespace ehd {
namespace {

constexpr double kPi = 3.14159265358979323846;

// c: the point source of phi^+, inside the surface, away from it.
void SmoothPair(InterfaceExample3D& e, const Eigen::Vector3d& c) {
  e.phi_minus = [](const Eigen::Vector3d& p) {
    return std::exp(p.x()) * std::cos(p.y()) + p.z() * p.z();
  };
  e.grad_minus = [](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return {std::exp(p.x()) * std::cos(p.y()), -std::exp(p.x()) * std::sin(p.y()), 2 * p.z()};
  };
  e.phi_plus = [c](const Eigen::Vector3d& p) {
    return p.x() * p.y() + p.z() + 0.5 * (p.x() * p.x() - p.z() * p.z()) + 0.05 / (p - c).norm();
  };
  e.grad_plus = [c](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    const Eigen::Vector3d r = p - c;
    return Eigen::Vector3d(p.y() + p.x(), p.x(), 1.0 - p.z()) - 0.05 * r / std::pow(r.norm(), 3);
  };
  e.laplacian_minus = 2.0;
  e.laplacian_plus = 0.0;
}

}  // namespace

TriangleMesh InterfaceExample3D::MeshFor(double h) const {
  for (int level = 2; level <= 6; ++level) {
    TriangleMesh m = mesh(level);
    if (MeasureQuality(m).max_edge <= 1.5 * h || level == 6) return m;
  }
  return mesh(6);
}

InterfaceExample3D MakeInterfaceExample3D(const std::string& name, double sigma_minus,
                                          double sigma_plus) {
  if (!(sigma_minus > 0) || !(sigma_plus > 0)) {
    throw std::invalid_argument("3D interface example: sigma_minus and sigma_plus must be > 0");
  }
  InterfaceExample3D e;
  e.name = name;
  e.sigma_minus = sigma_minus;
  e.sigma_plus = sigma_plus;
  if (name == "sphere_field") {
    e.description = "sphere r = 1/2 in a uniform field along z (leaky-dielectric conduction)";
    const double radius = 0.5;
    const double a = 3 * sigma_plus / (sigma_minus + 2 * sigma_plus);
    const double b = (sigma_minus - sigma_plus) / (sigma_minus + 2 * sigma_plus);
    const double r3 = radius * radius * radius;
    e.phi_minus = [a](const Eigen::Vector3d& p) { return -a * p.z(); };
    e.grad_minus = [a](const Eigen::Vector3d&) -> Eigen::Vector3d { return {0, 0, -a}; };
    e.phi_plus = [b, r3](const Eigen::Vector3d& p) {
      return -p.z() + b * r3 * p.z() / std::pow(p.norm(), 3);
    };
    e.grad_plus = [b, r3](const Eigen::Vector3d& p) -> Eigen::Vector3d {
      const double r = p.norm();
      return Eigen::Vector3d(0, 0, -1) +
             b * r3 * (Eigen::Vector3d(0, 0, 1) / std::pow(r, 3) - 3 * p.z() * p / std::pow(r, 5));
    };
    e.normal = [](const Eigen::Vector3d& p) -> Eigen::Vector3d { return p.normalized(); };
    e.mesh = [radius](int level) { return IcosphereMesh(level, radius); };
    e.inside_volume = 4.0 / 3.0 * kPi * radius * radius * radius;
    e.boundaries.x_min = e.boundaries.x_max = BoundaryKind::kNeumann;
    e.boundaries.y_min = e.boundaries.y_max = BoundaryKind::kNeumann;
  } else if (name == "sphere") {
    e.description = "sphere r = 1/2, [phi], [sigma phi_n] and f non-zero (the ellipsoid's phi)";
    SmoothPair(e, Eigen::Vector3d(0.1, -0.05, 0.02));
    e.normal = [](const Eigen::Vector3d& p) -> Eigen::Vector3d { return p.normalized(); };
    e.mesh = [](int level) { return IcosphereMesh(level, 0.5); };
    e.inside_volume = 4.0 / 3.0 * kPi * 0.125;
  } else if (name == "ellipsoid") {
    e.description = "ellipsoid 0.6 x 0.45 x 0.35, [phi], [sigma phi_n] and f non-zero";
    SmoothPair(e, Eigen::Vector3d(0.1, -0.05, 0.02));
    const double ax = 0.6, ay = 0.45, az = 0.35;
    e.normal = [=](const Eigen::Vector3d& p) -> Eigen::Vector3d {
      return Eigen::Vector3d(p.x() / (ax * ax), p.y() / (ay * ay), p.z() / (az * az)).normalized();
    };
    e.mesh = [=](int level) { return EllipsoidMesh(level, ax, ay, az); };
    e.inside_volume = 4.0 / 3.0 * kPi * ax * ay * az;
  } else if (name == "biconcave") {
    e.description = "biconcave red-cell surface a = 0.45 (non-convex), the ellipsoid's phi";
    SmoothPair(e, Eigen::Vector3d(0.38, 0.0, 0.15));  // in the rim
    BiconcaveParameters shape;
    shape.radius = 0.45;
    // Implicit form Y^2 - (R^2/4) q(S) = 0, S = (X^2 + Z^2)/R^2, R = a alpha,
    // q = (c0 + c1 S + c2 S^2)^2 (1 - S); its gradient is the normal (outward with this sign).
    e.normal = [shape](const Eigen::Vector3d& p) -> Eigen::Vector3d {
      const double big_r = shape.radius * shape.alpha;
      const double s = std::min(1.0, (p.x() * p.x() + p.z() * p.z()) / (big_r * big_r));
      const double poly = shape.c0 + shape.c1 * s + shape.c2 * s * s;
      const double dq = 2 * poly * (shape.c1 + 2 * shape.c2 * s) * (1 - s) - poly * poly;
      return Eigen::Vector3d(-0.5 * dq * p.x(), 2 * p.y(), -0.5 * dq * p.z()).normalized();
    };
    e.mesh = [shape](int level) { return BiconcaveMesh(level, shape); };
    e.inside_volume = BiconcaveVolume(shape);
  } else {
    throw std::invalid_argument("unknown 3D interface example '" + name +
                                "' (sphere_field, sphere, ellipsoid, biconcave)");
  }
  return e;
}

InterfaceProblem3D SampleInterfaceProblem3D(const InterfaceExample3D& e, const Grid3D& grid,
                                            const TriangleMesh& mesh,
                                            const SurfaceClassification3D& sides) {
  InterfaceProblem3D p;
  p.sigma_minus = e.sigma_minus;
  p.sigma_plus = e.sigma_plus;
  if (e.laplacian_minus != 0 || e.laplacian_plus != 0) {
    p.f.resize(grid.size());
    for (std::size_t c = 0; c < grid.size(); ++c) {
      p.f[c] =
          sides.side[c] > 0 ? e.sigma_plus * e.laplacian_plus : e.sigma_minus * e.laplacian_minus;
    }
    p.f_over_sigma_jump.assign(mesh.vertex_count(), e.laplacian_plus - e.laplacian_minus);
    p.interior_source_integral = e.laplacian_minus * e.inside_volume;
  }
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const Eigen::Vector3d x = mesh.vertices().col(v), n = e.normal(x);
    p.w.push_back(e.phi_plus(x) - e.phi_minus(x));
    p.v.push_back(e.sigma_plus * e.grad_plus(x).dot(n) - e.sigma_minus * e.grad_minus(x).dot(n));
  }
  p.boundary = SampleBoundaryData(
      grid, e.boundaries,
      [&](double x, double y, double z) {
        return e.phi_plus({x, y, z});
      },
      [&](double x, double y, double z) {
        return e.grad_plus({x, y, z});
      });
  return p;
}

Eigen::Vector3d FreeSpaceSphereTraction(const Eigen::Vector3d& p, double radius, double e,
                                        double sigma_minus, double sigma_plus, double eps_minus,
                                        double eps_plus) {
  const double a = 3 * sigma_plus / (sigma_minus + 2 * sigma_plus);
  const double b = (sigma_minus - sigma_plus) / (sigma_minus + 2 * sigma_plus);
  const Eigen::Vector3d n = p.normalized();
  const double r = p.norm();
  const Eigen::Vector3d e_minus(0, 0, -a * e);
  const Eigen::Vector3d e_plus =
      -(Eigen::Vector3d(0, 0, e) -
        b * e * std::pow(radius, 3) *
            (Eigen::Vector3d(0, 0, 1) / std::pow(r, 3) - 3 * p.z() * p / std::pow(r, 5)));
  const double enm = e_minus.dot(n), enp = e_plus.dot(n);
  const Eigen::Vector3d etm = e_minus - enm * n, etp = e_plus - enp * n;
  return 0.5 *
             (eps_plus * (enp * enp - etp.squaredNorm()) -
              eps_minus * (enm * enm - etm.squaredNorm())) *
             n +
         eps_plus * enp * etp - eps_minus * enm * etm;
}

}  // namespace ehd
