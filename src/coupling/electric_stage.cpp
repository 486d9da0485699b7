// The electric stage (coupling/stages/electric_stage.h).
#include "ehd_capsule/coupling/stages/electric_stage.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ehd_capsule/coupling/field_waveform.h"
#include "ehd_capsule/electric/leaky_dielectric_solver.h"

namespace ehd {

template <int D>
ElectricStage<D>::ElectricStage(const Scene& scene, const LatticeUnits& units, const Grid<D>& grid,
                                StepData<D>& data)
    : scene_(scene),
      data_(data),
      body_(data.bodies.front()),
      source_(data.bodies.front().AddForceSource("electric")) {
  if (data.bodies.size() != 1) {
    throw SceneError("scene " + scene.name + ": the electric field takes one body (" +
                     std::to_string(data.bodies.size()) + " in the scene)");
  }
  const std::string unresolved =
      WaveformResolutionProblem(scene.electric, scene.has_shear() ? units.shear_rate : units.dt);
  if (!unresolved.empty()) throw SceneError("scene " + scene.name + ": " + unresolved);
  typename DimensionTraits<D>::Electric::Options options;
  // electric.max_fit_disagreement, when given (absent: the solver's default).
  const auto limit = scene.values.find("electric.max_fit_disagreement");
  if (limit != scene.values.end()) options.max_fit_disagreement = limit->second.number;
  solver_ = std::make_unique<typename DimensionTraits<D>::Electric>(
      grid, units.sigma_minus, units.sigma_plus, units.eps_minus, units.eps_plus, options);
  if constexpr (D == 2) {
    data.on_points_resampled.push_back(
        [this](int, const typename StepData<D>::Resample& resample) { Resampled(resample); });
  }
}

template <int D>
ElectricStage<D>::~ElectricStage() = default;

template <int D>
std::string ElectricStage<D>::Describe() const {
  std::ostringstream out;
  const double field = data_.controls.field;
  if constexpr (D == 2) {
    out << "fast IIM leaky dielectric, sigma-/sigma+ = " << scene_.sigma_r
        << ", eps-/eps+ = " << scene_.eps_r << ", E_inf = (0, -" << field << "), solved every "
        << scene_.numerics.electric_every << " step(s)";
  } else {
    out << "3D fast IIM leaky dielectric, sigma-/sigma+ = " << scene_.sigma_r
        << ", eps-/eps+ = " << scene_.eps_r << ", E_inf = (0, 0, -" << field
        << ") (phi = E z on the z faces, Neumann x, y: song2019 ch. 6), solved every "
        << scene_.numerics.electric_every << " step(s)";
  }
  if (scene_.numerics.electric_move_tolerance > 0) {
    out << " or after a move > " << scene_.numerics.electric_move_tolerance << " h";
    if (D == 3 && scene_.numerics.electric_shape_tolerance > 0) {
      out << " that takes the surface more than " << scene_.numerics.electric_shape_tolerance
          << " h off the solved one (smaller moves re-interpolate the solved traction)";
    }
  }
  out << (D == 2 ? ", F_E = [M_E].n" : ", force [M_E].n A_i per vertex");
  const SceneElectric& e = scene_.electric;
  if (e.waveform == FieldWaveform::kAc) {
    out << "; AC field E (" << e.offset << " + cos(2 pi " << e.frequency << " t + " << e.phase
        << ")), between solves the force follows E(t)^2";
  } else if (e.waveform == FieldWaveform::kPulses) {
    out << "; pulsed field: on for " << e.pulse_width << " of every " << e.pulse_period << ", "
        << (e.pulse_count > 0 ? std::to_string(e.pulse_count) + " pulses" : "without end");
  }
  return out.str();
}

template <int D>
void ElectricStage<D>::Reset() {
  const int n = body_.size();
  source_.load.setZero(D, n);
  source_.traction.setZero(D, n);
  solver_->set_warm_start(typename LeakyDielectricSolver<D>::WarmStart());
  if constexpr (D == 3) {
    solved_positions_.resize(3, 0);
    solved_traction_.resize(3, 0);
    projector_.reset();
  }
  last_solve_step_ = -1;
  solved_field_ = -1.0;
  base_load_.resize(D, 0);
  base_traction_.resize(D, 0);
  base_field_ = 0.0;
}

template <int D>
void ElectricStage<D>::KeepBase(double field) {
  base_load_ = source_.load;
  base_traction_ = source_.traction;
  base_field_ = field;
}

template <int D>
void ElectricStage<D>::ScaleBase(double field) {
  const double r = field / base_field_;
  source_.load = base_load_ * (r * r);
  source_.traction = base_traction_ * (r * r);
}

template <int D>
const std::vector<double>& ElectricStage<D>::potential() const {
  return solver_->potential();
}

template <int D>
bool ElectricStage<D>::ReinterpolateTraction(double tolerance) {
  if constexpr (D == 3) {
    const TriangleMesh& mesh = body_.shape.mesh;
    if (!projector_) {
      TriangleMesh solved = mesh;
      solved.SetVertices(solved_positions_);
      projector_ = std::make_unique<SurfaceProjector>(solved, 1.0);
    }
    const Eigen::Matrix3Xd& x = mesh.vertices();
    // The feet first, stopping at the first vertex off the solved surface: a shape still
    // changing fails at once and costs little beyond the solve it triggers.
    feet_.resize(x.cols());
    for (int v = 0; v < x.cols(); ++v) {
      feet_[v] = projector_->Closest(x.col(v));
      if (feet_[v].distance > tolerance) return false;
    }
    const auto& triangles = mesh.triangles();
    const SurfaceGeometry geometry = MeasureSurface(mesh);
    for (int v = 0; v < x.cols(); ++v) {
      const SurfacePoint& foot = feet_[v];
      const auto& t = triangles[foot.triangle];
      const Eigen::Vector3d traction = foot.barycentric(0) * solved_traction_.col(t[0]) +
                                       foot.barycentric(1) * solved_traction_.col(t[1]) +
                                       foot.barycentric(2) * solved_traction_.col(t[2]);
      source_.traction.col(v) = traction;
      source_.load.col(v) = traction * geometry.vertex_area[v];
    }
    return true;
  } else {
    (void)tolerance;
    return false;  // 2D: no re-interpolation (numerics.electric_shape_tolerance is 3D only)
  }
}

template <int D>
void ElectricStage<D>::Run(long step) {
  SimulationState& state = *data_.state;
  state.gmres_iterations = 0;
  const int n = body_.size();
  // E(t) at the start of the step (the state's time is t^n until the step ends).
  const bool varying = IsTimeDependent(scene_.electric);
  const double field = data_.controls.field *
                       (varying ? FieldWaveformFactor(scene_.electric, data_.state->time) : 1.0);
  if (field == 0.0 || !(std::abs(field) > 0.0)) {
    source_.load.setZero(D, n);
    source_.traction.setZero(D, n);
    if (!varying) solved_field_ = 0.0;  // a time-dependent field keeps its last solve to scale
    return;
  }
  // A field that changes in time is not re-solved for its strength alone: with the points
  // within the move tolerance the quasi-static potential is the last solve's times E / E_solved
  // (G is linear in E: f = w = v = 0), and the Maxwell traction its times (E / E_solved)^2.
  const bool new_strength = solved_field_ != field && !(varying && base_field_ != 0.0);
  bool solve = last_solve_step_ < 0 || new_strength ||
               step - last_solve_step_ >= scene_.numerics.electric_every;
  if (!solve && scene_.numerics.electric_move_tolerance > 0.0) {
    // Largest point displacement since the last solve (no temporary: this runs every step).
    const PointsOf<D>& x = body_.positions();
    double moved2 = 0.0;
    for (int k = 0; k < n; ++k) {
      moved2 = std::max(moved2, (x.col(k) - positions_at_last_solve_.col(k)).squaredNorm());
    }
    const double tol = scene_.numerics.electric_move_tolerance;
    const bool moved = moved2 > tol * tol;
    if (moved && D == 3 && scene_.numerics.electric_shape_tolerance > 0.0) {
      // The vertices moved; if the surface did not (tank-treading along a steady shape), the
      // solved traction field, re-interpolated at the moved vertices, is still the answer.
      // (If the surface did move, the solve below replaces the re-interpolated forces.)
      if (ReinterpolateTraction(scene_.numerics.electric_shape_tolerance)) {
        positions_at_last_solve_ = x;
        if (varying) {
          KeepBase(solved_field_);  // the re-interpolated traction is at the solved field
          ScaleBase(field);
        }
        return;
      }
    }
    solve = moved;
  }
  if (!solve) {
    if (varying) ScaleBase(field);
    return;
  }
  solver_->SetAppliedField(field);
  InterfaceSolveReport report;
  try {
    if constexpr (D == 2) {
      report = solver_->Solve(body_.shape.curve, static_cast<double>(step));
    } else {
      report = solver_->Solve(body_.shape.mesh, static_cast<double>(step));
    }
  } catch (const std::exception& e) {
    FailStep(step, std::string("electric potential solve failed: ") + e.what());
  }
  state.gmres_iterations = report.iterations;
  state.gmres_residual = report.residual;
  if (!report.converged) {
    FailStep(step, "GMRES did not converge (residual " + FormatValue(report.residual) + " after " +
                       std::to_string(report.iterations) + " iterations)");
  }
  source_.load = solver_->force();
  source_.traction = solver_->traction();  // 2D: the force itself (per unit length)
  positions_at_last_solve_ = body_.positions();
  last_solve_step_ = step;
  solved_field_ = field;
  if (varying) KeepBase(field);
  if (D == 3 && scene_.numerics.electric_shape_tolerance > 0.0) {
    solved_positions_ = body_.positions();
    solved_traction_ = source_.traction;
    projector_.reset();
  }
}

template <int D>
void ElectricStage<D>::Resampled(const typename StepData<D>::Resample& resample) {
  if constexpr (D == 2) {
    // G along the re-spaced markers; the time history no longer applies.
    typename LeakyDielectricSolver<D>::WarmStart w;
    w.g = solver_->warm_start().g;
    if (static_cast<int>(w.g.size()) == body_.size()) {
      resample(w.g);
      solver_->set_warm_start(w);
    }
  }
  last_solve_step_ = -1;  // the force at the old points no longer applies
}

// Checkpoint section: the applied field, the warm start (G and its time history), the force,
// the points at the last solve and its step and field; 3D also the traction and the solved
// surface.
template <int D>
void ElectricStage<D>::Save(CheckpointWriter& w) const {
  w.Pod(solver_->applied_field());
  const typename LeakyDielectricSolver<D>::WarmStart& h = solver_->warm_start();
  w.Vec(h.g);
  w.Vec(h.g_previous);
  w.Pod(h.time_previous);
  w.Pod(h.time_last);
  w.Mat(source_.load);
  if constexpr (D == 3) w.Mat(source_.traction);  // 2D: the load itself
  w.Mat(positions_at_last_solve_);
  w.Pod(last_solve_step_);
  w.Pod(solved_field_);
  if constexpr (D == 3) {
    w.Mat(solved_positions_);
    w.Mat(solved_traction_);
  }
  if (IsTimeDependent(scene_.electric)) {  // (a dc scene's section is unchanged)
    w.Mat(base_load_);
    w.Mat(base_traction_);
    w.Pod(base_field_);
  }
}

template <int D>
void ElectricStage<D>::Restore(CheckpointReader& r) {
  solver_->SetAppliedField(r.Pod<double>());
  typename LeakyDielectricSolver<D>::WarmStart h;
  h.g = r.Vec();
  h.g_previous = r.Vec();
  h.time_previous = r.Pod<double>();
  h.time_last = r.Pod<double>();
  solver_->set_warm_start(h);
  source_.load = r.Mat<D>();
  if constexpr (D == 3) {
    source_.traction = r.Mat<3>();
  } else {
    source_.traction = source_.load;
  }
  positions_at_last_solve_ = r.Mat<D>();
  last_solve_step_ = r.Pod<long>();
  solved_field_ = r.Pod<double>();
  if constexpr (D == 3) {
    solved_positions_ = r.Mat<3>();
    solved_traction_ = r.Mat<3>();
    projector_.reset();  // rebuilt from solved_positions_ when needed
  }
  if (IsTimeDependent(scene_.electric)) {
    base_load_ = r.Mat<D>();
    base_traction_ = r.Mat<D>();
    base_field_ = r.Pod<double>();
  }
}

template class ElectricStage<2>;
template class ElectricStage<3>;

}  // namespace ehd
