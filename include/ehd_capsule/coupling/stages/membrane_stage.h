// The membrane stage: each body's membrane forces, written into its force sources.
//   2D  the force density at the markers: a drop's tension, or a capsule's Hookean +
//       Kelvin-Voigt + bending (song2019 eqs. (110)-(115)): source "membrane";
//   3D  finite-element neo-Hookean / Skalak / zero-thickness forces per vertex (source
//       "membrane") plus Helfrich bending (source "bending", with E_b > 0); a drop's surface
//       tension gamma (Delta x)_i A_i = -2 gamma H_i n_i A_i (cotangent; source "membrane").
// The constructor refuses (SceneError) a membrane whose explicit step is unstable at the initial
// shape, naming the term and the numerics.membrane_substeps needed, and in 3D a mesh too coarse
// for the grid, naming the subdivision needed.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

// The laws of one body's membrane (defined per dimension in membrane_stage.cpp).
template <int D>
struct MembraneMechanics;

template <int D>
class MembraneStage : public StepStage {
 public:
  MembraneStage(const Scene& scene, const LatticeUnits& units, StepData<D>& data);
  ~MembraneStage() override;
  const char* name() const override { return "membrane"; }
  std::string Describe() const override;
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter& out) const override;
  void Restore(CheckpointReader& in) override;
  // 3D: the in-plane mean principal tension (tau_1 + tau_2) / 2 at each vertex of body `body`'s
  // present shape, in units of the scene's modulus (a drop: gamma, so 1 everywhere).
  std::vector<double> VertexTension(int body) const;

 private:
  std::vector<std::unique_ptr<MembraneMechanics<D>>> bodies_;  // one per body
};

extern template class MembraneStage<2>;
extern template class MembraneStage<3>;

}  // namespace ehd
