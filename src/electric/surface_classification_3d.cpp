// Winding-number classification of grid nodes against a triangulated surface; see
// surface_classification_3d.h.
#include "ehd_capsule/electric/surface_classification_3d.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace ehd {
namespace {

// Edge function of p against the directed edge a -> b (positive on its left).
double EdgeFunction(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Top-left rule for a counter-clockwise triangle: a point exactly on an edge is inside only if
// the edge is a "top" edge (horizontal, pointing left) or a "left" edge (pointing down).
bool OwnsEdge(double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  return (dy == 0.0 && dx < 0.0) || dy < 0.0;
}

// Calls add(line, t, sign, cosine) for every crossing of the grid lines along `axis` (line =
// index of the line in the other two axes, u + n_u v, (u, v) the next axes in cyclic order; t the
// coordinate along axis; sign +1 where the outward normal points along +axis; cosine = |n . e|
// of the triangle's normal), by rasterising each triangle's projection with the top-left rule
// (no double counts at shared edges).
template <typename Add>
void ForEachLineCrossing(const Grid3D& g, const TriangleMesh& surface, int axis, Add add) {
  const Eigen::Matrix3Xd& x = surface.vertices();
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  const int nu = g.extent(ua), nv = g.extent(va);
  const double u0 = g.origin(ua), v0 = g.origin(va), h = g.h;
  for (const auto& t : surface.triangles()) {
    double px[3], py[3], pz[3];
    for (int c = 0; c < 3; ++c) {
      px[c] = x(ua, t[c]);
      py[c] = x(va, t[c]);
      pz[c] = x(axis, t[c]);
    }
    const double area2 = EdgeFunction(px[0], py[0], px[1], py[1], px[2], py[2]);
    if (area2 == 0.0) continue;  // edge-on in projection: crosses no line interior
    // Orient counter-clockwise in projection; sign = +1 if it was (outward normal along +axis:
    // (u, v, axis) is right-handed).
    int order[3] = {0, 1, 2};
    int sign = 1;
    if (area2 < 0.0) {
      std::swap(order[1], order[2]);
      sign = -1;
    }
    const double ax = px[order[0]], ay = py[order[0]], bx = px[order[1]], by = py[order[1]],
                 cx = px[order[2]], cy = py[order[2]];
    const int ia = t[order[0]], ib = t[order[1]], ic = t[order[2]];
    // The edge function of a shared edge is evaluated from its lower-index vertex in both of its
    // triangles (and negated in the one that runs it the other way), so the two see exactly
    // opposite values and the top-left rule stays watertight in floating point; a line through a
    // vertex or an edge (a centred sphere on an odd grid puts its poles on one) is counted once.
    const auto edge = [&](int i, double ix, double iy, int j, double jx, double jy, double qx,
                          double qy) {
      return i < j ? EdgeFunction(ix, iy, jx, jy, qx, qy) : -EdgeFunction(jx, jy, ix, iy, qx, qy);
    };
    const double az = pz[order[0]], bz = pz[order[1]], cz = pz[order[2]];
    const double area = std::abs(area2);
    const Eigen::Vector3d face = (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0]));
    const double cosine = area / face.norm();
    const bool own_ab = OwnsEdge(ax, ay, bx, by), own_bc = OwnsEdge(bx, by, cx, cy),
               own_ca = OwnsEdge(cx, cy, ax, ay);
    const int i0 =
        std::max(0, static_cast<int>(std::floor((std::min({ax, bx, cx}) - u0) / h - 0.5)));
    const int i1 =
        std::min(nu - 1, static_cast<int>(std::ceil((std::max({ax, bx, cx}) - u0) / h - 0.5)));
    const int j0 =
        std::max(0, static_cast<int>(std::floor((std::min({ay, by, cy}) - v0) / h - 0.5)));
    const int j1 =
        std::min(nv - 1, static_cast<int>(std::ceil((std::max({ay, by, cy}) - v0) / h - 0.5)));
    for (int j = j0; j <= j1; ++j) {
      const double qy = v0 + (j + 0.5) * h;
      for (int i = i0; i <= i1; ++i) {
        const double qx = u0 + (i + 0.5) * h;
        const double w0 = edge(ib, bx, by, ic, cx, cy, qx, qy);  // weight of a
        const double w1 = edge(ic, cx, cy, ia, ax, ay, qx, qy);  // weight of b
        const double w2 = edge(ia, ax, ay, ib, bx, by, qx, qy);  // weight of c
        const bool in = (w0 > 0.0 || (w0 == 0.0 && own_bc)) &&
                        (w1 > 0.0 || (w1 == 0.0 && own_ca)) && (w2 > 0.0 || (w2 == 0.0 && own_ab));
        if (!in) continue;
        add(static_cast<std::size_t>(j) * nu + i, (w0 * az + w1 * bz + w2 * cz) / area, sign,
            cosine);
      }
    }
  }
}

}  // namespace

SurfaceClassification3D ClassifyNodes(const Grid3D& g, const TriangleMesh& surface) {
  const Eigen::Matrix3Xd& x = surface.vertices();
  const double x_lo = g.x0, x_hi = g.x0 + g.nx * g.h, y_lo = g.y0, y_hi = g.y0 + g.ny * g.h;
  if (x.row(0).minCoeff() <= x_lo || x.row(0).maxCoeff() >= x_hi || x.row(1).minCoeff() <= y_lo ||
      x.row(1).maxCoeff() >= y_hi) {
    throw std::invalid_argument(
        "ClassifyNodes: the surface must lie strictly inside the grid's box in x and y");
  }
  // Crossings per column along z (line index i + nx j): (z, sign).
  std::vector<std::vector<std::pair<double, int>>> columns(static_cast<std::size_t>(g.nx) * g.ny);
  ForEachLineCrossing(g, surface, 2, [&](std::size_t line, double z, int sign, double) {
    columns[line].emplace_back(z, sign);
  });
  SurfaceClassification3D out;
  out.side.assign(g.size(), 1);
  out.irregular.assign(g.size(), 0);
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      auto& crossings = columns[static_cast<std::size_t>(j) * g.nx + i];
      if (crossings.empty()) continue;
      std::sort(crossings.begin(), crossings.end());
      int winding = 0;
      std::size_t next = 0;
      for (int k = 0; k < g.nz; ++k) {
        const double z = g.z(k);
        while (next < crossings.size() && crossings[next].first < z)
          winding += crossings[next++].second;
        // Outward normals: entering through a downward face (-1), leaving through an upward one.
        if (winding < 0) {
          out.side[g.index(i, j, k)] = -1;
          ++out.inside_count;
        }
      }
    }
  }
  const int n[3] = {g.nx, g.ny, g.nz};
  for (int k = 0; k < g.nz; ++k) {
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t node = g.index(i, j, k);
        const int c[3] = {i, j, k};
        bool irregular = false;
        for (int a = 0; a < 3 && !irregular; ++a) {
          for (int s : {-1, 1}) {
            int d[3] = {c[0], c[1], c[2]};
            d[a] += s;
            if (d[a] < 0 || d[a] >= n[a]) continue;
            if (out.side[g.index(d[0], d[1], d[2])] != out.side[node]) {
              irregular = true;
              break;
            }
          }
        }
        if (irregular) {
          out.irregular[node] = 1;
          ++out.irregular_count;
        }
      }
    }
  }
  return out;
}

MultipleCrossing FindMultipleCrossing(const Grid3D& g, const TriangleMesh& surface) {
  MultipleCrossing out;
  for (int axis = 0; axis < 3; ++axis) {
    const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
    const int nu = g.extent(ua), na = g.extent(axis);
    std::vector<std::vector<std::pair<double, double>>> lines(static_cast<std::size_t>(nu) *
                                                              g.extent(va));
    ForEachLineCrossing(g, surface, axis, [&](std::size_t line, double t, int, double cosine) {
      lines[line].emplace_back(t, cosine);
    });
    for (std::size_t line = 0; line < lines.size(); ++line) {
      const LineDoubleCrossing c = ClosestDoubleCrossing(lines[line], g.origin(axis), g.h, na);
      if (!c.found || (out.found && c.gap_h >= out.gap_h)) continue;
      out.found = true;
      out.axis = axis;
      out.gap_h = c.gap_h;
      out.node[axis] = c.node;
      out.node[ua] = static_cast<int>(line % nu);
      out.node[va] = static_cast<int>(line / nu);
    }
  }
  return out;
}

}  // namespace ehd
