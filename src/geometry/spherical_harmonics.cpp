#include "ehd_capsule/geometry/spherical_harmonics.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace ehd {

Eigen::MatrixXd RealSphericalHarmonics(const Eigen::Matrix3Xd& directions, int max_degree) {
  if (max_degree < 0) {
    throw std::invalid_argument(
        "RealSphericalHarmonics: max_degree = " + std::to_string(max_degree) + " < 0");
  }
  const long n = directions.cols();
  const int lmax = max_degree;
  Eigen::MatrixXd y(n, SphericalHarmonicCount(lmax));
  std::vector<double> p(lmax + 1);
  const double kPi = 3.14159265358979323846;
  for (long i = 0; i < n; ++i) {
    const double norm = directions.col(i).norm();
    if (!(norm > 0)) throw std::invalid_argument("RealSphericalHarmonics: a zero direction");
    const Eigen::Vector3d d = directions.col(i) / norm;
    const double ct = std::max(-1.0, std::min(1.0, d.z()));
    const double st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
    const double phi = std::atan2(d.y(), d.x());
    int col = 0;
    double pmm = std::sqrt(1.0 / (4.0 * kPi));  // fully normalised P_m^m, m = 0
    for (int m = 0; m <= lmax; ++m) {
      if (m > 0) pmm *= -std::sqrt((2.0 * m + 1.0) / (2.0 * m)) * st;
      // Fully normalised recurrence in l at fixed m (e.g. Holmes & Featherstone 2002).
      p[m] = pmm;
      if (m + 1 <= lmax) p[m + 1] = std::sqrt(2.0 * m + 3.0) * ct * pmm;
      for (int l = m + 2; l <= lmax; ++l) {
        const double a = std::sqrt((4.0 * l * l - 1.0) / (double(l) * l - double(m) * m));
        const double b = std::sqrt(((l - 1.0) * (l - 1.0) - double(m) * m) /
                                   (4.0 * (l - 1.0) * (l - 1.0) - 1.0));
        p[l] = a * (ct * p[l - 1] - b * p[l - 2]);
      }
      if (m == 0) {
        for (int l = 0; l <= lmax; ++l) y(i, col++) = p[l];
      } else {
        const double c = std::sqrt(2.0) * std::cos(m * phi), s = std::sqrt(2.0) * std::sin(m * phi);
        for (int l = m; l <= lmax; ++l) {
          y(i, col++) = c * p[l];
          y(i, col++) = s * p[l];
        }
      }
    }
  }
  return y;
}

namespace {

int IcosphereVertexCount(int level) { return 10 * (1 << (2 * level)) + 2; }

}  // namespace

int IcosphereLevel(const TriangleMesh& mesh) {
  const int nv = mesh.vertex_count();
  int level = -1;
  for (int k = 0; k <= 7; ++k) {
    if (IcosphereVertexCount(k) == nv) level = k;
  }
  if (level < 0 || mesh.triangle_count() != 20 * (1 << (2 * level))) return -1;
  const TriangleMesh reference = IcosphereMesh(level);
  return reference.triangles() == mesh.triangles() ? level : -1;
}

TriangleMesh IcosphereSubmesh(const TriangleMesh& mesh, int level) {
  const int full = IcosphereLevel(mesh);
  if (full < 0) {
    throw std::invalid_argument(
        "IcosphereSubmesh: the mesh is not of icosphere connectivity (not built by "
        "IcosphereMesh or a shape mapped from it)");
  }
  if (level < 0 || level > full) {
    throw std::invalid_argument("IcosphereSubmesh: level " + std::to_string(level) +
                                " outside [0, " + std::to_string(full) + "]");
  }
  TriangleMesh coarse = IcosphereMesh(level);
  return TriangleMesh(mesh.vertices().leftCols(IcosphereVertexCount(level)), coarse.triangles());
}

}  // namespace ehd
