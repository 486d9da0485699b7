#include "ehd_capsule/electric/interface_jumps_3d.h"

#include <stdexcept>
#include <string>

namespace ehd {

double JumpExtension(const LocalSurfaceFit& fit, const SurfaceJumps3D& jumps,
                     const Eigen::Vector3d& x) {
  const PatchFoot foot = fit.Project(x);
  const double d = foot.signed_distance;
  const double w = fit.Value(foot, jumps.w);
  const double g = fit.Value(foot, jumps.g);
  const double second =
      jumps.f_jump[foot.vertex] - foot.curvature_sum * g - fit.SurfaceLaplacian(foot, jumps.w);
  return w + d * (g + 0.5 * d * second);
}

void AddJumpCorrections(const Grid3D& grid, const SurfaceClassification3D& sides,
                        const LocalSurfaceFit& fit, const SurfaceJumps3D& jumps,
                        std::vector<double>& rhs) {
  const std::size_t nv = static_cast<std::size_t>(fit.vertex_count());
  if (jumps.w.size() != nv || jumps.g.size() != nv || jumps.f_jump.size() != nv) {
    throw std::invalid_argument("AddJumpCorrections: jump data for " + std::to_string(nv) +
                                " vertices expected (w " + std::to_string(jumps.w.size()) + ", g " +
                                std::to_string(jumps.g.size()) + ", f_jump " +
                                std::to_string(jumps.f_jump.size()) + ")");
  }
  if (rhs.size() != grid.size() || sides.side.size() != grid.size()) {
    throw std::invalid_argument(
        "AddJumpCorrections: rhs or classification size differs from the "
        "grid's " +
        std::to_string(grid.size()));
  }
  const double inv_h2 = 1.0 / (grid.h * grid.h);
  // J at each node that is a neighbour across the interface, computed once.
  std::vector<double> jump(grid.size(), 0.0);
  std::vector<std::uint8_t> done(grid.size(), 0);
  const int n[3] = {grid.nx, grid.ny, grid.nz};
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t c = grid.index(i, j, k);
        if (!sides.irregular[c]) continue;
        const int idx[3] = {i, j, k};
        for (int axis = 0; axis < 3; ++axis) {
          for (int s = -1; s <= 1; s += 2) {
            int q[3] = {idx[0], idx[1], idx[2]};
            q[axis] += s;
            if (q[axis] < 0 || q[axis] >= n[axis]) continue;
            const std::size_t o = grid.index(q[0], q[1], q[2]);
            if (sides.side[o] == sides.side[c]) continue;
            if (!done[o]) {
              jump[o] = JumpExtension(fit, jumps,
                                      Eigen::Vector3d(grid.x(q[0]), grid.y(q[1]), grid.z(q[2])));
              done[o] = 1;
            }
            rhs[c] += (sides.side[o] > 0 ? jump[o] : -jump[o]) * inv_h2;
          }
        }
      }
    }
  }
}

}  // namespace ehd
