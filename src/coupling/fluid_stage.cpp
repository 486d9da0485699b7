// The fluid stage (coupling/stages/fluid_stage.h).
#include "ehd_capsule/coupling/stages/fluid_stage.h"

#include <sstream>

namespace ehd {

template <int D>
FluidStage<D>::FluidStage(const Scene& scene, const LatticeUnits& units, StepData<D>& data)
    : scene_(scene), units_(units), data_(data) {
  LbmParameters p;
  p.viscosity = units.viscosity;
  p.threads = scene.numerics.threads;
  p.boundary = scene.has_shear() ? FluidBoundary::kShearWalls : FluidBoundary::kClosedBox;
  if constexpr (D == 2) {
    p.nx = p.ny = scene.N;  // the relaxation rates of song2019 sec. 3.1.1 (LbmParameters)
  } else {
    p.nx = units.nx;
    p.ny = units.ny;
    p.nz = units.nz;
    // song2019 sec. 3.1.2: the heat fluxes (and the bulk rate) follow the shear rate, the
    // higher-order moments relax at 1.8.
    const double s_nu = 1.0 / (3.0 * units.viscosity + 0.5);
    p.s_e = s_nu;
    p.s_q = s_nu;
    p.s_epsilon = 1.8;
    p.s_pi = 1.8;
    p.s_m = 1.8;
  }
  lattice_ = std::make_unique<FluidOf<D>>(p);
}

template <int D>
std::string FluidStage<D>::Describe() const {
  std::ostringstream out;
  if constexpr (D == 2) {
    out << "D2Q9 MRT LBM " << scene_.N << "x" << scene_.N << ", tau = " << units_.tau << ", "
        << (scene_.has_shear() ? "moving shear walls" : "closed box at rest");
  } else {
    out << "D3Q19 MRT LBM ";
    if (units_.nx == units_.ny) {
      out << units_.ny << "^3";
    } else {
      out << units_.nx << " x " << units_.ny << " x " << units_.nz;
    }
    out << ", tau = " << units_.tau << " (s_e = s_q = s_nu, s_eps = s_pi = s_m = 1.8), "
        << (scene_.has_shear() ? "moving shear walls, periodic x and z" : "closed box at rest");
  }
  return out.str();
}

template <int D>
void FluidStage<D>::Reset() {
  lattice_->ClearViscosityField();  // the initial state has the outer viscosity everywhere
  if (scene_.has_shear()) {
    lattice_->InitializeShear(data_.controls.shear_rate);
  } else {
    lattice_->InitializeAtRest();
  }
  lattice_->ClearForce();
}

template <int D>
void FluidStage<D>::ApplyShearRate() {
  lattice_->SetWallVelocities(-data_.controls.shear_rate * units_.half_width,
                              data_.controls.shear_rate * units_.half_width);
}

template <int D>
void FluidStage<D>::Run(long step) {
  lattice_->Step();
  SimulationState& state = *data_.state;
  const auto u = VelocityOf<D>(*lattice_);
  state.max_mach =
      MaxLatticeMach(step, std::vector<const std::vector<double>*>(u.begin(), u.end()));
  if (state.max_mach > scene_.numerics.max_mach) {
    // Name the forces behind the fast flow, so the user knows which number to lower.
    std::string forces;
    for (const Body<D>& body : data_.bodies) {
      forces += std::string(forces.empty() ? "" : "; ") + body.DescribeLargestLoads();
    }
    FailStep(step,
             "lattice Mach number " + FormatValue(state.max_mach) + " > " +
                 FormatValue(scene_.numerics.max_mach) + " (numerics.max_mach); largest " +
                 (D == 2 ? "force density" : "force per vertex") + ": " + forces +
                 (data_.controls.field > 0 ? " (Ca_E = " + FormatValue(state.ca_e) + ")" : ""));
  }
}

template <int D>
void FluidStage<D>::Save(CheckpointWriter& w) const {
  w.Pod(lattice_->step());
  w.Vec(lattice_->populations());
  for (int a = 0; a < D; ++a) w.Vec(lattice_->force(a));
}

template <int D>
void FluidStage<D>::Restore(CheckpointReader& r) {
  const long step = r.Pod<long>();
  const std::vector<double> f = r.Vec();
  for (int a = 0; a < D; ++a) lattice_->force(a) = r.Vec();
  lattice_->SetPopulations(f);
  lattice_->SetStep(step);
  if (scene_.has_shear()) ApplyShearRate();
}

template class FluidStage<2>;
template class FluidStage<3>;

}  // namespace ehd
