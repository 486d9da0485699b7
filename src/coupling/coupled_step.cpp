// The coupled step assembled from the scene (coupling/coupled_step.h): CoupledStepOf<D> builds
// the bodies and the stages the scene needs, in one place for both dimensions.
#include "ehd_capsule/coupling/coupled_step.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "ehd_capsule/coupling/force_term.h"
#include "ehd_capsule/coupling/stages/diagnostics_stage.h"
#include "ehd_capsule/coupling/stages/electric_stage.h"
#include "ehd_capsule/coupling/stages/fluid_stage.h"
#include "ehd_capsule/coupling/stages/marker_stage.h"
#include "ehd_capsule/coupling/stages/membrane_stage.h"
#include "ehd_capsule/coupling/stages/spread_stage.h"
#include "ehd_capsule/coupling/stages/viscosity_stage.h"
#include "ehd_capsule/geometry/initial_shapes.h"

namespace ehd {

void CoupledStep::Run(long step, double time) {
  if (stage_seconds_.size() != stages_.size()) stage_seconds_.assign(stages_.size(), 0.0);
  SetClock(step, time);
  auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < stages_.size(); ++i) {
    stages_[i]->Run(step);
    const auto t1 = std::chrono::steady_clock::now();
    stage_seconds_[i] += std::chrono::duration<double>(t1 - t0).count();
    t0 = t1;
  }
}

std::string CoupledStep::Pipeline() const {
  std::ostringstream out;
  out << "pipeline (song2019 sec. 3.6), stages built from the scene:\n";
  int number = 0;
  for (const StepStage* stage : stages_) {
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
  if (!not_built_.empty()) {
    out << "  not built:";
    for (std::size_t i = 0; i < not_built_.size(); ++i) {
      out << (i == 0 ? " " : ", ") << not_built_[i];
    }
    out << '\n';
  }
  return out.str();
}

namespace {

// The scene's initial body: markers on the curve (2D) or the mesh of its subdivision (3D), in
// lattice units about the scene's centre.
void PlaceInitialShape(const Scene& s, const LatticeUnits& u, Body<2>& body) {
  const double a = u.radius;
  const Eigen::Vector2d centre(s.geometry.center_x * a, s.geometry.center_y * a);
  switch (s.geometry.shape) {
    case InitialShape::kCircle:
      body.initial = CircleMarkers(s.M, a, centre);
      break;
    case InitialShape::kEllipse: {
      // Same area as the circle of radius a: semi-axes a / sqrt(q) (x) and a sqrt(q) (y).
      const double q = s.geometry.aspect_ratio;
      body.initial = EllipseMarkers(s.M, a / std::sqrt(q), a * std::sqrt(q), centre);
      break;
    }
    case InitialShape::kBiconcave: {
      BiconcaveParameters p;
      p.radius = a;
      body.initial = BiconcaveMarkers(s.M, p, centre);
      break;
    }
    case InitialShape::kSphere:  // 3D only (refused for dimension 2 by the scene validator)
      throw SceneError("scene " + s.name + ": shape " + ToString(s.geometry.shape) +
                       " has no 2D marker set");
  }
  body.shape.SetPositions(body.initial);
}

void PlaceInitialShape(const Scene& s, const LatticeUnits& u, Body<3>& body) {
  const double a = u.radius;
  TriangleMesh mesh;
  if (s.geometry.shape == InitialShape::kBiconcave) {
    BiconcaveParameters p;
    p.radius = a;
    mesh = BiconcaveMesh(s.mesh_subdivisions, p);
  } else {
    mesh = IcosphereMesh(s.mesh_subdivisions, a);
  }
  const Eigen::Vector3d centre(s.geometry.center_x * a, s.geometry.center_y * a,
                               s.geometry.center_z * a);
  mesh.SetVertices(mesh.vertices().colwise() + centre);
  body.shape.mesh = mesh;
  body.initial = mesh.vertices();
}

// The initial body against the box, before anything is allocated: a shape thinner than a cell
// along an axis (a degenerate ellipse) or longer than a periodic box, or one that reaches a wall
// or comes within the marker stage's 2 h margin of one, is refused naming the keys that place
// and size it. (A body that moves closer during the run is stopped by the marker stage.)
template <int D>
void CheckInitialShape(const Scene& s, const LatticeUnits& u,
                       const Eigen::Matrix<double, D, Eigen::Dynamic>& x) {
  const std::string fail = "scene " + s.name + ": the initial " + ToString(s.geometry.shape);
  const bool ellipse = s.geometry.shape == InitialShape::kEllipse;
  // The keys that make the body thicker in cells (the box's keys are named per axis).
  const std::string thicker =
      ellipse ? "raise geometry.aspect_ratio (now " + FormatValue(s.geometry.aspect_ratio) + ")"
              : "raise N or lower geometry.half_width (a = " + FormatValue(u.radius) + " cells)";
  const std::string shape_key =
      ellipse ? ", geometry.aspect_ratio (now " + FormatValue(s.geometry.aspect_ratio) + ")" : "";
  if (!x.allFinite()) throw SceneError(fail + " has points that are not finite: " + thicker);
  const int extent[3] = {u.nx, u.ny, u.nz};
  const double centre[3] = {s.geometry.center_x, s.geometry.center_y, s.geometry.center_z};
  for (int a = 0; a < D; ++a) {
    const std::string axis(1, "xyz"[a]);
    const double lo = x.row(a).minCoeff(), hi = x.row(a).maxCoeff();
    const double half_box = 0.5 * extent[a];  // the box is [-half_box, half_box] in cells
    const std::string box_key = a == 1 || D == 2 ? "geometry.half_width" : "geometry.half_length";
    const double box_a = half_box / u.radius;  // in units of a
    if (hi - lo < 1.0) {
      throw SceneError(fail + " is " + FormatValue(hi - lo) + " cells thick along " + axis +
                       " (less than one cell: the grid cannot resolve it): " + thicker);
    }
    const bool periodic = a != 1 && s.has_shear();
    if (periodic) {
      if (hi - lo >= 2.0 * half_box) {
        throw SceneError(
            fail + " spans " + FormatValue((hi - lo) / u.radius) + " a along " + axis +
            ", more than the periodic box (2 " + box_key + " = " + FormatValue(2.0 * box_a) +
            " a): " + (ellipse ? "change" + shape_key.substr(1) + " or " : std::string()) +
            "raise " + box_key);
      }
      continue;
    }
    // The marker stage's margin (MarkerStage::CheckInside): a point closer than 2 h to a wall
    // would lose part of its kernel's support, and the run would stop at step 1.
    const double margin = 2.0;  // 2 h, in cells
    if (lo >= -half_box + margin && hi <= half_box - margin) continue;
    const bool upper = hi > half_box - margin;
    const double reach = (upper ? hi : lo) / u.radius;
    const std::string where = std::abs(reach) < box_a    ? "within 2 h of"
                              : std::abs(reach) == box_a ? "on"
                                                         : "past";
    throw SceneError(
        fail + " reaches " + axis + " = " + FormatValue(reach) + " a, " + where + " the wall " +
        axis + " = " + FormatValue(upper ? box_a : -box_a) + " a (" + box_key + " = " +
        FormatValue(box_a) + "): move geometry.center_" + axis + " (now " + FormatValue(centre[a]) +
        ")" + (ellipse ? ", change" + shape_key.substr(1) : std::string()) + " or raise " +
        box_key +
        " so that the body lies inside, at least 2 h = " + FormatValue(margin / u.radius) +
        " a from the wall (the run stops at the first step " + "closer than that)");
  }
}

template <int D>
class CoupledStepOf : public CoupledStep {
 public:
  CoupledStepOf(const Scene& scene, const LatticeUnits& units, SimulationState& state)
      : scene_(scene), units_(units) {
    data_.state = &state;
    data_.controls = {units.shear_rate, units.field};
    data_.bodies.resize(1);  // the shipped scenes hold one body
    for (Body<D>& body : data_.bodies) {
      PlaceInitialShape(scene, units, body);
      CheckInitialShape<D>(scene, units, body.initial);
    }

    // Built in dependency order (the fluid first: the stages around it act on its arrays); the
    // membrane before the electric stage, so that the force sources add up as membrane (+
    // bending) + electric.
    fluid_ = std::make_unique<FluidStage<D>>(scene, units, data_);
    grid_ = fluid_->lattice().grid();
    std::array<bool, D> periodic{};
    for (int a = 0; a < D; ++a) periodic[a] = a != 1 && scene.has_shear();  // walls at y = +-L
    ib_ = std::make_unique<ImmersedBoundaryTransfer<D>>(grid_, periodic,
                                                        ParseDeltaKernel(scene.numerics.ib_kernel));
    membrane_ = std::make_unique<MembraneStage<D>>(scene, units, data_);
    if (scene.electric_field) {
      electric_ = std::make_unique<ElectricStage<D>>(scene, units, grid_, data_);
    } else {
      not_built_.push_back("electric (no field in the scene)");
    }
    // Force terms (src/forces/): their sources after the membrane's and the electric one.
    for (const ForceTermModule& term : ForceTermModules()) {
      if (term.active(scene)) {
        force_terms_.push_back(std::make_unique<ForceTermStage<D>>(term, scene, units, data_));
      }
    }
    spread_ = std::make_unique<SpreadStage<D>>(scene, *ib_, data_, fluid_->lattice());
    if constexpr (D == 2) {
      if (scene.has_viscosity_contrast()) {
        viscosity_ =
            std::make_unique<ViscosityStage<2>>(scene, units, grid_, data_, fluid_->lattice());
      }
    }
    if (!viscosity_) not_built_.push_back("viscosity (V = 1)");
    markers_ = std::make_unique<MarkerStage<D>>(scene, grid_, *ib_, data_, fluid_->lattice());
    diagnostics_ = std::make_unique<DiagnosticsStage<D>>(scene, units, data_, fluid_->lattice());

    // Run order, song2019 sec. 3.6 (the force terms between the membrane and the spread).
    std::vector<StepStage*> order{electric_.get(), membrane_.get()};
    for (const auto& term : force_terms_) order.push_back(term.get());
    for (StepStage* stage :
         {static_cast<StepStage*>(spread_.get()), viscosity_.get(),
          static_cast<StepStage*>(fluid_.get()), static_cast<StepStage*>(markers_.get()),
          static_cast<StepStage*>(diagnostics_.get())}) {
      order.push_back(stage);
    }
    for (StepStage* stage : order) {
      if (stage != nullptr) stages_.push_back(stage);
    }
  }

  int dimension() const override { return D; }
  StepControls& controls() override { return data_.controls; }

  void Reset() override {
    data_.controls = {units_.shear_rate, units_.field};
    for (Body<D>& body : data_.bodies) body.ResetTo(body.initial);
    fluid_->Reset();
    for (StepStage* stage : stages_) {
      if (stage != fluid_.get()) stage->Reset();
    }
  }

  void ApplyShearRate() override { fluid_->ApplyShearRate(); }

  void SetClock(long step, double time) override {
    data_.step = step;
    data_.time = time;
  }

  void SavePositions(CheckpointWriter& w) const override {
    w.Mat(data_.bodies.front().positions());
  }
  void RestorePositions(CheckpointReader& r) override {
    Body<D>& body = data_.bodies.front();
    const PointsOf<D> x = r.Mat<D>();
    if (x.cols() != body.initial.cols()) {
      r.Fail(std::string(BodyShape<D>::kPointName) + " count differs");
    }
    body.shape.SetPositions(x);
  }

  bool has_electric_field() const override { return electric_ != nullptr; }
  bool has_viscosity_contrast() const override { return viscosity_ != nullptr; }
  const Grid2D* grid2() const override {
    if constexpr (D == 2) return &grid_;
    return nullptr;
  }
  const Grid3D* grid3() const override {
    if constexpr (D == 3) return &grid_;
    return nullptr;
  }
  const std::vector<double>& velocity(int axis) const override {
    if (axis < 0 || axis >= D) {
      throw std::logic_error("Simulation: a " + std::to_string(D) +
                             "D simulation has no velocity component " + std::to_string(axis));
    }
    return fluid_->lattice().velocity(axis);
  }
  const std::vector<double>& potential() const override {
    return electric_ ? electric_->potential() : empty_;
  }
  const std::vector<std::array<int, 3>>& triangles() const override {
    if constexpr (D == 3) return data_.bodies.front().shape.mesh.triangles();
    return no_triangles_;
  }
  std::vector<double> VertexTension() const override {
    if constexpr (D == 2) {
      throw std::logic_error("Simulation::VertexTension: a 2D simulation has no surface mesh");
    }
    return membrane_->VertexTension(0);
  }
  Eigen::Matrix3Xd VertexVelocity() const override {
    if constexpr (D == 2) {
      throw std::logic_error("Simulation::VertexVelocity: a 2D simulation has no surface mesh");
    } else {
      return data_.bodies.front().U * (units_.steps_per_time_unit / units_.radius);
    }
  }
  long marker_redistributions() const override { return markers_->redistributions(); }

 private:
  const Scene& scene_;
  const LatticeUnits& units_;
  StepData<D> data_;
  Grid<D> grid_;
  std::unique_ptr<ImmersedBoundaryTransfer<D>> ib_;
  std::unique_ptr<FluidStage<D>> fluid_;
  std::unique_ptr<ElectricStage<D>> electric_;  // only with a field
  std::unique_ptr<MembraneStage<D>> membrane_;
  std::vector<std::unique_ptr<ForceTermStage<D>>> force_terms_;  // active force terms
  std::unique_ptr<SpreadStage<D>> spread_;
  std::unique_ptr<StepStage> viscosity_;  // 2D, only with V != 1
  std::unique_ptr<MarkerStage<D>> markers_;
  std::unique_ptr<DiagnosticsStage<D>> diagnostics_;
  std::vector<double> empty_;
  std::vector<std::array<int, 3>> no_triangles_;
};

}  // namespace

std::unique_ptr<CoupledStep> BuildCoupledStep(const Scene& scene, const LatticeUnits& units,
                                              SimulationState& state) {
  if (scene.dimension == 3) return std::make_unique<CoupledStepOf<3>>(scene, units, state);
  return std::make_unique<CoupledStepOf<2>>(scene, units, state);
}

}  // namespace ehd
