// Marker arc elements, song2019 eq. (105) forward Euler / Adams-Bashforth 2 marker update, and
// periodic wrap of a whole curve. See marker_update.h.
#include "ehd_capsule/ib/marker_update.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "ehd_capsule/geometry/curve_segments.h"

namespace ehd {

void MarkerArcElements(const ClosedCurve& c, std::vector<double>& dl) {
  // Segment-local spline evaluation (no knot search); same values as c.SegmentArcLength(k).
  thread_local CurveSegments segments;
  segments.Update(c);
  const int m = c.size();
  if (static_cast<int>(dl.size()) != m) dl.resize(m);
  const double last = segments.SegmentArcLength(m - 1);
  double prev = last;
  for (int k = 0; k < m; ++k) {
    const double seg = (k + 1 < m) ? segments.SegmentArcLength(k) : last;
    dl[k] = 0.5 * (prev + seg);
    prev = seg;
  }
}

void MarkerArcElementsFromSegments(const std::vector<double>& seg, std::vector<double>& dl) {
  const std::size_t m = seg.size();
  if (dl.size() != m) dl.resize(m);
  for (std::size_t k = 0; k < m; ++k) dl[k] = 0.5 * (seg[k == 0 ? m - 1 : k - 1] + seg[k]);
}

std::vector<double> MarkerArcElements(const ClosedCurve& c) {
  std::vector<double> dl;
  MarkerArcElements(c, dl);
  return dl;
}

double WrapCurveIntoDomain(const Grid2D& grid, Eigen::Matrix2Xd& X) {
  if (X.cols() == 0) return 0.0;
  const double width = grid.width();
  const double mean_x = X.row(0).mean();
  const double periods = std::floor((mean_x - grid.x0) / width);
  if (periods == 0.0) return 0.0;
  const double shift = -periods * width;
  X.row(0).array() += shift;
  return shift;
}

void WrapSurfaceIntoDomain(const Grid3D& grid, const std::array<bool, 3>& periodic,
                           Eigen::Matrix3Xd& X) {
  if (X.cols() == 0) return;
  for (int a = 0; a < 3; ++a) {
    if (!periodic[a]) continue;
    const double width = grid.extent(a) * grid.h;
    const double periods = std::floor((X.row(a).mean() - grid.origin(a)) / width);
    if (periods != 0.0) X.row(a).array() -= periods * width;
  }
}

}  // namespace ehd
