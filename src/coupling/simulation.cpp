// The coupled EHD step, song2019 sec. 3.6 (see simulation.h for the outline): holds the step
// assembled from the scene (coupled_step.h), applies the queued changes, advances the clock and
// writes the checkpoint from the stages.
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
#include <fstream>
#include <initializer_list>
#include <sstream>

#include "ehd_capsule/coupling/coupled_step.h"
#include "ehd_capsule/coupling/field_waveform.h"

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

namespace {

// The memory a scene's grid-sized arrays take, in doubles per lattice node: the peak resident
// size of `ehd_sim run --steps 2` over the node count, measured at N = 32 to 96 (3D) and 128 to
// 1024 (2D), rounded up. The fluid: the populations (D3Q19 in place: 19; D2Q9: 9 in place), rho,
// u and the force (2 D + 1), the stages' node fields; 3D 29.6, 2D 17.8. A field adds the
// potential solver's (FFTW buffer and eigenvalues, right-hand sides, the potential, E, the side
// and band tables): 3D 4.6, 2D 7.1. (Writing a checkpoint copies the populations once more.)
double EstimateBytes(const Scene& s, const LatticeUnits& u, std::string* parts) {
  const double nodes = static_cast<double>(u.nx) * u.ny * u.nz;
  const double fluid = s.dimension == 3 ? 30.0 : 18.0;
  const double electric = s.electric_field ? 8.0 : 0.0;
  std::ostringstream out;
  out << nodes << " nodes x (" << fluid << " fluid";
  if (electric > 0) out << " + " << electric << " electric";
  out << ") doubles";
  *parts = out.str();
  return 8.0 * nodes * (fluid + electric);
}

// MemAvailable in /proc/meminfo, in bytes; negative where it cannot be read.
double AvailableBytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return 1024.0 * kib;
  }
  return -1.0;
}

std::string Gigabytes(double bytes) {
  std::ostringstream o;
  o.precision(3);
  o << bytes / 1e9 << " GB";
  return o.str();
}

// Refuses a scene whose grid cannot fit in the memory available now (rather than dying in
// std::bad_alloc, or the kernel's OOM killer, while building it), naming N.
void CheckMemory(const Scene& s, const LatticeUnits& u) {
  std::string parts;
  const double needed = EstimateBytes(s, u, &parts);
  const double available = AvailableBytes();
  if (available < 0 || needed <= available) return;
  std::ostringstream grid;
  grid << u.nx << " x " << u.ny;
  if (s.dimension == 3) grid << " x " << u.nz;
  throw SceneError("scene " + s.name + ": N = " + std::to_string(s.N) + " (grid " + grid.str() +
                   (s.dimension == 3 && u.nx != u.ny ? ", set by N and geometry.half_length" : "") +
                   ") needs about " + Gigabytes(needed) + " (" + parts + ") but " +
                   Gigabytes(available) +
                   " are available (MemAvailable in /proc/meminfo): lower N");
}

}  // namespace

Simulation::Simulation(const Scene& scene) : scene_(scene), units_(DeriveLatticeUnits(scene)) {
  CheckMemory(scene_, units_);
  coupled_ = BuildCoupledStep(scene_, units_, state_);
  Reset();
}

Simulation::~Simulation() = default;

void Simulation::Reset() {
  pending_ca_ = pending_ca_e_ = -1.0;
  state_ = SimulationState();
  state_.dimension = coupled_->dimension();
  state_.ca = scene_.has_shear() ? scene_.Ca : 0.0;
  state_.ca_e = scene_.electric_field ? scene_.Ca_E : 0.0;
  coupled_->Reset();
}

bool Simulation::has_electric_field() const { return coupled_->has_electric_field(); }
bool Simulation::has_bending() const { return scene_.has_bending(); }
bool Simulation::has_viscosity_contrast() const { return coupled_->has_viscosity_contrast(); }
const std::vector<double>& Simulation::ux() const { return coupled_->velocity(0); }
const std::vector<double>& Simulation::uy() const { return coupled_->velocity(1); }
const std::vector<double>& Simulation::uz() const { return coupled_->velocity(2); }
std::vector<double> Simulation::VertexTension() const { return coupled_->VertexTension(); }
Eigen::Matrix3Xd Simulation::VertexVelocity() const { return coupled_->VertexVelocity(); }
const Grid2D& Simulation::grid() const {
  if (!coupled_->grid2()) throw std::logic_error("Simulation::grid: a 3D simulation has grid3d()");
  return *coupled_->grid2();
}
const Grid3D& Simulation::grid3d() const {
  if (!coupled_->grid3()) throw std::logic_error("Simulation::grid3d: a 2D simulation has grid()");
  return *coupled_->grid3();
}
const std::vector<std::array<int, 3>>& Simulation::triangles() const {
  return coupled_->triangles();
}
const std::vector<double>& Simulation::potential() const { return coupled_->potential(); }
long Simulation::marker_redistributions() const { return coupled_->marker_redistributions(); }
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
  pending_ca_e_ = ca_e;
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
  // With shear the unit of time is 1/k: a larger Ca takes more of a waveform's period per step.
  if (has_electric_field()) {
    const std::string unresolved = WaveformResolutionProblem(scene_.electric, k);
    if (!unresolved.empty()) {
      throw std::invalid_argument("Ca = " + FormatValue(ca) + ": " + unresolved);
    }
  }
  pending_ca_ = ca;
}

void Simulation::Step() {
  // Queued changes (applied before the step, turtlesim-style).
  StepControls& controls = coupled_->controls();
  if (pending_ca_ >= 0.0) {
    controls.shear_rate = ShearRateForCa(units_, pending_ca_);
    coupled_->ApplyShearRate();
    state_.ca = pending_ca_;
    pending_ca_ = -1.0;
  }
  if (pending_ca_e_ >= 0.0) {
    controls.field = FieldForCaE(units_, pending_ca_e_);
    state_.ca_e = pending_ca_e_;
    pending_ca_e_ = -1.0;
  }
  // The clock: time in units of 1/k with shear (the sum of k dt), else of the scene's unit.
  const long step = state_.step + 1;
  const double time = state_.time + (scene_.has_shear() ? controls.shear_rate : units_.dt);
  coupled_->Run(step, time);
  state_.step = step;
  state_.time = time;
}

std::vector<Simulation::StageTime> Simulation::StageTimes() const {
  std::vector<StageTime> out;
  const std::vector<StepStage*>& stages = coupled_->stages();
  const std::vector<double>& seconds = coupled_->stage_seconds();
  for (std::size_t i = 0; i < stages.size(); ++i) {
    out.push_back({stages[i]->name(), i < seconds.size() ? seconds[i] : 0.0});
  }
  return out;
}

void Simulation::ResetStageTimes() { coupled_->ResetStageTimes(); }

std::string Simulation::Pipeline() const { return coupled_->Pipeline(); }

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
  w.Pod(coupled_->controls().shear_rate);
  w.Pod(coupled_->controls().field);
  w.Pod(pending_ca_);
  w.Pod(pending_ca_e_);
  w.Section("markers positions");
  coupled_->SavePositions(w);
  for (const StepStage* stage : coupled_->stages()) {
    w.Section(stage->name());
    stage->Save(w);
  }
  w.Finish();
}

void Simulation::Restore(const std::string& path) {
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
  coupled_->controls().shear_rate = r.Pod<double>();
  coupled_->controls().field = r.Pod<double>();
  pending_ca_ = r.Pod<double>();
  pending_ca_e_ = r.Pod<double>();
  r.ExpectSection("markers positions");
  coupled_->RestorePositions(r);
  s.dimension = coupled_->dimension();
  state_ = s;
  for (StepStage* stage : coupled_->stages()) {
    r.ExpectSection(stage->name());
    stage->Restore(r);
  }
}

}  // namespace ehd
