// The body of the coupled step (coupling/body.h).
#include "ehd_capsule/coupling/body.h"

#include <sstream>

namespace ehd {

template <int D>
ForceSource<D>& Body<D>::AddForceSource(const std::string& name) {
  sources.push_back(std::make_unique<ForceSource<D>>());
  sources.back()->name = name;
  sources.back()->load.setZero(D, size());
  return *sources.back();
}

template <int D>
const ForceSource<D>* Body<D>::FindForceSource(const std::string& name) const {
  for (const auto& source : sources) {
    if (source->name == name) return source.get();
  }
  return nullptr;
}

template <int D>
void Body<D>::ResetTo(const Points& positions) {
  shape.SetPositions(positions);
  const Eigen::Index n = positions.cols();
  U.setZero(D, n);
  for (auto& source : sources) source->load.setZero(D, n);
  load.setZero(D, n);
  force.setZero(D, n);
  coupling.resize(D, 0);
  if constexpr (D == 2) {
    initial_measure = shape.curve.Area();
  } else {
    initial_measure = EnclosedVolume(shape.mesh);
    initial_surface = SurfaceArea(shape.mesh);
  }
  volume_corrected = 0.0;
}

template <int D>
void Body<D>::SumLoads() {
  if (sources.empty()) {
    load.setZero(D, size());
    return;
  }
  load = sources.front()->load;
  for (std::size_t i = 1; i < sources.size(); ++i) load += sources[i]->load;
}

template <int D>
std::string Body<D>::DescribeLargestLoads() const {
  std::ostringstream out;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const Points& l = sources[i]->load;
    out << (i ? ", " : "") << sources[i]->name << ' '
        << (l.cols() > 0 ? l.colwise().norm().maxCoeff() : 0.0);
  }
  return out.str();
}

template struct Body<2>;
template struct Body<3>;

}  // namespace ehd
