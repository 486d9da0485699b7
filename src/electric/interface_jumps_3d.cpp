#include "ehd_capsule/electric/interface_jumps_3d.h"

#include <stdexcept>
#include <string>

namespace ehd {

JumpStencil3D MakeJumpStencil(const LocalSurfaceFit& fit, const Eigen::Vector3d& x) {
  const PatchFoot foot = fit.Project(x);
  const SurfacePatch& patch = fit.patch(foot.vertex);
  const std::size_t m = patch.support.size();
  const double d = foot.signed_distance, d2 = d * d / 2.0, d3 = d * d * d / 6.0;
  const double h_sum = foot.curvature_sum;
  const double b_square = h_sum * h_sum - 2.0 * foot.gaussian_curvature;
  // Patch quantities at the vertex (frame t1, t2): the shape operator B = -Hess(height) (to
  // O(h^2): the frame's tilt is O(h^2)), and grad_s H from the fit of the vertices' H.
  const auto& c = patch.height;
  const double b11 = -2 * c[2], b12 = -c[3], b22 = -2 * c[4];
  double dh1 = 0, dh2 = 0;
  for (std::size_t q = 0; q < m; ++q) {
    const double hq = fit.patch(patch.support[q]).curvature_sum;
    dh1 += patch.function_fit(1, q) * hq;
    dh2 += patch.function_fit(2, q) * hq;
  }
  const std::vector<double> value = fit.ValueWeights(foot);
  const std::vector<double> laplace_foot = fit.SurfaceLaplacianWeights(foot);
  JumpStencil3D s;
  s.vertex = foot.vertex;
  s.distance = d;
  s.w_row.resize(m);
  s.g_row.resize(m);
  for (std::size_t q = 0; q < m; ++q) {
    const double lap = 2 * patch.function_fit(3, q) + 2 * patch.function_fit(5, q);
    // B : Hess w with Hess w = [[2 a3, a4], [a4, 2 a5]].
    const double b_hess = b11 * 2 * patch.function_fit(3, q) + 2 * b12 * patch.function_fit(4, q) +
                          b22 * 2 * patch.function_fit(5, q);
    const double grad = dh1 * patch.function_fit(1, q) + dh2 * patch.function_fit(2, q);
    // w: w + d^2/2 (-Delta w) + d^3/6 (H Delta w + 2 B:Hess w + grad H . grad w), Delta w of
    // the d^2 term at the foot point (at the vertex it would be O(h) off), the d^3 terms at the
    // vertex.
    s.w_row[q] = value[q] - d2 * laplace_foot[q] + d3 * (h_sum * lap + 2 * b_hess + grad);
    // g: g d - d^2/2 H g + d^3/6 ((H^2 + |B|^2) g - Delta g).
    s.g_row[q] = value[q] * (d - d2 * h_sum + d3 * (h_sum * h_sum + b_square)) - d3 * lap;
  }
  s.f_coefficient = d2 - d3 * h_sum;
  s.f_dxi_coefficient = d3;
  return s;
}

double ApplyJumpStencil(const LocalSurfaceFit& fit, const JumpStencil3D& stencil,
                        const SurfaceJumps3D& jumps) {
  const std::vector<int>& support = fit.patch(stencil.vertex).support;
  double j = stencil.f_coefficient * jumps.f_jump[stencil.vertex];
  if (!jumps.f_dxi_jump.empty()) j += stencil.f_dxi_coefficient * jumps.f_dxi_jump[stencil.vertex];
  for (std::size_t q = 0; q < support.size(); ++q) {
    j += stencil.w_row[q] * jumps.w[support[q]] + stencil.g_row[q] * jumps.g[support[q]];
  }
  return j;
}

double JumpExtension(const LocalSurfaceFit& fit, const SurfaceJumps3D& jumps,
                     const Eigen::Vector3d& x) {
  return ApplyJumpStencil(fit, MakeJumpStencil(fit, x), jumps);
}

void AddJumpCorrections(const Grid3D& grid, const SurfaceClassification3D& sides,
                        const LocalSurfaceFit& fit, const SurfaceJumps3D& jumps,
                        std::vector<double>& rhs) {
  const std::size_t nv = static_cast<std::size_t>(fit.vertex_count());
  if (jumps.w.size() != nv || jumps.g.size() != nv || jumps.f_jump.size() != nv ||
      (!jumps.f_dxi_jump.empty() && jumps.f_dxi_jump.size() != nv)) {
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
