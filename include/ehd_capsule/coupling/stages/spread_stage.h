// The spread stage: each body's force sources summed (Body::SumLoads, the one place they add up)
// and spread to the grid with the cosine delta (song2019 eqs. (103), (106); a tensor product in
// 3D). In 2D the load is a force per unit length and each marker carries load dl (its arc
// element); in 3D the load is already a force per vertex.
#pragma once

#include <string>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/dimension_traits.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd {

template <int D>
class SpreadStage : public StepStage {
 public:
  SpreadStage(const Scene& scene, const ImmersedBoundaryTransfer<D>& ib, StepData<D>& data,
              FluidOf<D>& fluid);
  const char* name() const override { return "spread"; }
  std::string Describe() const override;
  void Reset() override {}
  void Run(long step) override;
  void Save(CheckpointWriter&) const override {}  // the grid force is the fluid's
  void Restore(CheckpointReader&) override;       // 2D: the arc elements, for the diagnostics

 private:
  std::string Retraction() const;  // ", at the points retracted ..." or ""
  const Scene& scene_;
  const ImmersedBoundaryTransfer<D>& ib_;
  StepData<D>& data_;
  FluidOf<D>& fluid_;
};

extern template class SpreadStage<2>;
extern template class SpreadStage<3>;

}  // namespace ehd
