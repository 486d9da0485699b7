// Stage 4 of the coupled step: one D2Q9 MRT lattice Boltzmann step with the spread force
// (song2019 eqs. (97), (107)-(108)), then the fluid watchdogs (non-finite velocity, lattice Mach).
#include <cmath>
#include <sstream>

#include "ehd_capsule/coupling/capsule_stages_2d.h"

namespace ehd {
FluidStage2D::FluidStage2D(const Scene& scene, const LatticeUnits& units, MembraneMarkers2D& body)
    : scene_(scene), units_(units), body_(body) {
  LbmParameters p;
  p.nx = p.ny = scene.N;
  p.viscosity = units.viscosity;
  p.threads = scene.numerics.threads;
  p.boundary = scene.has_shear() ? FluidBoundary::kShearWalls : FluidBoundary::kClosedBox;
  lattice_ = std::make_unique<LatticeBoltzmann2D>(p);
}

std::string FluidStage2D::Describe() const {
  std::ostringstream out;
  out << "D2Q9 MRT LBM " << scene_.N << "x" << scene_.N << ", tau = " << units_.tau << ", "
      << (scene_.has_shear() ? "moving shear walls" : "closed box at rest");
  return out.str();
}

void FluidStage2D::Reset() {
  lattice_->ClearViscosityField();  // the initial state has the outer viscosity everywhere
  if (scene_.has_shear()) {
    lattice_->InitializeShear(body_.shear_rate);
  } else {
    lattice_->InitializeAtRest();
  }
  lattice_->ClearForce();
}

void FluidStage2D::ApplyShearRate() {
  lattice_->SetWallVelocities(-body_.shear_rate * units_.half_width,
                              body_.shear_rate * units_.half_width);
}

void FluidStage2D::Run(long step) {
  lattice_->Step();
  SimulationState& state = *body_.state;
  state.max_mach = MaxLatticeMach(step, {&lattice_->ux(), &lattice_->uy()});
  if (state.max_mach > scene_.numerics.max_mach) {
    // Name the force behind the fast flow, so the user knows which number to lower.
    const double membrane_max = body_.membrane_density.colwise().norm().maxCoeff();
    std::string forces = "; largest force density: membrane " + FormatValue(membrane_max);
    if (body_.electric_density.size() > 0) {
      forces += ", electric " + FormatValue(body_.electric_density.colwise().norm().maxCoeff()) +
                " (Ca_E = " + FormatValue(state.ca_e) + ")";
    }
    FailStep(step, "lattice Mach number " + FormatValue(state.max_mach) + " > " +
                       FormatValue(scene_.numerics.max_mach) + " (numerics.max_mach)" + forces);
  }
}

void FluidStage2D::Save(CheckpointWriter& w) const {
  w.Pod(lattice_->step());
  w.Vec(lattice_->populations());
  w.Vec(lattice_->force_x());
  w.Vec(lattice_->force_y());
}

void FluidStage2D::Restore(CheckpointReader& r) {
  const long step = r.Pod<long>();
  const std::vector<double> f = r.Vec();
  lattice_->force_x() = r.Vec();
  lattice_->force_y() = r.Vec();
  lattice_->SetPopulations(f);
  lattice_->SetStep(step);
  if (scene_.has_shear()) ApplyShearRate();
}

}  // namespace ehd
