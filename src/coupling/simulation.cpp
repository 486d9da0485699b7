// The coupled EHD step, song2019 sec. 3.6 (see simulation.h for the outline): builds the stages
// of capsule_stages_2d.h that the scene needs, runs them in order, and assembles the pipeline
// text and the checkpoint from them.
//
// Departures from the text: the markers may also be advanced by second-order Adams-Bashforth
// (numerics.integrator); the potential may be re-solved less often than every step
// (numerics.electric_every / electric_move_tolerance), reusing F_E at the (material) markers in
// between.
#include "ehd_capsule/coupling/simulation.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

#include "ehd_capsule/coupling/capsule_stages_2d.h"
#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {

void FailStep(long step, const std::string& what) {
  throw SimulationError("step " + std::to_string(step) + ": " + what);
}

struct Simulation::Impl {
  MembraneMarkers2D body;
  std::unique_ptr<ImmersedBoundary> ib;
  // Owned stages; `stages` is the run order (a subset: only what was built).
  std::unique_ptr<FluidStage2D> fluid;
  std::unique_ptr<ElectricStage2D> electric;  // only with a field
  std::unique_ptr<MembraneStage2D> membrane;
  std::unique_ptr<SpreadStage2D> spread;
  std::unique_ptr<ViscosityContrastStage2D> viscosity;  // only with V != 1
  std::unique_ptr<MarkerStage2D> markers;
  std::unique_ptr<DiagnosticsStage2D> diagnostics;
  std::vector<StepStage*> stages;
  std::vector<std::string> not_built;  // "electric (why)", for the pipeline text
  double pending_ca = -1.0, pending_ca_e = -1.0;
  std::vector<double> empty;
};

namespace {

Eigen::Matrix2Xd InitialMarkers(const Scene& s, const LatticeUnits& u) {
  const double a = u.radius;
  const Eigen::Vector2d centre(s.geometry.center_x * a, s.geometry.center_y * a);
  switch (s.geometry.shape) {
    case InitialShape::kCircle:
      return CircleMarkers(s.M, a, centre);
    case InitialShape::kEllipse: {
      // Same area as the circle of radius a: semi-axes a / sqrt(q) (x) and a sqrt(q) (y).
      const double q = s.geometry.aspect_ratio;
      return EllipseMarkers(s.M, a / std::sqrt(q), a * std::sqrt(q), centre);
    }
    case InitialShape::kBiconcave: {
      BiconcaveParameters p;
      p.radius = a;
      return BiconcaveMarkers(s.M, p, centre);
    }
  }
  return {};
}

std::string Fmt(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace

Simulation::Simulation(const Scene& scene) : scene_(scene), units_(DeriveLatticeUnits(scene)) {
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  MembraneMarkers2D& body = m.body;
  body.state = &state_;
  body.initial = InitialMarkers(scene_, units_);
  body.shear_rate = units_.shear_rate;
  body.field = units_.field;

  // Built in dependency order (the fluid first: the stages around it act on its arrays).
  m.fluid = std::make_unique<FluidStage2D>(scene_, units_, body);
  grid_ = m.fluid->lattice().grid();
  m.ib = std::make_unique<ImmersedBoundary>(grid_, scene_.has_shear(), false);
  m.membrane = std::make_unique<MembraneStage2D>(scene_, units_, body);
  if (scene_.electric_field) {
    m.electric = std::make_unique<ElectricStage2D>(scene_, units_, grid_, body);
  } else {
    m.not_built.push_back("electric (no field in the scene)");
  }
  m.spread = std::make_unique<SpreadStage2D>(scene_, *m.ib, body, m.fluid->lattice());
  if (scene_.has_viscosity_contrast()) {
    m.viscosity =
        std::make_unique<ViscosityContrastStage2D>(scene_, units_, grid_, body, m.fluid->lattice());
  } else {
    m.not_built.push_back("viscosity (V = 1)");
  }
  m.markers = std::make_unique<MarkerStage2D>(scene_, grid_, *m.ib, body, m.fluid->lattice(),
                                              m.electric.get());
  m.diagnostics = std::make_unique<DiagnosticsStage2D>(scene_, units_, body, m.fluid->lattice(),
                                                       m.electric != nullptr);

  // Run order, song2019 sec. 3.6.
  if (m.electric) m.stages.push_back(m.electric.get());
  m.stages.push_back(m.membrane.get());
  m.stages.push_back(m.spread.get());
  if (m.viscosity) m.stages.push_back(m.viscosity.get());
  m.stages.push_back(m.fluid.get());
  m.stages.push_back(m.markers.get());
  m.stages.push_back(m.diagnostics.get());
  Reset();
}

Simulation::~Simulation() = default;

void MembraneMarkers2D::ResetTo(const Eigen::Matrix2Xd& positions) {
  X = positions;
  curve.Update(X);
  const Eigen::Index n = X.cols();
  U.setZero(2, n);
  membrane_density.setZero(2, n);
  marker_force.setZero(2, n);
  electric_density.resize(2, 0);
  initial_area = curve.Area();
}

void Simulation::Reset() {
  Impl& m = *impl_;
  m.body.shear_rate = units_.shear_rate;
  m.body.field = units_.field;
  m.pending_ca = m.pending_ca_e = -1.0;
  m.body.ResetTo(m.body.initial);
  state_ = SimulationState();
  state_.ca = scene_.has_shear() ? scene_.Ca : 0.0;
  state_.ca_e = scene_.electric_field ? scene_.Ca_E : 0.0;
  // The fluid first: the stages that configure it (viscosity contrast) reset after it.
  m.fluid->Reset();
  for (StepStage* stage : m.stages) {
    if (stage != m.fluid.get()) stage->Reset();
  }
}

bool Simulation::has_electric_field() const { return impl_->electric != nullptr; }
bool Simulation::has_bending() const { return scene_.has_bending(); }
bool Simulation::has_viscosity_contrast() const { return impl_->viscosity != nullptr; }
const std::vector<double>& Simulation::ux() const { return impl_->fluid->lattice().ux(); }
const std::vector<double>& Simulation::uy() const { return impl_->fluid->lattice().uy(); }
const std::vector<double>& Simulation::potential() const {
  return impl_->electric ? impl_->electric->potential() : impl_->empty;
}
long Simulation::marker_redistributions() const { return impl_->markers->redistributions(); }

void Simulation::SetCaE(double ca_e) {
  const double max = scene_.electric.max_ca_e;
  if (!(ca_e >= 0.0 && ca_e <= max)) {
    throw std::invalid_argument("Ca_E = " + Fmt(ca_e) + " is out of range: accepted [0, " +
                                Fmt(max) + "] (electric.max_Ca_E)");
  }
  if (ca_e > 0.0 && !impl_->electric) {
    throw std::invalid_argument("Ca_E = " + Fmt(ca_e) + " needs the electric field, but scene " +
                                scene_.name +
                                " was built without it (accepted: 0; add an `electric:` block "
                                "or Ca_E > 0 to the scene)");
  }
  impl_->pending_ca_e = ca_e;
}

void Simulation::SetCa(double ca) {
  if (!scene_.has_shear()) {
    throw std::invalid_argument("Ca = " + Fmt(ca) + ": scene " + scene_.name +
                                " has no shear flow (flow: none); accepted: none");
  }
  if (ca == 0.0) {
    // Time is counted in units of 1/k (sum of k dt): with the walls stopped it would stand still
    // while the steps go on.
    throw std::invalid_argument(
        "Ca = 0 would stop the walls and with them the time unit 1/k: "
        "accepted (0, " +
        Fmt(scene_.max_Ca) + "]");
  }
  if (!(ca > 0.0 && ca <= scene_.max_Ca)) {
    throw std::invalid_argument("Ca = " + Fmt(ca) + " is out of range: accepted (0, " +
                                Fmt(scene_.max_Ca) + "] (max_Ca, the scene's measured limit)");
  }
  const double k = ShearRateForCa(units_, ca);
  const double mach = k * units_.half_width / kLatticeSoundSpeed;
  if (mach > scene_.numerics.max_mach) {
    const double ca_max = scene_.numerics.max_mach * kLatticeSoundSpeed / units_.half_width *
                          units_.viscosity * units_.radius / units_.tension;
    throw std::invalid_argument("Ca = " + Fmt(ca) + " gives wall Mach " + Fmt(mach) + " > " +
                                Fmt(scene_.numerics.max_mach) + ": accepted [0, " + Fmt(ca_max) +
                                "]");
  }
  impl_->pending_ca = ca;
}

void Simulation::Step() {
  Impl& m = *impl_;
  // Queued changes (applied before the step, turtlesim-style).
  if (m.pending_ca >= 0.0) {
    m.body.shear_rate = ShearRateForCa(units_, m.pending_ca);
    m.fluid->ApplyShearRate();
    state_.ca = m.pending_ca;
    m.pending_ca = -1.0;
  }
  if (m.pending_ca_e >= 0.0) {
    m.body.field = FieldForCaE(units_, m.pending_ca_e);
    state_.ca_e = m.pending_ca_e;
    m.pending_ca_e = -1.0;
  }
  const long step = state_.step + 1;
  for (StepStage* stage : m.stages) stage->Run(step);
}

std::string Simulation::Pipeline() const {
  const Impl& m = *impl_;
  std::ostringstream out;
  out << "pipeline (song2019 sec. 3.6), stages built from the scene:\n";
  int number = 0;
  for (const StepStage* stage : m.stages) {
    std::istringstream lines(stage->Describe());
    std::string line;
    bool first = true;
    while (std::getline(lines, line)) {
      if (first) {
        out << "  " << ++number << ". " << stage->name() << ": " << line << '\n';
      } else {
        out << "     " << line << '\n';
      }
      first = false;
    }
  }
  if (!m.not_built.empty()) {
    out << "  not built:";
    for (std::size_t i = 0; i < m.not_built.size(); ++i) {
      out << (i == 0 ? " " : ", ") << m.not_built[i];
    }
    out << '\n';
  }
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// Checkpoint: "EHDCKPT" + version + scene text + the clock + the markers + one section per stage
// in run order (checkpoint_io.h).
namespace {

constexpr char kCheckpointMagic[8] = {'E', 'H', 'D', 'C', 'K', 'P', 'T', '\0'};
// 2: electric warm-start history; 3: one section per stage (tank-treading tracker, re-spacing
// count).
constexpr std::int32_t kCheckpointVersion = 3;

}  // namespace

void Simulation::Save(const std::string& path) const {
  const Impl& m = *impl_;
  CheckpointWriter w(path);
  for (char c : kCheckpointMagic) w.Pod(c);
  w.Pod(kCheckpointVersion);
  w.Text(scene_.yaml_text);
  w.Section("clock");
  w.Pod(state_.step);
  w.Pod(state_.time);
  w.Pod(state_.ca);
  w.Pod(state_.ca_e);
  w.Pod(state_.gmres_iterations);
  w.Pod(state_.gmres_residual);
  w.Pod(m.body.shear_rate);
  w.Pod(m.body.field);
  w.Pod(m.pending_ca);
  w.Pod(m.pending_ca_e);
  w.Section("markers positions");
  w.Mat(m.body.X);
  for (const StepStage* stage : m.stages) {
    w.Section(stage->name());
    stage->Save(w);
  }
  w.Finish();
}

void Simulation::Restore(const std::string& path) {
  Impl& m = *impl_;
  CheckpointReader r(path);
  char magic[8];
  for (char& c : magic) c = r.Pod<char>();
  if (std::memcmp(magic, kCheckpointMagic, 8) != 0) r.Fail("not an ehd_capsule checkpoint");
  const auto version = r.Pod<std::int32_t>();
  if (version != kCheckpointVersion) {
    r.Fail("version " + std::to_string(version) + ", this build reads version " +
           std::to_string(kCheckpointVersion));
  }
  const std::string text = r.Text();
  if (text != scene_.yaml_text) {
    r.Fail("written for a different scene (or overrides):\n" + text);
  }
  r.ExpectSection("clock");
  SimulationState s;
  s.step = r.Pod<long>();
  s.time = r.Pod<double>();
  s.ca = r.Pod<double>();
  s.ca_e = r.Pod<double>();
  s.gmres_iterations = r.Pod<int>();
  s.gmres_residual = r.Pod<double>();
  m.body.shear_rate = r.Pod<double>();
  m.body.field = r.Pod<double>();
  m.pending_ca = r.Pod<double>();
  m.pending_ca_e = r.Pod<double>();
  r.ExpectSection("markers positions");
  Eigen::Matrix2Xd X = r.Mat<2>();
  if (X.cols() != m.body.initial.cols()) r.Fail("marker count differs");
  m.body.X = X;
  m.body.curve.Update(m.body.X);
  state_ = s;
  for (StepStage* stage : m.stages) {
    r.ExpectSection(stage->name());
    stage->Restore(r);
  }
}

}  // namespace ehd
