// The dimension-free guarantees of the fast immersed interface method (interface_guarantees.h).
#include "ehd_capsule/electric/interface_guarantees.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ehd_capsule/electric/gmres.h"

namespace ehd {

void CheckInnerRatio(const std::string& solver, double sigma_minus, double sigma_plus,
                     double max_inner_ratio) {
  const double ratio = sigma_minus / sigma_plus;
  if (ratio > max_inner_ratio) {
    std::ostringstream os;
    os << solver << ": sigma^-/sigma^+ = " << ratio << " > max_inner_ratio = " << max_inner_ratio
       << " (the near-null mode of the Schur system amplifies the discretisation error by about "
          "the ratio; the solver is measured up to max_inner_ratio)";
    throw SolverError(os.str());
  }
}

double CheckFitAgreement(const std::string& solver, const std::vector<double>& dn_fit,
                         const std::vector<double>& dn_check, const std::vector<double>& g,
                         double max_fit_disagreement, const PointName& name) {
  double scale = 0, worst = 0;
  int worst_point = 0;
  const int n = static_cast<int>(dn_fit.size());
  for (int k = 0; k < n; ++k) {
    scale = std::max({scale, std::abs(dn_fit[k]), std::abs(dn_fit[k] + g[k])});
    const double d = std::abs(dn_check[k] - dn_fit[k]);
    if (!(d <= worst)) {  // NaN too
      worst = d;
      worst_point = k;
    }
  }
  const double disagreement = scale > 0 ? worst / scale : (worst > 0 ? worst : 0.0);
  if (!(disagreement <= max_fit_disagreement)) {
    std::ostringstream os;
    os << solver << ": at " << name(worst_point)
       << " the cubic and quadratic fits of phi_n^- differ by " << disagreement
       << " of max |phi_n| (> max_fit_disagreement = " << max_fit_disagreement
       << "): the potential is not resolved by the grid near the interface there (a thin part, "
          "or a source or field varying on the grid scale); refine the grid";
    throw SolverError(os.str());
  }
  return disagreement;
}

double CheckPointOscillation(const std::string& solver, const std::string& point_kind,
                             const std::vector<double>& content, double scale,
                             double max_marker_oscillation, const PointName& name,
                             const PointName& detail) {
  if (!(scale > 0.0)) return 0.0;
  int worst = 0;
  double worst_value = 0.0;
  const int n = static_cast<int>(content.size());
  for (int k = 0; k < n; ++k) {
    if (!(content[k] <= worst_value)) {  // NaN too
      worst_value = content[k];
      worst = k;
    }
  }
  if (!(worst_value <= max_marker_oscillation * scale)) {
    std::ostringstream os;
    os << solver << ": [phi_n] oscillates at the " << point_kind << " scale at " << name(worst)
       << ": " << worst_value << " = " << worst_value / scale << " of max(|[phi_n]|, |phi_n|) "
       << "> max_marker_oscillation = " << max_marker_oscillation << detail(worst)
       << "; the interface is not resolved: refine the grid";
    throw SolverError(os.str());
  }
  return worst_value / scale;
}

// A line grazing a curved interface crosses it twice within a cell through a sliver much thinner
// than h that does no harm; a thin layer is crossed nearly head-on twice.
constexpr double kHeadOnCosine = 0.5;

LineDoubleCrossing ClosestDoubleCrossing(std::vector<std::pair<double, double>>& t, double origin,
                                         double h, int nodes) {
  LineDoubleCrossing out;
  if (t.size() < 2) return out;
  std::sort(t.begin(), t.end());
  for (std::size_t k = 0; k + 1 < t.size(); ++k) {
    // Interval between nodes i and i + 1 along the line (cell-centred coordinates).
    const double s0 = (t[k].first - origin) / h - 0.5;
    const double s1 = (t[k + 1].first - origin) / h - 0.5;
    const int i = static_cast<int>(std::floor(s0));
    if (i < 0 || i + 1 >= nodes || static_cast<int>(std::floor(s1)) != i) continue;
    if (std::min(t[k].second, t[k + 1].second) < kHeadOnCosine) continue;
    const double gap = (t[k + 1].first - t[k].first) / h;
    if (out.found && gap >= out.gap_h) continue;
    out.found = true;
    out.node = i;
    out.gap_h = gap;
  }
  return out;
}

void ThrowThinPart(const std::string& solver, const std::string& interface,
                   const std::string& where, double gap_h, double h) {
  std::ostringstream os;
  os << solver << ": the " << interface << " crosses " << where << " twice, " << gap_h
     << " h apart: ";
  if (gap_h < 0.05) {
    // No grid resolves that: the interface doubles back on itself within a sliver of a cell.
    os << "the "
       << interface << " folds there (a wrinkle or a tangled interface, not a part any grid resolves)";
  } else {
    os << "a part thinner than the grid spacing h = " << h
       << " (e.g. a biconcave dimple), which the stencil cannot see; the electric grid needs h "
          "below "
       << gap_h * h << " there: refine the grid";
  }
  throw SolverError(os.str());
}

}  // namespace ehd
