// The spread stage (coupling/stages/spread_stage.h).
#include "ehd_capsule/coupling/stages/spread_stage.h"

#include <sstream>

#include "ehd_capsule/coupling/retracted_points.h"
#include "ehd_capsule/ib/marker_update.h"

namespace ehd {

template <int D>
SpreadStage<D>::SpreadStage(const Scene& scene, const ImmersedBoundaryTransfer<D>& ib,
                            StepData<D>& data, FluidOf<D>& fluid)
    : scene_(scene), ib_(ib), data_(data), fluid_(fluid) {}

template <int D>
std::string SpreadStage<D>::Describe() const {
  std::string sources;
  for (const auto& source : data_.bodies.front().sources) {
    sources += (sources.empty() ? "" : " + ") + source->name;
  }
  const std::string kernel =
      ib_.kernel() == DeltaKernel::kRoma3        ? "roma3 delta (Roma, Peskin & Berger 1999)"
      : ib_.kernel() == DeltaKernel::kTrapezoid3 ? "trapezoid3 delta (3 nodes, even-odd)"
      : ib_.kernel() == DeltaKernel::kRoma3EvenOdd
          ? "roma3_even_odd delta (trapezoid3 along each component's axis, roma3 across)"
          : "cosine delta (eq. 103)";
  if constexpr (D == 2) {
    return kernel + ", spread the sum of the force sources (" + sources + ") dl" +
           (scene_.has_shear() ? ", periodic in x" : "") + Retraction();
  } else {
    return kernel + " as a product in 3D, spread the sum of the force sources (" + sources +
           ") per vertex" + Retraction();
  }
}

template <int D>
std::string SpreadStage<D>::Retraction() const {
  if (!(scene_.numerics.ib_retraction > 0.0)) return "";
  std::ostringstream out;
  out << ", at the points retracted " << scene_.numerics.ib_retraction << " h along their normals";
  return out.str();
}

template <int D>
void SpreadStage<D>::Run(long) {
  for (Body<D>& body : data_.bodies) {
    body.SumLoads();
    if constexpr (D == 2) {
      MarkerArcElements(body.shape.curve, body.dl);
      body.force.resize(2, body.size());
      for (int k = 0; k < body.size(); ++k) body.force.col(k) = body.load.col(k) * body.dl[k];
    } else {
      body.force = body.load;
    }
  }
  const double retraction = scene_.numerics.ib_retraction * ib_.grid().h;
  for (Body<D>& body : data_.bodies) {
    if (retraction > 0.0) RetractAlongNormals(body.shape, retraction, body.coupling);
  }
  fluid_.ClearForce();
  for (const Body<D>& body : data_.bodies) {
    ib_.Spread(body.coupling_points(), body.force, ForceOf<D>(fluid_));  // adds
  }
}

template <int D>
void SpreadStage<D>::Restore(CheckpointReader&) {
  if constexpr (D == 2) {
    for (Body<D>& body : data_.bodies) MarkerArcElements(body.shape.curve, body.dl);
  }
}

template class SpreadStage<2>;
template class SpreadStage<3>;

}  // namespace ehd
