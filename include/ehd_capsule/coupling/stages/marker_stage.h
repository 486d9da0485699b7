// The marker stage: interpolate u^{n+1} at each body's points (song2019 eq. (104)), move them
// (eq. (105) forward Euler, or Adams-Bashforth 2), every numerics.marker_filter_every steps
// remove the mode the grid cannot see (2D: the sawtooth filter; 3D: the mesh-scale filter of the
// deformation), 3D: restore the enclosed volume (numerics.volume_correction_every), wrap the
// points along the periodic axes, check that they stayed finite and 2 h inside the walls; 2D
// drops: re-space bunched markers (numerics.redistribute_markers); 3D drops: move the vertices
// with the normal velocity and the mean (numerics.relax_mesh_every relaxes them along the
// surface).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/dimension_traits.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/ib/marker_update.h"
#include "ehd_capsule/ib/mesh_scale_filter.h"
#include "ehd_capsule/ib/sawtooth_filter.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd {

template <int D>
class MarkerStage : public StepStage {
 public:
  MarkerStage(const Scene& scene, const Grid<D>& grid, const ImmersedBoundaryTransfer<D>& ib,
              StepData<D>& data, const FluidOf<D>& fluid);
  const char* name() const override { return "markers"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;

  long redistributions() const { return redistributions_; }

 private:
  // The point filter of the dimension: the sawtooth filter of the markers (2D; order 8, lower
  // for fewer than 17 markers: it needs 2p + 1) or the mesh-scale filter of the deformation,
  // built on the rest mesh (3D).
  using Filter = std::conditional_t<D == 2, SawtoothFilter, MeshScaleFilter>;

  void Move(long step, int index, Body<D>& body);
  void CheckInside(long step, const PointsOf<D>& x) const;
  void RedistributeBunchedMarkers(int index, Body<D>& body);  // 2D drops

  const Scene& scene_;
  Grid<D> grid_;
  const ImmersedBoundaryTransfer<D>& ib_;
  StepData<D>& data_;
  const FluidOf<D>& fluid_;
  std::vector<PointAdvector<D>> advectors_;       // one per body
  std::vector<std::unique_ptr<Filter>> filters_;  // one per body (numerics.marker_filter_every)
  PointsOf<D> scratch_;
  long redistributions_ = 0;
};

extern template class MarkerStage<2>;
extern template class MarkerStage<3>;

}  // namespace ehd
