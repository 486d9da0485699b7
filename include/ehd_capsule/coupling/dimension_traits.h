// The types a coupled step uses in each dimension, for the stages that are templates over D.
#pragma once

#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/ib/immersed_boundary.h"
#include "ehd_capsule/lbm/lattice_boltzmann.h"

namespace ehd {

template <int D>
class LeakyDielectricSolver;

template <int D>
struct DimensionTraits;

template <>
struct DimensionTraits<2> {
  using Fluid = LatticeBoltzmann2D;           // D2Q9 MRT
  using Electric = LeakyDielectricSolver<2>;  // 2D fast IIM
};

template <>
struct DimensionTraits<3> {
  using Fluid = LatticeBoltzmann3D;           // D3Q19 MRT
  using Electric = LeakyDielectricSolver<3>;  // 3D fast IIM
};

template <int D>
using FluidOf = typename DimensionTraits<D>::Fluid;

// The fluid's velocity and force components as the immersed boundary takes them.
template <int D>
std::array<const std::vector<double>*, D> VelocityOf(const FluidOf<D>& fluid) {
  std::array<const std::vector<double>*, D> u{};
  for (int a = 0; a < D; ++a) u[a] = &fluid.velocity(a);
  return u;
}
template <int D>
std::array<std::vector<double>*, D> ForceOf(FluidOf<D>& fluid) {
  std::array<std::vector<double>*, D> f{};
  for (int a = 0; a < D; ++a) f[a] = &fluid.force(a);
  return f;
}

}  // namespace ehd
