// The leaky-dielectric layer, one for both dimensions (song2019 sec. 3.5 and 4.2; ch. 6 in 3D):
// the potential of a drop or capsule in a DC field, div(sigma grad phi) = 0 with sigma^- inside
// and sigma^+ outside, [phi] = 0, [sigma phi_n] = 0 (the quasi-static leaky-dielectric model, no
// charge relaxation term), solved by the fast IIM of the dimension (2D: fast_iim_solver.h on the
// markers of a closed curve; 3D: fast_iim_solver_3d.h on the vertices of a closed triangle mesh),
// and the Maxwell-stress traction [M_E] . n with eps^+-.
//
// Box sides (ElectricInterfaceOf<D>): E_inf = -E e_D along the last axis, phi = E y (2D) or
// phi = E z (3D) on the two faces across it (Dirichlet), zero normal derivative on the others
// (song2019 ch. 4 and ch. 6).
// Force: 2D, per unit length at each marker (= the traction, electric_field.h MaxwellForce);
// 3D, per vertex, the traction per unit area times the vertex's mixed Voronoi area
// (triangle_mesh.h), so that it spreads like the membrane's vertex forces.
//
// Jumps (issue #43 item 3; not in the reference): a caller may give [phi] = w and [sigma phi_n] = v
// at the points (SetInterfaceJumps), e.g. a capacitive membrane's transmembrane potential
// w = phi^+ - phi^- = -V_m (V_m = phi^- - phi^+, inside minus outside). The fast IIM takes them
// with the tangential derivatives of w in its corrections; the tangential field then jumps,
// E_tau^+ = E_tau^- - grad_s w, and the Maxwell traction uses each side's.
//
// Warm start, the same in both dimensions: G = [phi_n] of the previous solve is the next guess
// (when the point count is unchanged); a caller that passes the time of each solve gets the
// linear extrapolation of the last two solutions instead (Solve(shape, time)), and a new field
// strength rescales them (G is linear in E while f = w = v = 0 and the box data scale with E).
// With a jump set, G is not proportional to E: a new field strength keeps the warm start
// unscaled (a guess: the solve's tolerance does not depend on it).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "ehd_capsule/electric/fast_iim_solver.h"
#include "ehd_capsule/electric/fast_iim_solver_3d.h"
#include "ehd_capsule/electric/interface_problem.h"
#include "ehd_capsule/geometry/closed_curve.h"
#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

// The interface solver of each dimension and the types it takes.
template <int D>
struct ElectricInterfaceOf;

template <>
struct ElectricInterfaceOf<2> {
  using Shape = ClosedCurve;  // markers
  using Solver = FastIimSolver;
  using Options = FastIimOptions;
  using Problem = InterfaceProblem;
};

template <>
struct ElectricInterfaceOf<3> {
  using Shape = TriangleMesh;  // vertices
  using Solver = FastIimSolver3D;
  using Options = FastIim3DOptions;
  using Problem = InterfaceProblem3D;
};

template <int D>
class LeakyDielectricSolver {
 public:
  using Shape = typename ElectricInterfaceOf<D>::Shape;
  using Solver = typename ElectricInterfaceOf<D>::Solver;
  using Options = typename ElectricInterfaceOf<D>::Options;
  using Points = Eigen::Matrix<double, D, Eigen::Dynamic>;

  // sigma and eps must be > 0 (std::invalid_argument otherwise).
  LeakyDielectricSolver(const Grid<D>& grid, double sigma_minus, double sigma_plus,
                        double eps_minus, double eps_plus, const Options& options = Options());

  // E_inf = -e along the last axis. A change from e_old != 0 to e != 0 rescales the stored
  // solutions by e / e_old when no jump is set: a step in Ca_E keeps its warm start.
  void SetAppliedField(double e);
  double applied_field() const { return applied_field_; }

  // [phi] = w and [sigma phi_n] = v at the points of the shapes solved next (one value per
  // point; empty: zero). Solve throws std::invalid_argument when a size differs from the
  // point count.
  void SetInterfaceJumps(std::vector<double> w, std::vector<double> v = {});
  const std::vector<double>& potential_jump() const { return problem_.w; }
  const std::vector<double>& flux_jump() const { return problem_.v; }

  // Solves for the shape at `time` (any monotone clock, e.g. the step number). When the two
  // previous solves were timed too (t0 < t1 < time, same point count), GMRES starts from
  //   G_guess = G1 + r (G1 - G0),   r = min((time - t1) / (t1 - t0), kMaxExtrapolationRatio),
  // which is O(dt^2) from the new solution where G1 alone is O(dt): with points moving ~0.01 h
  // per solve it leaves GMRES 0-1 iterations instead of 2 (bench/electric_warm_start_bench).
  // Throws SolverError when the interface solver refuses or GMRES does not converge.
  const InterfaceSolveReport& Solve(const Shape& shape, double time);
  // The same from G1 alone (forgets the time history).
  const InterfaceSolveReport& Solve(const Shape& shape);
  static constexpr double kMaxExtrapolationRatio = 2.0;
  const InterfaceSolveReport& report() const { return report_; }

  const Points& force() const { return force_; }        // 2D: per unit length; 3D: per vertex
  const Points& traction() const { return traction_; }  // [M_E].n per unit length / area
  const std::vector<double>& potential() const { return phi_; }
  // Normal field E_n = -phi_n inside and outside at the points.
  const std::vector<double>& normal_field_minus() const { return en_minus_; }
  const std::vector<double>& normal_field_plus() const { return en_plus_; }
  // Free surface charge [eps E_n] at the points.
  std::vector<double> SurfaceCharge() const;
  // E = -grad phi on the grid for the last solve (component a in [a]), computed on demand.
  std::vector<std::vector<double>> GridField() const;

  // The warm start: G1 (the last solution), G0 and the times t0, t1 of the last two timed solves
  // (NaN: none). Exposed so that a checkpoint restarts bit for bit.
  struct WarmStart {
    std::vector<double> g, g_previous;
    double time_previous = std::numeric_limits<double>::quiet_NaN();
    double time_last = std::numeric_limits<double>::quiet_NaN();
  };
  const WarmStart& warm_start() const { return warm_; }
  void set_warm_start(const WarmStart& w) { warm_ = w; }

  const Solver& iim() const { return iim_; }
  const Grid<D>& grid() const { return iim_.grid(); }

 private:
  const InterfaceSolveReport& SolveFromGuess(const Shape& shape);

  Solver iim_;
  double eps_minus_, eps_plus_;
  double applied_field_ = 0.0;
  typename ElectricInterfaceOf<D>::Problem problem_;
  InterfaceSolveReport report_;
  WarmStart warm_;
  std::vector<double> phi_, en_minus_, en_plus_;
  Points traction_, force_;
};

extern template class LeakyDielectricSolver<2>;
extern template class LeakyDielectricSolver<3>;

}  // namespace ehd
