// Helfrich bending force from the discrete mean and Gaussian curvatures; see helfrich_bending.h.
#include "ehd_capsule/membrane/helfrich_bending.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace ehd {

HelfrichBending::HelfrichBending(const HelfrichParameters& p) : params_(p) {
  if (!(p.bending_modulus >= 0.0) || !std::isfinite(p.bending_modulus)) {
    throw std::invalid_argument("HelfrichBending: bending modulus E_B = " +
                                std::to_string(p.bending_modulus) + " must be >= 0");
  }
  if (!std::isfinite(p.spontaneous_curvature)) {
    throw std::invalid_argument("HelfrichBending: spontaneous curvature c0 must be finite");
  }
}

double HelfrichBending::ComputeForces(const TriangleMesh& mesh, Eigen::Matrix3Xd& forces) const {
  const SurfaceGeometry g = MeasureSurface(mesh);
  const std::vector<double> laplace_h = LaplaceBeltrami(mesh, g.vertex_area, g.mean_curvature);
  const double eb = params_.bending_modulus, c0 = params_.spontaneous_curvature;
  const int n = mesh.vertex_count();
  forces.resize(3, n);
  double energy = 0.0;
  for (int v = 0; v < n; ++v) {
    const double h = g.mean_curvature[v], k = g.gaussian_curvature[v];
    const double density =
        eb * (2.0 * laplace_h[v] + (2.0 * h - c0) * (2.0 * h * h - 2.0 * k + c0 * h));
    forces.col(v) = density * g.vertex_area[v] * g.normal.col(v);
    energy += 0.5 * eb * g.vertex_area[v] * (2.0 * h - c0) * (2.0 * h - c0);
  }
  return energy;
}

double HelfrichBending::Energy(const TriangleMesh& mesh) const {
  const SurfaceGeometry g = MeasureSurface(mesh);
  double energy = 0.0;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    const double d = 2.0 * g.mean_curvature[v] - params_.spontaneous_curvature;
    energy += 0.5 * params_.bending_modulus * g.vertex_area[v] * d * d;
  }
  return energy;
}

std::string HelfrichBending::Describe() const {
  std::ostringstream o;
  o << "Helfrich bending E_B = " << params_.bending_modulus
    << ", c0 = " << params_.spontaneous_curvature;
  return o.str();
}

}  // namespace ehd
