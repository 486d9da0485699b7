// The force-term registry and stage (coupling/force_term.h).
#include "ehd_capsule/coupling/force_term.h"

#include <stdexcept>

namespace ehd {
namespace {

std::vector<ForceTermModule>& Modules() {
  static std::vector<ForceTermModule> modules;
  return modules;
}

}  // namespace

bool RegisterForceTermModule(ForceTermModule module) {
  if (!module.active || !module.make_2d || !module.make_3d) {
    throw std::logic_error("force term '" + module.keys.name +
                           "': active, make_2d and make_3d are all required");
  }
  RegisterSceneModule(module.keys);  // throws on a name or key declared twice
  Modules().push_back(std::move(module));
  return true;
}

const std::vector<ForceTermModule>& ForceTermModules() { return Modules(); }

template <int D>
ForceTermStage<D>::ForceTermStage(const ForceTermModule& module, const Scene& scene,
                                  const LatticeUnits& units, StepData<D>& data)
    : name_(module.keys.name), data_(data) {
  for (Body<D>& body : data_.bodies) {
    if constexpr (D == 2) {
      terms_.push_back(module.make_2d(scene, units, body));
    } else {
      terms_.push_back(module.make_3d(scene, units, body));
    }
    sources_.push_back(&body.AddForceSource(name_));
  }
}

template <int D>
void ForceTermStage<D>::Reset() {
  for (std::size_t b = 0; b < sources_.size(); ++b) {
    sources_[b]->load.setZero(D, data_.bodies[b].size());
  }
}

template <int D>
void ForceTermStage<D>::Run(long) {
  for (std::size_t b = 0; b < sources_.size(); ++b) {
    const Body<D>& body = data_.bodies[b];
    PointsOf<D>& load = sources_[b]->load;
    load.setZero(D, body.size());
    terms_[b]->Compute(body, load);
  }
}

template class ForceTermStage<2>;
template class ForceTermStage<3>;

}  // namespace ehd
