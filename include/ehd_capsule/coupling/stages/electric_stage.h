// The electric stage: the leaky-dielectric potential by the fast immersed interface method
// (2D: song2019 ch. 4; 3D: ch. 6, E_inf along z), warm-started, and the Maxwell-stress force
// [M_E] . n at the points (eq. (148)), written into the body's "electric" force source (2D:
// per unit length; 3D: per vertex, with the traction per unit area for output). Built only with
// a field; takes one body (the fast IIM solves one interface).
//
// Departure from the text: the potential may be re-solved less often than every step
// (numerics.electric_every; numerics.electric_move_tolerance), reusing the force at the
// (material) points in between; in 3D moves that keep the surface within
// numerics.electric_shape_tolerance of the solved one re-interpolate the solved traction. A field
// that changes in time (electric.waveform) scales the last solve's force by (E(t) / E_solved)^2
// between solves (exact for the quasi-static leaky dielectric, whose G is linear in E).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/dimension_traits.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/geometry/surface_projection.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

template <int D>
class ElectricStage : public StepStage {
 public:
  // The electric grid is the lattice's (cell-centred nodes, the box faces half a cell out).
  ElectricStage(const Scene& scene, const LatticeUnits& units, const Grid<D>& grid,
                StepData<D>& data);
  ~ElectricStage() override;
  const char* name() const override { return "electric"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;
  const std::vector<double>& potential() const;

 private:
  // After the markers were re-spaced (StepData::on_points_resampled): resample the warm start
  // along the curve and solve again at the next step.
  void Resampled(const typename StepData<D>::Resample& resample);
  // 3D: if every vertex lies within `tolerance` cells of the last solve's surface, sets the
  // forces from that solve's traction re-interpolated at the current vertices (closest points on
  // the solved surface, barycentric weights) and returns true; otherwise returns false at the
  // first vertex beyond it, the forces untouched (a re-solve follows).
  bool ReinterpolateTraction(double tolerance);
  // A time-dependent field (electric.waveform ac, pulses): the force source as set at `field`
  // (a solve or a re-interpolation) is kept as the base that later strengths scale, by
  // (E / field)^2, until the next solve.
  void KeepBase(double field);
  void ScaleBase(double field);

  const Scene& scene_;
  StepData<D>& data_;
  Body<D>& body_;
  ForceSource<D>& source_;
  std::unique_ptr<typename DimensionTraits<D>::Electric> solver_;
  PointsOf<D> positions_at_last_solve_;  // at the last force update (solve or re-interpolation)
  long last_solve_step_ = -1;
  double solved_field_ = -1.0;             // E of the last solve
  PointsOf<D> base_load_, base_traction_;  // time-dependent field: at base_field_
  double base_field_ = 0.0;
  // 3D, numerics.electric_shape_tolerance > 0: the surface and traction of the last solve.
  PointsOf<D> solved_positions_, solved_traction_;
  std::unique_ptr<SurfaceProjector> projector_;  // of the solved surface, rebuilt on demand
  std::vector<SurfacePoint> feet_;               // ReinterpolateTraction scratch
};

extern template class ElectricStage<2>;
extern template class ElectricStage<3>;

}  // namespace ehd
