// The coupled EHD step, song2019 sec. 3.6 (see simulation.h for the outline): builds the stages
// of capsule_stages_2d.h that the scene needs, runs them in order, and assembles the pipeline
// text and the checkpoint from them.
//
// Departures from the text: the markers may also be advanced by second-order Adams-Bashforth
// (numerics.integrator); the potential may be re-solved less often than every step
// (numerics.electric_every / electric_move_tolerance), reusing F_E at the (material) markers in
// between.
#include "ehd_capsule/coupling/simulation.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <sstream>

#include "ehd_capsule/coupling/capsule_stages_2d.h"
#include "ehd_capsule/coupling/capsule_stages_3d.h"
#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {

std::string FormatValue(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

double MaxLatticeMach(long step, const std::vector<const std::vector<double>*>& components) {
  double max_speed2 = 0.0;
  const std::size_t n = components.front()->size();
  for (std::size_t i = 0; i < n; ++i) {
    double s2 = 0.0;
    for (const std::vector<double>* c : components) s2 += (*c)[i] * (*c)[i];
    if (!(s2 <= max_speed2)) {
      if (!std::isfinite(s2)) {
        FailStep(step, "fluid velocity is not finite (NaN/Inf) at node " + std::to_string(i));
      }
      max_speed2 = s2;
    }
  }
  return std::sqrt(max_speed2) / kLatticeSoundSpeed;
}

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
  // 3D (dimension: 3).
  std::unique_ptr<MembraneSurface3D> surface;
  std::unique_ptr<ImmersedBoundary3D> ib3;
  std::unique_ptr<FluidStage3D> fluid3;
  std::unique_ptr<ElectricStage3D> electric3;  // only with a field
  std::unique_ptr<MembraneStage3D> membrane3;
  std::unique_ptr<SpreadStage3D> spread3;
  std::unique_ptr<MarkerStage3D> markers3;
  std::unique_ptr<DiagnosticsStage3D> diagnostics3;

  std::vector<StepStage*> stages;
  std::vector<double> stage_seconds;   // aligned with stages
  std::vector<std::string> not_built;  // "electric (why)", for the pipeline text
  double pending_ca = -1.0, pending_ca_e = -1.0;
  std::vector<double> empty;
  std::vector<std::array<int, 3>> no_triangles;

  bool three_d() const { return surface != nullptr; }
  double& shear_rate() { return surface ? surface->shear_rate : body.shear_rate; }
  double& field() { return surface ? surface->field : body.field; }
  void ApplyShearRate() {
    if (fluid3) {
      fluid3->ApplyShearRate();
    } else {
      fluid->ApplyShearRate();
    }
  }
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
    case InitialShape::kSphere:
      break;  // 3D only (refused for dimension 2 by the scene validator)
  }
  throw SceneError("scene " + s.name + ": shape " + ToString(s.geometry.shape) +
                   " has no 2D marker set");
}

}  // namespace

Simulation::Simulation(const Scene& scene) : scene_(scene), units_(DeriveLatticeUnits(scene)) {
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  if (scene_.dimension == 3) {
    m.surface = std::make_unique<MembraneSurface3D>();
    MembraneSurface3D& surface = *m.surface;
    surface.state = &state_;
    surface.mesh = InitialSurface(scene_, units_);
    surface.initial = surface.mesh.vertices();
    surface.shear_rate = units_.shear_rate;
    surface.field = units_.field;
    m.fluid3 = std::make_unique<FluidStage3D>(scene_, units_, surface);
    grid3d_ = m.fluid3->lattice().grid();
    if (scene_.electric_field) {
      m.electric3 = std::make_unique<ElectricStage3D>(scene_, units_, grid3d_, surface);
    }
    m.ib3 = std::make_unique<ImmersedBoundary3D>(
        grid3d_, std::array<bool, 3>{scene_.has_shear(), false, scene_.has_shear()});
    m.membrane3 = std::make_unique<MembraneStage3D>(scene_, units_, surface);
    m.spread3 = std::make_unique<SpreadStage3D>(*m.ib3, surface, m.fluid3->lattice());
    m.markers3 =
        std::make_unique<MarkerStage3D>(scene_, grid3d_, *m.ib3, surface, m.fluid3->lattice());
    m.diagnostics3 = std::make_unique<DiagnosticsStage3D>(
        scene_, units_, surface, m.fluid3->lattice(), m.electric3 != nullptr);
    if (m.electric3) {
      m.stages.push_back(m.electric3.get());
    } else {
      m.not_built.push_back("electric (no field in the scene)");
    }
    for (StepStage* stage :
         std::initializer_list<StepStage*>{m.membrane3.get(), m.spread3.get(), m.fluid3.get(),
                                           m.markers3.get(), m.diagnostics3.get()}) {
      m.stages.push_back(stage);
    }
    m.not_built.push_back("viscosity (V = 1)");
    Reset();
    return;
  }
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
  if (m.three_d()) {
    m.surface->shear_rate = units_.shear_rate;
    m.surface->field = units_.field;
    m.pending_ca = m.pending_ca_e = -1.0;
    m.surface->ResetTo(m.surface->initial);
    state_ = SimulationState();
    state_.dimension = 3;
    state_.ca = scene_.has_shear() ? scene_.Ca : 0.0;
    state_.ca_e = scene_.electric_field ? scene_.Ca_E : 0.0;
    m.fluid3->Reset();
    for (StepStage* stage : m.stages) {
      if (stage != m.fluid3.get()) stage->Reset();
    }
    return;
  }
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

bool Simulation::has_electric_field() const {
  return impl_->electric != nullptr || impl_->electric3 != nullptr;
}
bool Simulation::has_bending() const { return scene_.has_bending(); }
bool Simulation::has_viscosity_contrast() const { return impl_->viscosity != nullptr; }
const std::vector<double>& Simulation::ux() const {
  return impl_->fluid3 ? impl_->fluid3->lattice().ux() : impl_->fluid->lattice().ux();
}
const std::vector<double>& Simulation::uy() const {
  return impl_->fluid3 ? impl_->fluid3->lattice().uy() : impl_->fluid->lattice().uy();
}
const std::vector<double>& Simulation::uz() const {
  if (!impl_->fluid3) throw std::logic_error("Simulation::uz: a 2D simulation has no z velocity");
  return impl_->fluid3->lattice().velocity(2);
}
std::vector<double> Simulation::VertexTension() const {
  if (!impl_->membrane3) {
    throw std::logic_error("Simulation::VertexTension: a 2D simulation has no surface mesh");
  }
  return impl_->membrane3->VertexTension();
}
Eigen::Matrix3Xd Simulation::VertexVelocity() const {
  if (!impl_->three_d()) {
    throw std::logic_error("Simulation::VertexVelocity: a 2D simulation has no surface mesh");
  }
  return impl_->surface->U * (units_.steps_per_time_unit / units_.radius);
}
const Grid2D& Simulation::grid() const {
  if (impl_->three_d()) throw std::logic_error("Simulation::grid: a 3D simulation has grid3d()");
  return grid_;
}
const Grid3D& Simulation::grid3d() const {
  if (!impl_->three_d()) throw std::logic_error("Simulation::grid3d: a 2D simulation has grid()");
  return grid3d_;
}
const std::vector<std::array<int, 3>>& Simulation::triangles() const {
  return impl_->three_d() ? impl_->surface->mesh.triangles() : impl_->no_triangles;
}
const std::vector<double>& Simulation::potential() const {
  if (impl_->electric3) return impl_->electric3->potential();
  return impl_->electric ? impl_->electric->potential() : impl_->empty;
}
long Simulation::marker_redistributions() const {
  return impl_->markers ? impl_->markers->redistributions() : 0;
}

void Simulation::SetCaE(double ca_e) {
  const double max = scene_.electric.max_ca_e;
  if (!(ca_e >= 0.0 && ca_e <= max)) {
    throw std::invalid_argument("Ca_E = " + FormatValue(ca_e) + " is out of range: accepted [0, " +
                                FormatValue(max) + "] (electric.max_Ca_E)");
  }
  if (ca_e > 0.0 && !has_electric_field()) {
    throw std::invalid_argument("Ca_E = " + FormatValue(ca_e) +
                                " needs the electric field, but scene " + scene_.name +
                                " was built without it (accepted: 0; add an `electric:` block "
                                "or Ca_E > 0 to the scene)");
  }
  impl_->pending_ca_e = ca_e;
}

void Simulation::SetCa(double ca) {
  if (!scene_.has_shear()) {
    throw std::invalid_argument("Ca = " + FormatValue(ca) + ": scene " + scene_.name +
                                " has no shear flow (flow: none); accepted: none");
  }
  if (ca == 0.0) {
    // Time is counted in units of 1/k (sum of k dt): with the walls stopped it would stand still
    // while the steps go on.
    throw std::invalid_argument(
        "Ca = 0 would stop the walls and with them the time unit 1/k: "
        "accepted (0, " +
        FormatValue(scene_.max_Ca) + "]");
  }
  if (!(ca > 0.0 && ca <= scene_.max_Ca)) {
    throw std::invalid_argument("Ca = " + FormatValue(ca) + " is out of range: accepted (0, " +
                                FormatValue(scene_.max_Ca) +
                                "] (max_Ca, the scene's measured limit)");
  }
  const double k = ShearRateForCa(units_, ca);
  const double mach = k * units_.half_width / kLatticeSoundSpeed;
  if (mach > scene_.numerics.max_mach) {
    const double ca_max = scene_.numerics.max_mach * kLatticeSoundSpeed / units_.half_width *
                          units_.viscosity * units_.radius / units_.tension;
    throw std::invalid_argument("Ca = " + FormatValue(ca) + " gives wall Mach " +
                                FormatValue(mach) + " > " + FormatValue(scene_.numerics.max_mach) +
                                ": accepted [0, " + FormatValue(ca_max) + "]");
  }
  impl_->pending_ca = ca;
}

void Simulation::Step() {
  Impl& m = *impl_;
  // Queued changes (applied before the step, turtlesim-style).
  if (m.pending_ca >= 0.0) {
    m.shear_rate() = ShearRateForCa(units_, m.pending_ca);
    m.ApplyShearRate();
    state_.ca = m.pending_ca;
    m.pending_ca = -1.0;
  }
  if (m.pending_ca_e >= 0.0) {
    m.field() = FieldForCaE(units_, m.pending_ca_e);
    state_.ca_e = m.pending_ca_e;
    m.pending_ca_e = -1.0;
  }
  const long step = state_.step + 1;
  if (m.stage_seconds.size() != m.stages.size()) m.stage_seconds.assign(m.stages.size(), 0.0);
  auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < m.stages.size(); ++i) {
    m.stages[i]->Run(step);
    const auto t1 = std::chrono::steady_clock::now();
    m.stage_seconds[i] += std::chrono::duration<double>(t1 - t0).count();
    t0 = t1;
  }
}

std::vector<Simulation::StageTime> Simulation::StageTimes() const {
  const Impl& m = *impl_;
  std::vector<StageTime> out;
  for (std::size_t i = 0; i < m.stages.size(); ++i) {
    out.push_back({m.stages[i]->name(), i < m.stage_seconds.size() ? m.stage_seconds[i] : 0.0});
  }
  return out;
}

void Simulation::ResetStageTimes() { impl_->stage_seconds.assign(impl_->stages.size(), 0.0); }

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
  w.Pod(m.three_d() ? m.surface->shear_rate : m.body.shear_rate);
  w.Pod(m.three_d() ? m.surface->field : m.body.field);
  w.Pod(m.pending_ca);
  w.Pod(m.pending_ca_e);
  w.Section("markers positions");
  if (m.three_d()) {
    w.Mat(m.surface->mesh.vertices());
  } else {
    w.Mat(m.body.X);
  }
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
  m.shear_rate() = r.Pod<double>();
  m.field() = r.Pod<double>();
  m.pending_ca = r.Pod<double>();
  m.pending_ca_e = r.Pod<double>();
  r.ExpectSection("markers positions");
  if (m.three_d()) {
    const Eigen::Matrix3Xd X = r.Mat<3>();
    if (X.cols() != m.surface->initial.cols()) r.Fail("vertex count differs");
    m.surface->mesh.SetVertices(X);
    s.dimension = 3;
  } else {
    Eigen::Matrix2Xd X = r.Mat<2>();
    if (X.cols() != m.body.initial.cols()) r.Fail("marker count differs");
    m.body.X = X;
    m.body.curve.Update(m.body.X);
  }
  state_ = s;
  for (StepStage* stage : m.stages) {
    r.ExpectSection(stage->name());
    stage->Restore(r);
  }
}

}  // namespace ehd
