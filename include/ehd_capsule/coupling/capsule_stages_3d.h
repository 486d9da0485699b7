// The stages of the 3D coupled step of one capsule with a triangulated membrane, and the surface
// data they share. Same contract as the 2D stages (step_stage.h):
//   electric     3D fast IIM potential (E_inf along z, song2019 ch. 6) and the Maxwell force per
//                vertex (only with a field)
//   membrane     finite-element elastic forces (+ Helfrich bending) per vertex, plus the electric
//                force; for a drop the
//                surface tension gamma (Delta x)_i A_i = -2 gamma H_i n_i A_i (cotangent)
//   spread       the vertex forces to the grid (eq. (106) with the 3D cosine delta)
//   fluid        one D3Q19 MRT LBM step, walls y = +-L moving at +-k L, periodic in x and z
//   markers      interpolate u (eq. (104)), advance, wrap periodically, check the walls
//   diagnostics  volume and mesh-quality watchdogs, equivalent-ellipsoid D_xy and inclination,
//                tank-treading
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/simulation_state.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/diagnostics/shape_diagnostics_3d.h"
#include "ehd_capsule/diagnostics/tank_treading.h"
#include "ehd_capsule/geometry/surface_projection.h"
#include "ehd_capsule/geometry/triangle_mesh.h"
#include "ehd_capsule/ib/immersed_boundary.h"
#include "ehd_capsule/ib/marker_update.h"
#include "ehd_capsule/ib/mesh_scale_filter.h"
#include "ehd_capsule/lbm/lattice_boltzmann.h"
#include "ehd_capsule/membrane/helfrich_bending.h"
#include "ehd_capsule/membrane/surface_elasticity.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

// The membrane surface and what the stages exchange on it in one step.
struct MembraneSurface3D {
  TriangleMesh mesh;         // current vertex positions (lattice units, stored unwrapped)
  Eigen::Matrix3Xd initial;  // the scene's initial shape
  Eigen::Matrix3Xd U;        // velocity interpolated this step
  Eigen::Matrix3Xd elastic_force, bending_force, force;  // per vertex (forces, not densities)
  Eigen::Matrix3Xd electric_force, electric_traction;  // per vertex / per unit area (with a field)
  double field = 0;                                    // |E_inf| in effect (lattice units)
  double initial_volume = 0;
  double initial_area = 0;  // surface area of the initial shape
  // The volume restored by numerics.volume_correction_every so far / initial_volume.
  double volume_corrected = 0;
  int tracked_vertex = 0;  // the material vertex whose angle is the tank-treading phase
  double shear_rate = 0;   // k in effect
  SimulationState* state = nullptr;

  void ResetTo(const Eigen::Matrix3Xd& positions);
};

class LeakyDielectricSolver3D;

class ElectricStage3D : public StepStage {
 public:
  // The electric grid is the lattice's (cell-centred nodes, the box faces half a cell out).
  ElectricStage3D(const Scene& scene, const LatticeUnits& units, const Grid3D& grid,
                  MembraneSurface3D& body);
  ~ElectricStage3D() override;
  const char* name() const override { return "electric"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;
  const std::vector<double>& potential() const;

 private:
  const Scene& scene_;
  MembraneSurface3D& body_;
  // If every vertex lies within `tolerance` cells of the last solve's surface, re-interpolates
  // that solve's traction at the current vertices (closest points on the solved surface,
  // barycentric weights), sets the forces from it and returns true. Otherwise returns false at
  // the first vertex beyond it, the forces untouched (a re-solve follows).
  bool ReinterpolateTraction(double tolerance);

  std::unique_ptr<LeakyDielectricSolver3D> solver_;
  Eigen::Matrix3Xd vertices_at_last_solve_;  // at the last force update (solve or re-interpolation)
  long last_solve_step_ = -1;
  double solved_field_ = -1.0;
  // The surface and traction of the last solve (numerics.electric_shape_tolerance > 0).
  Eigen::Matrix3Xd solved_vertices_, solved_traction_;
  std::unique_ptr<SurfaceProjector> projector_;  // of the solved surface, rebuilt on demand
  std::vector<SurfacePoint> feet_;               // ReinterpolateTraction scratch
};

class MembraneStage3D : public StepStage {
 public:
  // Throws SceneError if the explicit step is unstable at the initial shape (naming the term
  // and the numerics.membrane_substeps needed), as in 2D.
  MembraneStage3D(const Scene& scene, const LatticeUnits& units, MembraneSurface3D& body);
  const char* name() const override { return "membrane"; }
  std::string Describe() const override;
  void Reset() override {}
  void Run(long step) override;
  void Save(CheckpointWriter&) const override {}  // a function of the vertex positions
  void Restore(CheckpointReader&) override {}
  // The in-plane mean principal tension (tau_1 + tau_2) / 2 at each vertex of the present
  // shape, in units of the scene's modulus (a drop: gamma, so 1 everywhere).
  std::vector<double> VertexTension() const;

 private:
  MembraneSurface3D& body_;
  double modulus_ = 1;                             // units.tension (lattice)
  std::unique_ptr<SurfaceElasticity> elasticity_;  // capsule
  std::unique_ptr<HelfrichBending> bending_;       // capsule with E_b > 0
  double tension_ = 0;                             // drop: surface tension gamma
  std::string stability_;
};

class SpreadStage3D : public StepStage {
 public:
  SpreadStage3D(const ImmersedBoundary3D& ib, MembraneSurface3D& body, LatticeBoltzmann3D& fluid);
  const char* name() const override { return "spread"; }
  std::string Describe() const override;
  void Reset() override {}
  void Run(long step) override;
  void Save(CheckpointWriter&) const override {}
  void Restore(CheckpointReader&) override {}

 private:
  const ImmersedBoundary3D& ib_;
  MembraneSurface3D& body_;
  LatticeBoltzmann3D& fluid_;
};

class FluidStage3D : public StepStage {
 public:
  FluidStage3D(const Scene& scene, const LatticeUnits& units, MembraneSurface3D& body);
  const char* name() const override { return "fluid"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;
  LatticeBoltzmann3D& lattice() { return *lattice_; }
  const LatticeBoltzmann3D& lattice() const { return *lattice_; }
  void ApplyShearRate();

 private:
  const Scene& scene_;
  const LatticeUnits& units_;
  MembraneSurface3D& body_;
  std::unique_ptr<LatticeBoltzmann3D> lattice_;
};

class MarkerStage3D : public StepStage {
 public:
  MarkerStage3D(const Scene& scene, const Grid3D& grid, const ImmersedBoundary3D& ib,
                MembraneSurface3D& body, const LatticeBoltzmann3D& fluid);
  const char* name() const override { return "markers"; }
  std::string Describe() const override;
  void Reset() override { advector_.Reset(); }
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

 private:
  const Scene& scene_;
  Grid3D grid_;
  const ImmersedBoundary3D& ib_;
  MembraneSurface3D& body_;
  const LatticeBoltzmann3D& fluid_;
  PointAdvector<3> advector_;
  Eigen::Matrix3Xd scratch_;
  // The mesh-scale filter of the deformation (numerics.marker_filter_every > 0), built on the
  // rest mesh.
  std::unique_ptr<MeshScaleFilter> filter_;
};

class DiagnosticsStage3D : public StepStage {
 public:
  DiagnosticsStage3D(const Scene& scene, const LatticeUnits& units, MembraneSurface3D& body,
                     const LatticeBoltzmann3D& fluid, bool electric);
  const char* name() const override { return "diagnostics"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

 private:
  void MeasureInto(const ShapeDiagnostics3D& d, SimulationState& s) const;
  const Scene& scene_;
  const LatticeUnits& units_;
  MembraneSurface3D& body_;
  const LatticeBoltzmann3D& fluid_;
  bool electric_;
  TankTreadingTracker tracker_;
  double initial_min_angle_ = 0;  // of the initial mesh, for the degeneration watchdog
};

// The scene's initial vertex positions (lattice units) on the icosphere of its subdivision.
TriangleMesh InitialSurface(const Scene& scene, const LatticeUnits& units);

}  // namespace ehd
