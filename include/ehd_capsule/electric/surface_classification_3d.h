// Inside/outside classification of the nodes of a Grid3D against a closed triangulated surface,
// and the irregular nodes of the 3D immersed interface method (issue #13: robust for the
// biconcave cell and other non-convex surfaces).
//
// Winding number along grid columns: for each column (x_i, y_j) every triangle whose xy
// projection contains the point contributes a crossing at its height z with the sign of its
// projected orientation (+1 where the outward normal points up). A node's winding number is the
// sum of the signs of the crossings below it: going up, a column enters a closed outward-oriented
// surface through a face whose normal points down (-1) and leaves through one pointing up (+1),
// so the nodes inside have a negative sum (any number of entries and exits: non-convex). The
// point-in-triangle test follows the top-left rule of rasterisation on edges normalised to a
// fixed direction, so a column through a shared edge or vertex is counted once for triangles of
// equal projected orientation and cancels for a fold (silhouette) edge: no double counts and no
// holes, whatever the mesh. Triangles are binned to the columns of their bounding box, so the
// cost is O(F + N^2 + crossings), not O(N^2 F).
//
// Irregular node (song2019 sec. 2.4 in 3D): a node with a neighbour of the 7-point stencil on the
// other side.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "ehd_capsule/electric/interface_guarantees.h"
#include "ehd_capsule/geometry/grid.h"
#include "ehd_capsule/geometry/triangle_mesh.h"

namespace ehd {

struct SurfaceClassification3D {
  std::vector<std::int8_t> side;        // -1 inside, +1 outside, per node (grid index)
  std::vector<std::uint8_t> irregular;  // 1 where a 7-point neighbour is on the other side
  long inside_count = 0, irregular_count = 0;
};

// Throws std::invalid_argument if the surface does not lie inside the grid's box in x and y (a
// column outside the box would go unclassified).
SurfaceClassification3D ClassifyNodes(const Grid3D& grid, const TriangleMesh& surface);

// A grid segment (between two neighbouring nodes along an axis) that the surface crosses twice
// or more: a part of the surface thinner than h along that axis (a biconcave dimple), which the
// 7-point stencil cannot see (both nodes are on the same side) and the immersed interface
// corrections cannot represent. Only crossings where the line is within 60 degrees of the
// surface normal count (a line grazing a curved sheet crosses it twice within a cell through a
// harmless sliver). Of all such segments, the one with the closest crossings (the per-line search
// is the curve's too: ClosestDoubleCrossing, interface_guarantees.h).
using MultipleCrossing = GridDoubleCrossing<3>;
MultipleCrossing FindMultipleCrossing(const Grid3D& grid, const TriangleMesh& surface);

}  // namespace ehd
