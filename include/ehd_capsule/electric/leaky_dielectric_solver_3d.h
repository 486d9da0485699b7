// Electric potential and interfacial force of a leaky-dielectric capsule or drop in a DC field in
// 3D (song2019 ch. 6 and sec. 3.5 in 3D): div(sigma grad phi) = 0 with sigma^- inside, sigma^+
// outside, [phi] = 0, [sigma phi_n] = 0 (the quasi-static leaky-dielectric model, as in 2D), by
// the 3D fast IIM (fast_iim_solver_3d.h). Box faces as in song2019 ch. 6: phi = E z on z = z0 and
// z = z_max (Dirichlet; E_inf = (0, 0, -E)), zero normal derivative on the x and y faces. The
// force per vertex is the Maxwell traction jump [M_E] . n times the vertex's mixed Voronoi area
// (triangle_mesh.h), so that it spreads like the membrane's vertex forces.
// G = [phi_n] of the previous solves warm-starts GMRES (linear extrapolation of the last two in
// time, as the 2D LeakyDielectricSolver), and a new field strength rescales them.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "ehd_capsule/electric/fast_iim_solver_3d.h"

namespace ehd {

class LeakyDielectricSolver3D {
 public:
  // sigma and eps must be > 0 (std::invalid_argument otherwise).
  LeakyDielectricSolver3D(const Grid3D& grid, double sigma_minus, double sigma_plus,
                          double eps_minus, double eps_plus,
                          const FastIim3DOptions& options = FastIim3DOptions());

  void SetAppliedField(double e);  // E_inf = (0, 0, -e)
  double applied_field() const { return applied_field_; }

  // Solves for the surface at `time` (any monotone clock, e.g. the step number); GMRES starts
  // from the extrapolation of the last two solutions of the same vertex count. Throws
  // SolverError when the 3D IIM refuses or GMRES does not converge.
  const InterfaceSolveReport& Solve(const TriangleMesh& surface, double time);
  static constexpr double kMaxExtrapolationRatio = 2.0;
  const InterfaceSolveReport& report() const { return report_; }

  const Eigen::Matrix3Xd& traction() const { return traction_; }  // [M_E].n per unit area
  const Eigen::Matrix3Xd& force() const { return force_; }        // per vertex
  const std::vector<double>& potential() const { return phi_; }
  // Free surface charge [eps E_n] at the vertices.
  std::vector<double> SurfaceCharge() const;

  // Warm-start state (exposed so that a checkpoint restarts bit for bit).
  struct WarmStart {
    std::vector<double> g, g_previous;
    double time_previous = std::numeric_limits<double>::quiet_NaN();
    double time_last = std::numeric_limits<double>::quiet_NaN();
  };
  const WarmStart& warm_start() const { return warm_; }
  void set_warm_start(const WarmStart& w) { warm_ = w; }

  const FastIimSolver3D& iim() const { return iim_; }
  const Grid3D& grid() const { return iim_.grid(); }

 private:
  FastIimSolver3D iim_;
  double eps_minus_, eps_plus_;
  double applied_field_ = 0.0;
  InterfaceProblem3D problem_;
  InterfaceSolveReport report_;
  WarmStart warm_;
  std::vector<double> phi_, en_minus_, en_plus_;
  Eigen::Matrix3Xd traction_, force_;
};

}  // namespace ehd
