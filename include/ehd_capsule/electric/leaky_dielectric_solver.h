// Electric potential, field and interfacial force of a leaky dielectric drop/capsule in a DC
// field (song2019 sec. 3.5 and 4.2): div(sigma grad phi) = 0 with sigma^- inside, sigma^+
// outside, [phi] = 0, [sigma phi_n] = 0 (no surface charge relaxation term: the quasi-static
// leaky dielectric model), solved by the fast IIM (fast_iim_solver.h). Box sides: phi = E y on
// y = y0 and y = y_max (Dirichlet; E_inf = (0, -E)), dphi/dx = 0 on the x sides (Neumann).
// The force is F_E = [M_E] . n per unit length at each marker (electric_field.h) with eps^+-.
// G = [phi_n] of the previous Solve warm-starts GMRES when the marker count is unchanged; a
// time-stepping caller that passes the time of each solve gets the linear extrapolation of the
// last two solutions instead (Solve(curve, time)), and a new field strength rescales them.
#pragma once

#include <Eigen/Core>
#include <limits>
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

  // E_inf = (0, -E): phi = E y on the y sides. G is linear in E (f = w = v = 0 and the box data
  // scale with E), so a change from E_old != 0 to E != 0 rescales the stored G (and G0) by E/E_old:
  // a step in Ca_E keeps its warm start.
  void SetAppliedField(double e);
  double applied_field() const { return applied_field_; }

  // Solves for the curve, GMRES starting from the last G; throws SolverError if GMRES does not
  // converge. Forgets the time history used by Solve(curve, time).
  const InterfaceSolveReport& Solve(const ClosedCurve& curve);
  // The same for a solve at `time` (any monotone clock, e.g. the step number). When the two
  // previous solves were timed too (t0 < t1 < time, same marker count), GMRES starts from
  //   G_guess = G1 + r (G1 - G0),   r = min((time - t1) / (t1 - t0), kMaxExtrapolationRatio),
  // which is O(dt^2) from the new solution where G1 alone is O(dt): with markers moving ~0.01 h
  // per solve it leaves GMRES 0-1 iterations instead of 2 (bench/electric_warm_start_bench).
  const InterfaceSolveReport& Solve(const ClosedCurve& curve, double time);
  static constexpr double kMaxExtrapolationRatio = 2.0;
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

  // G = [phi_n] of the last solve (the next warm start). Setting it forgets the time history.
  const std::vector<double>& jump_normal_derivative() const { return g_; }
  void set_jump_normal_derivative(const std::vector<double>& g);

  // What Solve(curve, time) extrapolates from besides G1 = jump_normal_derivative(): G0 and the
  // times t0, t1 (NaN: none). Exposed so that a checkpoint restarts bit for bit.
  struct WarmStartHistory {
    std::vector<double> g_previous;
    double time_previous = std::numeric_limits<double>::quiet_NaN();
    double time_last = std::numeric_limits<double>::quiet_NaN();
  };
  const WarmStartHistory& warm_start_history() const { return history_; }
  void set_warm_start_history(const WarmStartHistory& history) { history_ = history; }

  // Fast IIM options (fit radius, control spacing, warm-start mode; see fast_iim_solver.h).
  void SetIimOptions(const FastIimOptions& options) { iim_.set_options(options); }

  const Grid2D& grid() const { return iim_.grid(); }
  const FastIimSolver& iim() const { return iim_; }

 private:
  const InterfaceSolveReport& SolveFromGuess(const ClosedCurve& curve);

  FastIimSolver iim_;
  double eps_minus_, eps_plus_;
  double applied_field_ = 0.0;
  InterfaceProblem problem_;
  InterfaceSolveReport report_;
  WarmStartHistory history_;
  std::vector<double> g_, phi_, ex_, ey_, en_minus_, en_plus_, et_, et_plus_;
  Eigen::Matrix2Xd force_;
};

}  // namespace ehd
