// The guarantees of the fast immersed interface method that do not depend on the dimension
// (issue #43 item 1; not in song2019): the curve solver (2D, fast_iim_solver.h) and the surface
// solver (3D, fast_iim_solver_3d.h) call the same checks, each giving only what its geometry
// supplies (the names of its points, the crossings of its grid lines, its point-scale operator).
// Each check throws SolverError naming the solver, the point or grid segment, the quantity, the
// option (InterfaceSolverOptions) and the remedy.
//
// - Inner ratio: sigma^-/sigma^+ <= max_inner_ratio.
// - Fit agreement: after the solve, phi_n^- of the fit one degree lower (the quadratic beside the
//   cubic) agrees with the fit's to max_fit_disagreement of max(|phi_n^-|, |phi_n^+|).
// - Point-scale oscillation: after the solve, the point-scale content of G (from the dimension's
//   operator: the fourth difference along the markers / 16, the squared graph Laplacian of the
//   mesh / 4) stays below max_marker_oscillation of max(|G|, |phi_n^-|, |phi_n^+|).
// - Thin parts: no grid segment (between two neighbouring nodes along an axis) crossed twice by
//   the interface nearly head-on (within 60 degrees of its normal): a part thinner than h, which
//   the stencil cannot see (both nodes on the same side); a line grazing a curved interface also
//   crosses it twice within a cell, through a harmless sliver, and is not counted.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace ehd {

// Names interface point k in a message, e.g. "marker 3 (0.1, 0.2)" or "vertex 12".
using PointName = std::function<std::string(int k)>;

// Throws SolverError if sigma_minus / sigma_plus > max_inner_ratio.
void CheckInnerRatio(const std::string& solver, double sigma_minus, double sigma_plus,
                     double max_inner_ratio);

// The largest |dn_check - dn_fit| relative to max(|dn_fit|, |dn_fit + g|) (0 if that is 0);
// throws SolverError above max_fit_disagreement (or if it is not finite).
double CheckFitAgreement(const std::string& solver, const std::vector<double>& dn_fit,
                         const std::vector<double>& dn_check, const std::vector<double>& g,
                         double max_fit_disagreement, const PointName& name);

// content[k]: the point-scale content of G at point k (see above); scale: max(|G|, |phi_n^+-|).
// Returns max content / scale (0 if scale is 0); throws SolverError above
// max_marker_oscillation (or if it is not finite). point_kind: "marker" or "vertex"; detail(k):
// what to add about point k (e.g. the curvature radius there).
double CheckPointOscillation(const std::string& solver, const std::string& point_kind,
                             const std::vector<double>& content, double scale,
                             double max_marker_oscillation, const PointName& name,
                             const PointName& detail);

// The crossings of one grid line (coordinate along the line, |cos| between the line and the
// interface normal), sorted in place. The closest pair of head-on crossings (both |cos| >= 1/2)
// between two neighbouring nodes, node i and i + 1 at origin + (i + 1/2) h, i + 1 < nodes.
struct LineDoubleCrossing {
  bool found = false;
  int node = -1;     // the segment from node to node + 1 along the line
  double gap_h = 0;  // distance between its two crossings, in h
};
LineDoubleCrossing ClosestDoubleCrossing(std::vector<std::pair<double, double>>& crossings,
                                         double origin, double h, int nodes);

// Of all grid segments crossed twice head-on, the one with the closest crossings (2D:
// FindMultipleCrossing of interface_classification.h; 3D: of surface_classification_3d.h).
template <int D>
struct GridDoubleCrossing {
  bool found = false;
  int axis = -1;              // 0, 1, 2: x, y, z
  std::array<int, D> node{};  // the segment from node to node + e_axis
  double gap_h = 0;           // distance between its two crossings, in h
};

// Throws the thin-part SolverError for a segment crossed twice gap_h apart; where: the segment
// ("the grid segment from node (i, j) along x"), interface: "curve" or "surface".
[[noreturn]] void ThrowThinPart(const std::string& solver, const std::string& interface,
                                const std::string& where, double gap_h, double h);

template <int D>
[[noreturn]] void ThrowThinPart(const std::string& solver, const std::string& interface,
                                const GridDoubleCrossing<D>& c, double h) {
  std::string where = "the grid segment from node (";
  for (int a = 0; a < D; ++a) where += (a ? ", " : "") + std::to_string(c.node[a]);
  where += ") along ";
  where += "xyz"[c.axis];
  ThrowThinPart(solver, interface, where, c.gap_h, h);
}

}  // namespace ehd
