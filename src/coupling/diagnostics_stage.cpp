// Last stage of the coupled step: the shape diagnostics (D_xy, inclination of the equivalent
// ellipse, enclosed area), the area watchdog, the tank-treading phase of marker 0 and the public
// state (SimulationState) with the clock.
#include <cmath>
#include <sstream>

#include "ehd_capsule/coupling/capsule_stages_2d.h"
#include "ehd_capsule/diagnostics/shape_diagnostics.h"

namespace ehd {
DiagnosticsStage2D::DiagnosticsStage2D(const Scene& scene, const LatticeUnits& units,
                                       MembraneMarkers2D& body, const LatticeBoltzmann2D& fluid,
                                       bool electric)
    : scene_(scene), units_(units), body_(body), fluid_(fluid), electric_(electric), tracker_(0) {}

std::string DiagnosticsStage2D::Describe() const {
  std::ostringstream out;
  out << "D_xy and inclination of the equivalent ellipse, tank-treading phase of marker 0; "
         "watchdogs: non-finite values, Mach > "
      << scene_.numerics.max_mach << ", |area drift| > " << scene_.numerics.area_drift_limit
      << ", a marker within 2h of a wall";
  if (electric_) out << ", GMRES not converged";
  return out.str();
}

void DiagnosticsStage2D::MeasureInto(const ShapeDiagnostics& d, SimulationState& s) const {
  const int markers = static_cast<int>(body_.X.cols());
  s.dimension = 2;
  s.markers.resize(3, markers);
  s.markers.topRows<2>() = body_.X;
  s.markers.row(2).setZero();
  s.dxy = d.dxy;
  s.inclination = d.inclination;
  s.area = d.area;
  s.area_drift = RelativeAreaDrift(d.area, body_.initial_area);
  s.surface_drift = initial_length_ > 0.0 ? d.length / initial_length_ - 1.0 : 0.0;
  s.tt_phase = tracker_.phase();
  if (electric_) {
    s.electric_force.resize(3, markers);
    s.electric_force.topRows<2>() = body_.electric_density;
    s.electric_force.row(2).setZero();
    Eigen::Vector2d total(0, 0);
    for (int k = 0; k < markers; ++k) total += body_.electric_density.col(k) * body_.dl[k];
    s.electric_force_total = Eigen::Vector3d(total.x(), total.y(), 0.0);
  }
}

void DiagnosticsStage2D::Reset() {
  SimulationState& s = *body_.state;
  const ShapeDiagnostics d = MeasureShape(body_.curve);
  initial_length_ = d.length;
  tracker_ = TankTreadingTracker(0);
  tracker_.UpdateRelative(0.0, body_.X.col(0) - d.centroid, d.inclination);
  MarkerArcElements(body_.curve, body_.dl);
  MeasureInto(d, s);
  s.area_drift = 0.0;
}

void DiagnosticsStage2D::Run(long step) {
  SimulationState& s = *body_.state;
  const ShapeDiagnostics d = MeasureShape(body_.curve);
  const double drift = RelativeAreaDrift(d.area, body_.initial_area);
  if (!std::isfinite(d.area) || std::abs(drift) > scene_.numerics.area_drift_limit) {
    // The usual cause is a gap between markers through which the immersed boundary leaks:
    // name the spacing, and for a drop the cure (its markers are not material and bunch).
    s.area_drift = drift;
    double smallest = 1e300, largest = 0.0;
    for (int k = 0; k < body_.X.cols(); ++k) {
      const double l = body_.curve.SegmentArcLength(k);
      smallest = std::min(smallest, l);
      largest = std::max(largest, l);
    }
    std::string hint =
        "; marker spacing " + FormatValue(smallest) + " .. " + FormatValue(largest) + " h";
    if (scene_.membrane == MembraneKind::kDrop && scene_.numerics.redistribute_markers == 0.0) {
      hint +=
          " (a drop's markers drift along its surface and bunch, leaving gaps the flow leaks "
          "through: set numerics.redistribute_markers = 2)";
    } else if (largest > 2.0) {
      hint += " (gaps > 2 h leak: raise M)";
    }
    FailStep(step, "enclosed area drifted by " + FormatValue(100.0 * drift) + "% (limit " +
                       FormatValue(100.0 * scene_.numerics.area_drift_limit) +
                       "%, numerics.area_drift_limit)" + hint);
  }
  const double time = s.time + (scene_.has_shear() ? body_.shear_rate : units_.dt);
  tracker_.UpdateRelative(time, body_.X.col(0) - d.centroid, d.inclination);
  s.step = step;
  s.time = time;
  MeasureInto(d, s);
}

void DiagnosticsStage2D::Save(CheckpointWriter& w) const { w.Pod(tracker_.snapshot()); }

void DiagnosticsStage2D::Restore(CheckpointReader& r) {
  tracker_.Restore(r.Pod<TankTreadingTracker::Snapshot>());
  SimulationState& s = *body_.state;
  MeasureInto(MeasureShape(body_.curve), s);
  double max_speed2 = 0.0;
  const auto& ux = fluid_.ux();
  const auto& uy = fluid_.uy();
  for (std::size_t i = 0; i < ux.size(); ++i) {
    max_speed2 = std::max(max_speed2, ux[i] * ux[i] + uy[i] * uy[i]);
  }
  s.max_mach = std::sqrt(max_speed2) / kLatticeSoundSpeed;
}

}  // namespace ehd
