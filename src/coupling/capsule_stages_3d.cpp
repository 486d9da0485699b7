// The 3D coupled step's stages (see capsule_stages_3d.h): a triangulated capsule in the D3Q19
// fluid, coupled by the 3D cosine-delta immersed boundary (song2019 sec. 3.2 and 3.4, ch. 6).
#include "ehd_capsule/coupling/capsule_stages_3d.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ehd_capsule/electric/leaky_dielectric_solver_3d.h"
#include "ehd_capsule/geometry/mesh_relaxation.h"
#include "ehd_capsule/membrane/membrane_stability.h"

namespace ehd {
namespace {

SurfaceLaw LawOf(const Scene& s) {
  switch (s.law) {
    case SurfaceLawKind::kSkalak:
      return SurfaceLaw::kSkalak;
    case SurfaceLawKind::kZeroThickness:
      return SurfaceLaw::kZeroThickness;
    case SurfaceLawKind::kNeoHookean:
      break;
  }
  return SurfaceLaw::kNeoHookean;
}

MarkerIntegrator IntegratorOf(const Scene& scene) {
  return scene.numerics.integrator == MarkerTimeScheme::kAdamsBashforth2
             ? MarkerIntegrator::kAdamsBashforth2
             : MarkerIntegrator::kForwardEuler;
}

}  // namespace

TriangleMesh InitialSurface(const Scene& s, const LatticeUnits& u) {
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
  return mesh;
}

void MembraneSurface3D::ResetTo(const Eigen::Matrix3Xd& positions) {
  mesh.SetVertices(positions);
  const Eigen::Index n = positions.cols();
  U.setZero(3, n);
  elastic_force.setZero(3, n);
  bending_force.setZero(3, n);
  force.setZero(3, n);
  electric_force.setZero(3, n);
  electric_traction.setZero(3, n);
  initial_volume = EnclosedVolume(mesh);
  initial_area = SurfaceArea(mesh);
  volume_corrected = 0.0;
}

// ---------------------------------------------------------------------------------------------
// Electric stage: as the 2D ElectricStage2D (electric_stage.cpp), with the 3D solver; the
// potential may be re-solved less often than every step (numerics.electric_every,
// numerics.electric_move_tolerance), reusing the force at the (material) vertices in between.

ElectricStage3D::ElectricStage3D(const Scene& scene, const LatticeUnits& units, const Grid3D& grid,
                                 MembraneSurface3D& body)
    : scene_(scene), body_(body) {
  solver_ = std::make_unique<LeakyDielectricSolver3D>(grid, units.sigma_minus, units.sigma_plus,
                                                      units.eps_minus, units.eps_plus);
}

ElectricStage3D::~ElectricStage3D() = default;

std::string ElectricStage3D::Describe() const {
  std::ostringstream out;
  out << "3D fast IIM leaky dielectric, sigma-/sigma+ = " << scene_.sigma_r
      << ", eps-/eps+ = " << scene_.eps_r << ", E_inf = (0, 0, -" << body_.field
      << ") (phi = E z on the z faces, Neumann x, y: song2019 ch. 6), solved every "
      << scene_.numerics.electric_every << " step(s)";
  if (scene_.numerics.electric_move_tolerance > 0) {
    out << " or after a move > " << scene_.numerics.electric_move_tolerance << " h";
    if (scene_.numerics.electric_shape_tolerance > 0) {
      out << " that takes the surface more than " << scene_.numerics.electric_shape_tolerance
          << " h off the solved one (smaller moves re-interpolate the solved traction)";
    }
  }
  out << ", force [M_E].n A_i per vertex";
  return out.str();
}

void ElectricStage3D::Reset() {
  const int n = body_.mesh.vertex_count();
  body_.electric_force.setZero(3, n);
  body_.electric_traction.setZero(3, n);
  solver_->set_warm_start(LeakyDielectricSolver3D::WarmStart());
  last_solve_step_ = -1;
  solved_field_ = -1.0;
  solved_vertices_.resize(3, 0);
  solved_traction_.resize(3, 0);
  projector_.reset();
}

bool ElectricStage3D::ReinterpolateTraction(double tolerance) {
  if (!projector_) {
    TriangleMesh solved = body_.mesh;
    solved.SetVertices(solved_vertices_);
    projector_ = std::make_unique<SurfaceProjector>(solved, 1.0);
  }
  const Eigen::Matrix3Xd& x = body_.mesh.vertices();
  // The feet first, stopping at the first vertex off the solved surface: a shape still changing
  // fails at once and costs little beyond the solve it triggers.
  feet_.resize(x.cols());
  for (int v = 0; v < x.cols(); ++v) {
    feet_[v] = projector_->Closest(x.col(v));
    if (feet_[v].distance > tolerance) return false;
  }
  const auto& triangles = body_.mesh.triangles();
  const SurfaceGeometry geometry = MeasureSurface(body_.mesh);
  for (int v = 0; v < x.cols(); ++v) {
    const SurfacePoint& foot = feet_[v];
    const auto& t = triangles[foot.triangle];
    const Eigen::Vector3d traction = foot.barycentric(0) * solved_traction_.col(t[0]) +
                                     foot.barycentric(1) * solved_traction_.col(t[1]) +
                                     foot.barycentric(2) * solved_traction_.col(t[2]);
    body_.electric_traction.col(v) = traction;
    body_.electric_force.col(v) = traction * geometry.vertex_area[v];
  }
  return true;
}

const std::vector<double>& ElectricStage3D::potential() const { return solver_->potential(); }

void ElectricStage3D::Run(long step) {
  SimulationState& state = *body_.state;
  state.gmres_iterations = 0;
  const int n = body_.mesh.vertex_count();
  if (!(body_.field > 0.0)) {
    body_.electric_force.setZero(3, n);
    body_.electric_traction.setZero(3, n);
    solved_field_ = 0.0;
    return;
  }
  bool solve = last_solve_step_ < 0 || solved_field_ != body_.field ||
               step - last_solve_step_ >= scene_.numerics.electric_every;
  if (!solve && scene_.numerics.electric_move_tolerance > 0.0) {
    const double tol = scene_.numerics.electric_move_tolerance;
    const bool moved =
        (body_.mesh.vertices() - vertices_at_last_solve_).colwise().squaredNorm().maxCoeff() >
        tol * tol;
    if (moved && scene_.numerics.electric_shape_tolerance > 0.0) {
      // The vertices moved; if the surface did not (tank-treading along a steady shape), the
      // solved traction field, re-interpolated at the moved vertices, is still the answer.
      // (If the surface did move, the solve below replaces the re-interpolated forces.)
      if (ReinterpolateTraction(scene_.numerics.electric_shape_tolerance)) {
        vertices_at_last_solve_ = body_.mesh.vertices();
        return;
      }
    }
    solve = moved;
  }
  if (!solve) return;
  solver_->SetAppliedField(body_.field);
  InterfaceSolveReport report;
  try {
    report = solver_->Solve(body_.mesh, static_cast<double>(step));
  } catch (const std::exception& e) {
    FailStep(step, std::string("electric potential solve failed: ") + e.what());
  }
  state.gmres_iterations = report.iterations;
  state.gmres_residual = report.residual;
  body_.electric_force = solver_->force();
  body_.electric_traction = solver_->traction();
  vertices_at_last_solve_ = body_.mesh.vertices();
  last_solve_step_ = step;
  solved_field_ = body_.field;
  if (scene_.numerics.electric_shape_tolerance > 0.0) {
    solved_vertices_ = body_.mesh.vertices();
    solved_traction_ = body_.electric_traction;
    projector_.reset();
  }
}

void ElectricStage3D::Save(CheckpointWriter& w) const {
  const LeakyDielectricSolver3D::WarmStart& h = solver_->warm_start();
  w.Pod(solver_->applied_field());
  w.Vec(h.g);
  w.Vec(h.g_previous);
  w.Pod(h.time_previous);
  w.Pod(h.time_last);
  w.Mat(body_.electric_force);
  w.Mat(body_.electric_traction);
  w.Mat(vertices_at_last_solve_);
  w.Pod(last_solve_step_);
  w.Pod(solved_field_);
  w.Mat(solved_vertices_);
  w.Mat(solved_traction_);
}

void ElectricStage3D::Restore(CheckpointReader& r) {
  solver_->SetAppliedField(r.Pod<double>());
  LeakyDielectricSolver3D::WarmStart h;
  h.g = r.Vec();
  h.g_previous = r.Vec();
  h.time_previous = r.Pod<double>();
  h.time_last = r.Pod<double>();
  solver_->set_warm_start(h);
  body_.electric_force = r.Mat<3>();
  body_.electric_traction = r.Mat<3>();
  vertices_at_last_solve_ = r.Mat<3>();
  last_solve_step_ = r.Pod<long>();
  solved_field_ = r.Pod<double>();
  solved_vertices_ = r.Mat<3>();
  solved_traction_ = r.Mat<3>();
  projector_.reset();  // rebuilt from solved_vertices_ when needed
}

// ---------------------------------------------------------------------------------------------

MembraneStage3D::MembraneStage3D(const Scene& scene, const LatticeUnits& units,
                                 MembraneSurface3D& body)
    : body_(body), modulus_(units.tension) {
  // Vertices farther apart than 2 h leave holes the immersed boundary leaks through (the 4-point
  // kernel's support is 4 h): refuse the scene, naming the subdivision that closes them (each
  // level halves the edges).
  {
    const MeshQuality q = MeasureQuality(body.mesh);
    if (q.max_edge > 2.0) {
      int need = scene.mesh_subdivisions;
      double edge = q.max_edge;
      while (edge > 2.0 && need < 6) {
        edge *= 0.5;
        ++need;
      }
      throw SceneError("scene " + scene.name +
                       ": the membrane mesh is too coarse for the grid: " + "longest edge " +
                       FormatValue(q.max_edge) + " h > 2 h (a = " + FormatValue(units.radius) +
                       " cells); set mesh_subdivisions >= " + std::to_string(need) + " (now " +
                       std::to_string(scene.mesh_subdivisions) + ")");
    }
  }
  if (scene.membrane == MembraneKind::kDrop) {
    tension_ = units.tension;
    const MeshQuality q = MeasureQuality(body.mesh);
    const MembraneStabilityLimits limits =
        EstimateMembraneStability(tension_, 0.0, 0.0, 0.0, units.viscosity, 1.0, q.min_edge);
    const double dt_stable =
        limits.min_dt() *
        (scene.numerics.integrator == MarkerTimeScheme::kForwardEuler ? 2.0 : 1.0);
    if (dt_stable < 1.0) {
      throw SceneError("scene " + scene.name +
                       ": membrane explicit limit exceeded by the tension (Ca) term: stable "
                       "lattice dt " +
                       FormatValue(dt_stable) + " < 1; set numerics.membrane_substeps >= " +
                       std::to_string(static_cast<int>(
                           std::ceil(scene.numerics.membrane_substeps / dt_stable))));
    }
    stability_ = "explicit limit dt <= " + FormatValue(dt_stable);
    return;
  }
  SurfaceLawParameters law;
  law.law = LawOf(scene);
  law.shear_modulus = units.tension;  // G_s
  law.area_dilation = scene.law == SurfaceLawKind::kSkalak ? scene.area_dilation : 1.0;
  elasticity_ = std::make_unique<SurfaceElasticity>(law, body.mesh);
  if (scene.E_b > 0.0) {
    bending_ = std::make_unique<HelfrichBending>(
        HelfrichParameters{units.bending_modulus, scene.c0 / units.radius});
  }
  // Explicit limit at the initial shape (membrane_stability.h): a planar membrane mode of
  // wavenumber k relaxes at S k^(p-1) phi_hat(k h)^2 / (4 mu) in 3D as in 2D, with the in-plane
  // stiffness S = 4 G_s (neo-Hookean, zero-thickness: tension G_s (4 e_1 + 2 e_2)) or
  // (2 + 2C) G_s (Skalak), and S = E_B for bending (p = 4); k up to pi / (shortest edge).
  const MeshQuality q = MeasureQuality(body.mesh);
  const double stiffness =
      units.tension *
      (scene.law == SurfaceLawKind::kSkalak ? 2.0 + 2.0 * scene.area_dilation : 4.0);
  const MembraneStabilityLimits limits =
      EstimateMembraneStability(0.0, stiffness, bending_ ? units.bending_modulus : 0.0, 0.0,
                                units.viscosity, 1.0, q.min_edge);
  const double dt_stable =
      limits.min_dt() * (scene.numerics.integrator == MarkerTimeScheme::kForwardEuler ? 2.0 : 1.0);
  if (dt_stable < 1.0) {
    const int need = static_cast<int>(std::ceil(scene.numerics.membrane_substeps / dt_stable));
    const char* term =
        limits.bending_dt == limits.min_dt() ? "bending (E_b)" : "elasticity (Ca, C)";
    throw SceneError("scene " + scene.name + ": membrane explicit limit exceeded by the " + term +
                     " term: stable lattice dt " + FormatValue(dt_stable) + " < 1 (" +
                     elasticity_->Describe() + ", shortest edge " + FormatValue(q.min_edge) +
                     " h); set numerics.membrane_substeps >= " + std::to_string(need) + " (now " +
                     std::to_string(scene.numerics.membrane_substeps) + ")");
  }
  stability_ = "explicit limit dt <= " + FormatValue(dt_stable);
}

std::vector<double> MembraneStage3D::VertexTension() const {
  if (!elasticity_) return std::vector<double>(body_.mesh.vertex_count(), 1.0);
  std::vector<double> tension = elasticity_->VertexMeanTension(body_.mesh.vertices());
  for (double& t : tension) t /= modulus_;
  return tension;
}

std::string MembraneStage3D::Describe() const {
  if (!elasticity_) {
    return "drop: surface tension gamma = " + FormatValue(tension_) +
           ", force gamma (Delta x)_i A_i (cotangent mean-curvature normal); " + stability_ +
           "\nmesh: " + MeasureQuality(body_.mesh).Describe();
  }
  std::string d = elasticity_->Describe();
  if (bending_) d += ", " + bending_->Describe();
  return d + "; " + stability_ + "\nmesh: " + MeasureQuality(body_.mesh).Describe();
}

void MembraneStage3D::Run(long step) {
  if (!elasticity_) {
    const SurfaceGeometry g = MeasureSurface(body_.mesh);
    for (int v = 0; v < body_.mesh.vertex_count(); ++v) {
      body_.force.col(v) = tension_ * g.vertex_area[v] * g.laplace_position.col(v);
    }
    if (body_.electric_force.cols() == body_.force.cols()) body_.force += body_.electric_force;
    return;
  }
  try {
    elasticity_->ComputeForces(body_.mesh.vertices(), body_.elastic_force);
  } catch (const std::exception& e) {
    FailStep(step, std::string("membrane: ") + e.what());
  }
  body_.force = body_.elastic_force;
  if (bending_) {
    bending_->ComputeForces(body_.mesh, body_.bending_force);
    body_.force += body_.bending_force;
  }
  if (body_.electric_force.cols() == body_.force.cols()) body_.force += body_.electric_force;
}

// ---------------------------------------------------------------------------------------------

SpreadStage3D::SpreadStage3D(const ImmersedBoundary3D& ib, MembraneSurface3D& body,
                             LatticeBoltzmann3D& fluid)
    : ib_(ib), body_(body), fluid_(fluid) {}

std::string SpreadStage3D::Describe() const {
  return "cosine delta (eq. 103) as a product in 3D, spread the vertex forces";
}

void SpreadStage3D::Run(long) {
  fluid_.ClearForce();
  ib_.Spread(body_.mesh.vertices(), body_.force,
             {&fluid_.force(0), &fluid_.force(1), &fluid_.force(2)});
}

// ---------------------------------------------------------------------------------------------

FluidStage3D::FluidStage3D(const Scene& scene, const LatticeUnits& units, MembraneSurface3D& body)
    : scene_(scene), units_(units), body_(body) {
  LbmParameters p;
  p.nx = units.nx;
  p.ny = units.ny;
  p.nz = units.nz;
  p.viscosity = units.viscosity;
  p.threads = scene.numerics.threads;
  p.boundary = scene.has_shear() ? FluidBoundary::kShearWalls : FluidBoundary::kClosedBox;
  // song2019 sec. 3.1.2: the heat fluxes (and the bulk rate) follow the shear rate, the
  // higher-order moments relax at 1.8.
  const double s_nu = 1.0 / (3.0 * units.viscosity + 0.5);
  p.s_e = s_nu;
  p.s_q = s_nu;
  p.s_epsilon = 1.8;
  p.s_pi = 1.8;
  p.s_m = 1.8;
  lattice_ = std::make_unique<LatticeBoltzmann3D>(p);
}

std::string FluidStage3D::Describe() const {
  std::ostringstream out;
  out << "D3Q19 MRT LBM ";
  if (units_.nx == units_.ny) {
    out << units_.ny << "^3";
  } else {
    out << units_.nx << " x " << units_.ny << " x " << units_.nz;
  }
  out << ", tau = " << units_.tau << " (s_e = s_q = s_nu, s_eps = s_pi = s_m = 1.8), "
      << (scene_.has_shear() ? "moving shear walls, periodic x and z" : "closed box at rest");
  return out.str();
}

void FluidStage3D::Reset() {
  lattice_->ClearViscosityField();
  if (scene_.has_shear()) {
    lattice_->InitializeShear(body_.shear_rate);
  } else {
    lattice_->InitializeAtRest();
  }
  lattice_->ClearForce();
}

void FluidStage3D::ApplyShearRate() {
  lattice_->SetWallVelocities(-body_.shear_rate * units_.half_width,
                              body_.shear_rate * units_.half_width);
}

void FluidStage3D::Run(long step) {
  lattice_->Step();
  SimulationState& state = *body_.state;
  state.max_mach = MaxLatticeMach(
      step, {&lattice_->velocity(0), &lattice_->velocity(1), &lattice_->velocity(2)});
  if (state.max_mach > scene_.numerics.max_mach) {
    FailStep(step, "lattice Mach number " + FormatValue(state.max_mach) + " > " +
                       FormatValue(scene_.numerics.max_mach) +
                       " (numerics.max_mach); largest membrane force per vertex " +
                       FormatValue(body_.force.colwise().norm().maxCoeff()));
  }
}

void FluidStage3D::Save(CheckpointWriter& w) const {
  w.Pod(lattice_->step());
  w.Vec(lattice_->populations());
  for (int a = 0; a < 3; ++a) w.Vec(lattice_->force(a));
}

void FluidStage3D::Restore(CheckpointReader& r) {
  const long step = r.Pod<long>();
  const std::vector<double> f = r.Vec();
  for (int a = 0; a < 3; ++a) lattice_->force(a) = r.Vec();
  lattice_->SetPopulations(f);
  lattice_->SetStep(step);
  if (scene_.has_shear()) ApplyShearRate();
}

// ---------------------------------------------------------------------------------------------

MarkerStage3D::MarkerStage3D(const Scene& scene, const Grid3D& grid, const ImmersedBoundary3D& ib,
                             MembraneSurface3D& body, const LatticeBoltzmann3D& fluid)
    : scene_(scene),
      grid_(grid),
      ib_(ib),
      body_(body),
      fluid_(fluid),
      advector_(IntegratorOf(scene)) {
  if (scene.numerics.marker_filter_every > 0) {
    filter_ = std::make_unique<MeshScaleFilter>(body.mesh,  // the rest mesh
                                                scene.numerics.mesh_filter_order);
  }
}

std::string MarkerStage3D::Describe() const {
  std::string text =
      std::string(scene_.membrane == MembraneKind::kDrop
                      ? "interpolate u at the vertices, move them with its normal part and the "
                        "mean (a drop's vertices are not material), "
                      : "interpolate u at the vertices, ") +
      (advector_.scheme() == MarkerIntegrator::kAdamsBashforth2 ? "Adams-Bashforth 2"
                                                                : "forward Euler");
  if (filter_) {
    text += ", mesh-scale filter of the deformation (order " + std::to_string(filter_->order()) +
            ") every " + std::to_string(scene_.numerics.marker_filter_every) + " steps";
  }
  if (scene_.numerics.volume_correction_every > 0) {
    text +=
        ", the enclosed volume restored to its initial value (a uniform normal displacement) "
        "every " +
        std::to_string(scene_.numerics.volume_correction_every) + " steps";
  }
  if (scene_.numerics.relax_mesh_every > 0) {
    text += ", vertices relaxed along the surface every " +
            std::to_string(scene_.numerics.relax_mesh_every) + " steps";
  }
  return text;
}

void MarkerStage3D::Run(long step) {
  ib_.Interpolate({&fluid_.velocity(0), &fluid_.velocity(1), &fluid_.velocity(2)},
                  body_.mesh.vertices(), body_.U);
  scratch_ = body_.mesh.vertices();
  if (scene_.membrane == MembraneKind::kDrop) {
    advector_.Advance(DropVertexVelocity(body_.mesh, body_.U), 1.0, scratch_);
  } else {
    advector_.Advance(body_.U, 1.0, scratch_);
  }
  if (filter_ && step % scene_.numerics.marker_filter_every == 0) filter_->Apply(scratch_);
  if (scene_.numerics.volume_correction_every > 0 &&
      step % scene_.numerics.volume_correction_every == 0 && scratch_.allFinite()) {
    // The immersed boundary's leak (its interpolated velocity is not exactly divergence-free at
    // the surface) changes the enclosed volume slowly; an incompressible inside keeps it.
    const double before = EnclosedVolume(scratch_, body_.mesh.triangles());
    try {
      RestoreEnclosedVolume(body_.mesh.triangles(), body_.initial_volume, scratch_);
    } catch (const std::exception& e) {
      FailStep(step, std::string("volume correction failed: ") + e.what());
    }
    body_.volume_corrected += (body_.initial_volume - before) / body_.initial_volume;
  }
  if (scene_.has_shear()) WrapSurfaceIntoDomain(grid_, {true, false, true}, scratch_);
  if (!scratch_.allFinite()) FailStep(step, "vertex position is not finite (NaN/Inf)");
  const double margin = 2.0 * grid_.h;
  for (int k = 0; k < scratch_.cols(); ++k) {
    for (int a = 0; a < 3; ++a) {
      if (a != 1 && scene_.has_shear()) continue;  // periodic axes
      const double v = scratch_(a, k), lo = grid_.origin(a),
                   hi = grid_.origin(a) + grid_.extent(a) * grid_.h;
      if (v < lo + margin || v > hi - margin) {
        FailStep(step, "vertex " + std::to_string(k) + " at " + std::string(1, "xyz"[a]) + " = " +
                           FormatValue(v) + " is within 2h of the wall " +
                           std::string(1, "xyz"[a]) + " = " + FormatValue(v < 0 ? lo : hi) +
                           " (the membrane left the domain)");
      }
    }
  }
  body_.mesh.SetVertices(scratch_);
  if (scene_.numerics.relax_mesh_every > 0 && step % scene_.numerics.relax_mesh_every == 0) {
    RelaxMeshTangentially(body_.mesh, 1, 0.5, grid_.h);
  }
}

void MarkerStage3D::Save(CheckpointWriter& w) const {
  w.Mat(advector_.previous_velocity());
  w.Pod(static_cast<std::int32_t>(advector_.has_previous_velocity()));
  if (scene_.numerics.volume_correction_every > 0) w.Pod(body_.volume_corrected);
}

void MarkerStage3D::Restore(CheckpointReader& r) {
  const Eigen::Matrix3Xd previous = r.Mat<3>();
  const bool has_previous = r.Pod<std::int32_t>() != 0;
  if (has_previous && previous.cols() != body_.mesh.vertex_count()) {
    r.Fail("vertex velocity count differs");
  }
  advector_.SetPreviousVelocity(previous, has_previous);
  if (scene_.numerics.volume_correction_every > 0) body_.volume_corrected = r.Pod<double>();
}

// ---------------------------------------------------------------------------------------------

DiagnosticsStage3D::DiagnosticsStage3D(const Scene& scene, const LatticeUnits& units,
                                       MembraneSurface3D& body, const LatticeBoltzmann3D& fluid,
                                       bool electric)
    : scene_(scene), units_(units), body_(body), fluid_(fluid), electric_(electric), tracker_(0) {}

std::string DiagnosticsStage3D::Describe() const {
  std::ostringstream out;
  out << "D_xy and inclination of the equivalent ellipsoid in the shear plane, tank-treading "
         "phase of vertex "
      << body_.tracked_vertex << "; watchdogs: non-finite values, Mach > "
      << scene_.numerics.max_mach << ", |volume drift| > " << scene_.numerics.area_drift_limit
      << ", a vertex within 2h of a wall";
  return out.str();
}

void DiagnosticsStage3D::MeasureInto(const ShapeDiagnostics3D& d, SimulationState& s) const {
  s.dimension = 3;
  s.markers = body_.mesh.vertices();
  if (electric_) {
    s.electric_force = body_.electric_traction;
    s.electric_force_total = body_.electric_force.rowwise().sum();
  } else {
    s.electric_force.resize(3, 0);
  }
  s.dxy = d.dxy;
  s.inclination = d.inclination;
  s.area = d.volume;
  s.area_drift = d.volume / body_.initial_volume - 1.0;
  s.surface_drift = d.area / body_.initial_area - 1.0;
  s.volume_corrected = body_.volume_corrected;
  s.d_field = d.dz;
  // body_.U: the vertex velocities of the last marker step (lattice units), none before it.
  s.surface_flow = body_.U.cols() == body_.mesh.vertex_count()
                       ? MeasureMeridionalFlow(body_.mesh, body_.U, d.centroid) *
                             units_.steps_per_time_unit / units_.radius
                       : 0.0;
  s.tt_phase = tracker_.phase();
}

void DiagnosticsStage3D::Reset() {
  // The tank-treading vertex: the one farthest along +x on the equator z = z_c.
  const ShapeDiagnostics3D d = MeasureShape3D(body_.mesh);
  const Eigen::Matrix3Xd& x = body_.mesh.vertices();
  int best = 0;
  double best_score = -1e300;
  for (int k = 0; k < x.cols(); ++k) {
    const double score = (x(0, k) - d.centroid.x()) - 10.0 * std::abs(x(2, k) - d.centroid.z());
    if (score > best_score) {
      best_score = score;
      best = k;
    }
  }
  body_.tracked_vertex = best;
  initial_min_angle_ = MeasureQuality(body_.mesh).min_angle_deg;
  tracker_ = TankTreadingTracker(0);
  const Eigen::Vector3d r = x.col(best) - d.centroid;
  tracker_.UpdateRelative(0.0, Eigen::Vector2d(r.x(), r.y()), d.inclination);
  MeasureInto(d, *body_.state);
  body_.state->area_drift = 0.0;
}

void DiagnosticsStage3D::Run(long step) {
  SimulationState& s = *body_.state;
  ShapeDiagnostics3D d;
  try {
    d = MeasureShape3D(body_.mesh);
  } catch (const std::exception& e) {
    FailStep(step, e.what());
  }
  // The watchdog sees the leak itself: the drift plus what the volume correction restored.
  const double drift = d.volume / body_.initial_volume - 1.0 - body_.volume_corrected;
  if (!std::isfinite(drift) || std::abs(drift) > scene_.numerics.area_drift_limit) {
    // The usual cause is an edge longer than 2 h: the immersed boundary leaks through the gap.
    const MeshQuality q = MeasureQuality(body_.mesh);
    FailStep(step, "enclosed volume drifted by " + FormatValue(100.0 * drift) + "%" +
                       (body_.volume_corrected != 0.0 ? " (before the volume correction)" : "") +
                       " (limit " + FormatValue(100.0 * scene_.numerics.area_drift_limit) +
                       "%, numerics.area_drift_limit); " + q.Describe() +
                       (q.max_edge > 2.0 ? " (edges > 2 h leak: raise mesh_subdivisions)" : ""));
  }
  // Mesh-scale instability: vertices closer than a grid cell carry modes the immersed boundary
  // cannot see, which can grow until triangles fold (the 3D counterpart of the 2D markers'
  // sawtooth mode). Every 20 steps, a triangle angle below 5 degrees stops the run naming it,
  // before the fold becomes a NaN or a Mach blow-up.
  if (step % 20 == 0) {
    const MeshQuality q = MeasureQuality(body_.mesh);
    if (q.min_angle_deg < 5.0) {
      FailStep(step, "membrane mesh degenerating: smallest triangle angle " +
                         FormatValue(q.min_angle_deg) + " deg (initially " +
                         FormatValue(initial_min_angle_) +
                         "): triangles folding (a mesh-scale instability: use fewer vertices per "
                         "grid cell, i.e. mesh_subdivisions lower or N higher, or more bending "
                         "E_b) or stretched beyond use (the mesh is not refined as it stretches: "
                         "lower Ca or raise mesh_subdivisions); " +
                         q.Describe());
    }
  }
  const double time = s.time + (scene_.has_shear() ? body_.shear_rate : units_.dt);
  const Eigen::Vector3d r = body_.mesh.vertices().col(body_.tracked_vertex) - d.centroid;
  tracker_.UpdateRelative(time, Eigen::Vector2d(r.x(), r.y()), d.inclination);
  s.step = step;
  s.time = time;
  MeasureInto(d, s);
}

void DiagnosticsStage3D::Save(CheckpointWriter& w) const {
  w.Pod(static_cast<std::int32_t>(body_.tracked_vertex));
  w.Pod(tracker_.snapshot());
}

void DiagnosticsStage3D::Restore(CheckpointReader& r) {
  body_.tracked_vertex = r.Pod<std::int32_t>();
  tracker_.Restore(r.Pod<TankTreadingTracker::Snapshot>());
  SimulationState& s = *body_.state;
  MeasureInto(MeasureShape3D(body_.mesh), s);
  s.max_mach = fluid_.MaxSpeed() / kLatticeSoundSpeed;
}

}  // namespace ehd
