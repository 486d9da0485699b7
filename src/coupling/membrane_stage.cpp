// Stage 2 of the coupled step: the membrane force density at the markers (drop: tension;
// capsule: Hookean + Kelvin-Voigt + bending, song2019 eqs. (110)-(115)).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "ehd_capsule/coupling/capsule_stages_2d.h"

namespace ehd {
MembraneStage2D::MembraneStage2D(const Scene& scene, const LatticeUnits& units,
                                 MembraneMarkers2D& body)
    : scene_(scene), body_(body) {
  MembraneParameters& mp = parameters_;
  if (scene.membrane == MembraneKind::kDrop) {
    mp.tension = units.tension;
  } else {
    mp.shear_modulus = units.tension;
    mp.tension = scene.prestress * units.tension;  // tau = tau_p + E_s (lambda - 1)
    mp.membrane_viscosity = units.membrane_viscosity;
    mp.bending_modulus = units.bending_modulus;
  }
  const ClosedCurve reference(body.initial);
  model_ = std::make_unique<MembraneModel>(mp, reference);
  // Explicit membrane limit at the initial shape (membrane_stability.h: the estimate is safe for
  // AB2; forward Euler allows twice the step). The lattice step is 1; numerics.membrane_substeps
  // = n divides the physical step by n (units.h), which multiplies the limit by n.
  const MembraneStabilityLimits limits = model_->Stability(reference, units.viscosity);
  const double dt_stable =
      limits.min_dt() * (scene.numerics.integrator == MarkerTimeScheme::kForwardEuler ? 2.0 : 1.0);
  if (dt_stable < 1.0) {
    const int need = static_cast<int>(std::ceil(scene.numerics.membrane_substeps / dt_stable));
    const char* term = limits.bending_dt == limits.min_dt()   ? "bending (E_b)"
                       : limits.elastic_dt == limits.min_dt() ? "elasticity (Ca)"
                                                              : "tension (Ca)";
    throw SceneError("scene " + scene.name + ": membrane explicit limit exceeded by the " + term +
                     " term: stable lattice dt " + FormatValue(dt_stable) + " < 1 (" +
                     model_->Describe() +
                     "); set numerics.membrane_substeps >= " + std::to_string(need) + " (now " +
                     std::to_string(scene.numerics.membrane_substeps) + ")");
  }
  viscous_number_ = limits.viscous_number;
}

std::string MembraneStage2D::Describe() const {
  std::ostringstream out;
  out << model_->Describe();
  if (scene_.numerics.membrane_substeps > 1) {
    out << " (time step refined " << scene_.numerics.membrane_substeps << "x)";
  }
  if (viscous_number_ >= 0.5) {
    out << "\nwarning: Kelvin-Voigt stability number " << viscous_number_
        << " >= 1/2 (explicit membrane viscosity may be unstable; lower eta)";
  }
  return out.str();
}

void MembraneStage2D::Reset() {
  model_ = std::make_unique<MembraneModel>(parameters_, ClosedCurve(body_.X));
  history_ = 0;
}

void MembraneStage2D::Run(long) {
  model_->ComputeForce(body_.curve, 1.0, body_.membrane_density);
  previous2_ = previous1_;
  previous1_ = body_.X;
  history_ = std::min(history_ + 1, 2);
}

void MembraneStage2D::Save(CheckpointWriter& w) const {
  w.Pod(static_cast<std::int32_t>(history_));
  w.Mat(previous1_);
  w.Mat(previous2_);
}

void MembraneStage2D::Restore(CheckpointReader& r) {
  history_ = r.Pod<std::int32_t>();
  previous1_ = r.Mat<2>();
  previous2_ = r.Mat<2>();
  // Replay the force evaluations on a fresh model to rebuild its stretch history.
  model_ = std::make_unique<MembraneModel>(parameters_, ClosedCurve(body_.initial));
  Eigen::Matrix2Xd scratch;
  if (history_ >= 2) model_->ComputeForce(ClosedCurve(previous2_), 1.0, scratch);
  if (history_ >= 1) model_->ComputeForce(ClosedCurve(previous1_), 1.0, scratch);
}

}  // namespace ehd
