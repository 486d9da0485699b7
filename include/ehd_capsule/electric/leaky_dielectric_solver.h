// Electric potential, field and interfacial force of a leaky dielectric drop/capsule in a DC
// field (song2019 sec. 3.5 and 4.2): div(sigma grad phi) = 0 with sigma^- inside, sigma^+
// outside, [phi] = 0, [sigma phi_n] = 0 (no surface charge relaxation term: the quasi-static
// leaky dielectric model), solved by the fast IIM (fast_iim_solver.h). Box sides: phi = E y on
// y = y0 and y = y_max (Dirichlet; E_inf = (0, -E)), dphi/dx = 0 on the x sides (Neumann).
// The force is F_E = [M_E] . n per unit length at each marker (electric_field.h) with eps^+-.
// G = [phi_n] of the previous Solve warm-starts GMRES when the marker count is unchanged.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ehd_capsule/electric/fast_iim_solver.h"
#include "ehd_capsule/electric/interface_problem.h"
#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"

namespace ehd {

class LeakyDielectricSolver {
 public:
  // sigma and eps must be > 0 (std::invalid_argument otherwise).
  LeakyDielectricSolver(const Grid2D& grid, double sigma_minus, double sigma_plus, double eps_minus,
                        double eps_plus, const GmresOptions& gmres = GmresOptions());

  // E_inf = (0, -E): phi = E y on the y sides.
  void SetAppliedField(double e);
  double applied_field() const { return applied_field_; }

  // Solves for the curve; throws SolverError if GMRES does not converge.
  const InterfaceSolveReport& Solve(const ClosedCurve& curve);
  const InterfaceSolveReport& report() const { return report_; }

  const Eigen::Matrix2Xd& force() const { return force_; }  // per unit length, per marker
  const std::vector<double>& potential() const { return phi_; }
  const std::vector<double>& field_x() const { return ex_; }
  const std::vector<double>& field_y() const { return ey_; }
  // Normal field inside/outside and tangential field at the markers (E = -grad phi).
  const std::vector<double>& normal_field_minus() const { return en_minus_; }
  const std::vector<double>& normal_field_plus() const { return en_plus_; }
  const std::vector<double>& tangential_field() const { return et_; }
  // Free surface charge [eps E_n] at the markers.
  std::vector<double> SurfaceCharge() const;

  const std::vector<double>& jump_normal_derivative() const { return g_; }
  void set_jump_normal_derivative(const std::vector<double>& g) { g_ = g; }

  // Fast IIM options (fit radius, control spacing, warm-start mode; see fast_iim_solver.h).
  void SetIimOptions(const FastIimOptions& options) { iim_.set_options(options); }

  const Grid2D& grid() const { return iim_.grid(); }
  const FastIimSolver& iim() const { return iim_; }

 private:
  FastIimSolver iim_;
  double eps_minus_, eps_plus_;
  double applied_field_ = 0.0;
  InterfaceProblem problem_;
  InterfaceSolveReport report_;
  std::vector<double> g_, phi_, ex_, ey_, en_minus_, en_plus_, et_, et_plus_;
  Eigen::Matrix2Xd force_;
};

}  // namespace ehd
