// Force terms: a physics module that adds one force on the membrane, as one unit (docs/
// architecture.md, "Adding a force term"). A force term is
//   - its scene keys (a SceneModule: type, range, units, doc line of each; scene/scene_keys.h),
//     read and checked by LoadScene with every other key and listed in docs/scene_keys.md;
//   - a test on the scene that says whether it acts (its keys given, its strength not zero);
//   - a class template over the dimension, ForceTerm<D>, that computes its load on a body from
//     the body's points (in the body's load unit: per unit length in 2D, per vertex in 3D).
// RegisterForceTerm, called at static initialisation from the term's own file (src/forces/),
// registers all three. For each active term the coupled step builds one ForceTermStage: it adds
// a force source named after the module to every body, after the membrane's and the electric
// one (so they sum membrane + electric + terms, in registration order), and runs after the
// membrane stage and before the spread, which sums the sources. Files in src/forces/ are linked
// into every binary of ehd_core (an object library), so a term needs no other file to act.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ehd_capsule/coupling/body.h"
#include "ehd_capsule/coupling/step_stage.h"
#include "ehd_capsule/scene/scene.h"
#include "ehd_capsule/scene/units.h"

namespace ehd {

template <int D>
class ForceTerm {
 public:
  virtual ~ForceTerm() = default;
  // The pipeline line: what it applies and how strong, in scene and lattice values.
  virtual std::string Describe() const = 0;
  // This step's load on `body` (D x points, already sized and zeroed): called after the membrane
  // stage has updated the body's shape and force, before the sources are summed.
  virtual void Compute(const Body<D>& body, PointsOf<D>& load) = 0;
};

// What a force term's file registers.
struct ForceTermModule {
  SceneModule keys;  // keys.name names the term, its force source and its stage
  std::function<bool(const Scene&)> active;
  // One term per body; the body holds its initial positions (a term may pick material points).
  std::function<std::unique_ptr<ForceTerm<2>>(const Scene&, const LatticeUnits&, const Body<2>&)>
      make_2d;
  std::function<std::unique_ptr<ForceTerm<3>>(const Scene&, const LatticeUnits&, const Body<3>&)>
      make_3d;
};

// Registers the term and its keys (RegisterSceneModule). Returns true, for a static initialiser.
bool RegisterForceTermModule(ForceTermModule module);
const std::vector<ForceTermModule>& ForceTermModules();

// The usual registration: Term<D> constructed from (scene, units, body) in both dimensions.
template <template <int> class Term>
bool RegisterForceTerm(SceneModule keys, std::function<bool(const Scene&)> active) {
  ForceTermModule m;
  m.keys = std::move(keys);
  m.active = std::move(active);
  m.make_2d = [](const Scene& s, const LatticeUnits& u, const Body<2>& b) {
    return std::unique_ptr<ForceTerm<2>>(std::make_unique<Term<2>>(s, u, b));
  };
  m.make_3d = [](const Scene& s, const LatticeUnits& u, const Body<3>& b) {
    return std::unique_ptr<ForceTerm<3>>(std::make_unique<Term<3>>(s, u, b));
  };
  return RegisterForceTermModule(std::move(m));
}

// The stage of one active term: one ForceTerm and one force source per body.
template <int D>
class ForceTermStage : public StepStage {
 public:
  ForceTermStage(const ForceTermModule& module, const Scene& scene, const LatticeUnits& units,
                 StepData<D>& data);
  const char* name() const override { return name_.c_str(); }
  std::string Describe() const override { return terms_.front()->Describe(); }
  void Reset() override;
  void Run(long step) override;
  void Save(CheckpointWriter&) const override {}  // a term's load follows from the points
  void Restore(CheckpointReader&) override {}

 private:
  std::string name_;
  StepData<D>& data_;
  std::vector<std::unique_ptr<ForceTerm<D>>> terms_;  // per body
  std::vector<ForceSource<D>*> sources_;              // per body
};

extern template class ForceTermStage<2>;
extern template class ForceTermStage<3>;

}  // namespace ehd
