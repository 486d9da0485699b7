// Stage 1 of the coupled step: the electric potential by the fast IIM (warm-started) and the
// interfacial force F_E = [M_E] . n at the markers (song2019 eq. (148)).
//
// Departure from the text: the potential may be re-solved less often than every step
// (numerics.electric_every, numerics.electric_move_tolerance), reusing F_E at the (material)
// markers in between.
#include <algorithm>
#include <sstream>

#include "ehd_capsule/coupling/capsule_stages_2d.h"
#include "ehd_capsule/electric/leaky_dielectric_solver.h"

namespace ehd {
ElectricStage2D::ElectricStage2D(const Scene& scene, const LatticeUnits& units, const Grid2D& grid,
                                 MembraneMarkers2D& body)
    : scene_(scene), body_(body) {
  solver_ = std::make_unique<LeakyDielectricSolver>(grid, units.sigma_minus, units.sigma_plus,
                                                    units.eps_minus, units.eps_plus);
}

ElectricStage2D::~ElectricStage2D() = default;

std::string ElectricStage2D::Describe() const {
  std::ostringstream out;
  out << "fast IIM leaky dielectric, sigma-/sigma+ = " << scene_.sigma_r
      << ", eps-/eps+ = " << scene_.eps_r << ", E_inf = (0, -" << body_.field << "), solved every "
      << scene_.numerics.electric_every << " step(s)";
  if (scene_.numerics.electric_move_tolerance > 0) {
    out << " or after a move > " << scene_.numerics.electric_move_tolerance << " h";
  }
  out << ", F_E = [M_E].n";
  return out.str();
}

void ElectricStage2D::Reset() {
  const int markers = static_cast<int>(body_.X.cols());
  body_.electric_density.setZero(2, markers);
  solver_->set_jump_normal_derivative(std::vector<double>(markers, 0.0));
  last_solve_step_ = -1;
  solved_field_ = -1.0;
}

const std::vector<double>& ElectricStage2D::potential() const { return solver_->potential(); }

void ElectricStage2D::Run(long step) {
  SimulationState& state = *body_.state;
  state.gmres_iterations = 0;
  const int markers = static_cast<int>(body_.X.cols());
  if (!(body_.field > 0.0)) {
    body_.electric_density.setZero(2, markers);
    solved_field_ = 0.0;
    return;
  }
  bool solve = last_solve_step_ < 0 || solved_field_ != body_.field ||
               step - last_solve_step_ >= scene_.numerics.electric_every;
  if (!solve && scene_.numerics.electric_move_tolerance > 0.0) {
    // Largest marker displacement since the last solve (no temporary: this runs every step).
    double moved2 = 0.0;
    for (int k = 0; k < markers; ++k) {
      moved2 = std::max(moved2, (body_.X.col(k) - markers_at_last_solve_.col(k)).squaredNorm());
    }
    const double tol = scene_.numerics.electric_move_tolerance;
    solve = moved2 > tol * tol;
  }
  if (!solve) return;
  solver_->SetAppliedField(body_.field);
  InterfaceSolveReport report;
  try {
    report = solver_->Solve(body_.curve, static_cast<double>(step));
  } catch (const std::exception& e) {
    FailStep(step, std::string("electric potential solve failed: ") + e.what());
  }
  state.gmres_iterations = report.iterations;
  state.gmres_residual = report.residual;
  if (!report.converged) {
    FailStep(step, "GMRES did not converge (residual " + FormatValue(report.residual) + " after " +
                       std::to_string(report.iterations) + " iterations)");
  }
  body_.electric_density = solver_->force();
  markers_at_last_solve_ = body_.X;
  last_solve_step_ = step;
  solved_field_ = body_.field;
}

void ElectricStage2D::Respaced(const std::function<void(std::vector<double>&)>& resample) {
  std::vector<double> g = solver_->jump_normal_derivative();
  if (static_cast<long>(g.size()) == body_.X.cols()) {
    resample(g);
    solver_->set_jump_normal_derivative(g);
  }
  last_solve_step_ = -1;  // F_E at the old markers no longer applies
}

void ElectricStage2D::Save(CheckpointWriter& w) const {
  const LeakyDielectricSolver::WarmStartHistory& h = solver_->warm_start_history();
  w.Pod(solver_->applied_field());
  w.Vec(solver_->jump_normal_derivative());
  w.Vec(h.g_previous);
  w.Pod(h.time_previous);
  w.Pod(h.time_last);
  w.Mat(body_.electric_density);
  w.Mat(markers_at_last_solve_);
  w.Pod(last_solve_step_);
  w.Pod(solved_field_);
}

void ElectricStage2D::Restore(CheckpointReader& r) {
  solver_->SetAppliedField(r.Pod<double>());
  solver_->set_jump_normal_derivative(r.Vec());
  LeakyDielectricSolver::WarmStartHistory h;
  h.g_previous = r.Vec();
  h.time_previous = r.Pod<double>();
  h.time_last = r.Pod<double>();
  solver_->set_warm_start_history(h);
  body_.electric_density = r.Mat<2>();
  markers_at_last_solve_ = r.Mat<2>();
  last_solve_step_ = r.Pod<long>();
  solved_field_ = r.Pod<double>();
}

}  // namespace ehd
