// The diagnostics stage (coupling/stages/diagnostics_stage.h).
#include "ehd_capsule/coupling/stages/diagnostics_stage.h"

#include <cmath>
#include <sstream>

#include "ehd_capsule/ib/marker_update.h"

namespace ehd {
namespace {

ShapeDiagnostics MeasureBody(const Body<2>& body) { return MeasureShape(body.shape.curve); }
ShapeDiagnostics3D MeasureBody(const Body<3>& body) { return MeasureShape3D(body.shape.mesh); }

// The tracked point's offset from the centroid in the shear plane x-y.
Eigen::Vector2d TrackedOffset(const Body<2>& body, const ShapeDiagnostics& d) {
  return body.positions().col(body.tracked_point) - d.centroid;
}
Eigen::Vector2d TrackedOffset(const Body<3>& body, const ShapeDiagnostics3D& d) {
  const Eigen::Vector3d r = body.positions().col(body.tracked_point) - d.centroid;
  return Eigen::Vector2d(r.x(), r.y());
}

}  // namespace

template <int D>
DiagnosticsStage<D>::DiagnosticsStage(const Scene& scene, const LatticeUnits& units,
                                      StepData<D>& data, const FluidOf<D>& fluid)
    : scene_(scene), units_(units), data_(data), fluid_(fluid) {
  for (const Body<D>& body : data.bodies) {
    electric_.push_back(body.FindForceSource("electric"));
    tracked_.emplace_back();
  }
}

template <int D>
std::string DiagnosticsStage<D>::Describe() const {
  std::ostringstream out;
  const char* point = BodyShape<D>::kPointName;
  if constexpr (D == 2) {
    out << "D_xy and inclination of the equivalent ellipse, tank-treading phase of marker 0; ";
  } else {
    out << "D_xy and inclination of the equivalent ellipsoid in the shear plane, tank-treading "
           "phase of vertex "
        << data_.bodies.front().tracked_point << "; ";
  }
  out << "watchdogs: non-finite values, Mach > " << scene_.numerics.max_mach << ", |"
      << (D == 2 ? "area" : "volume") << " drift| > " << scene_.numerics.area_drift_limit << ", a "
      << point << " within 2h of a wall";
  if (D == 2 && electric_.front() != nullptr) out << ", GMRES not converged";
  return out.str();
}

template <int D>
void DiagnosticsStage<D>::MeasureInto(const Shape& d, SimulationState& s) const {
  const Body<D>& body = data_.bodies.front();
  const ForceSource<D>* electric = electric_.front();
  const int n = body.size();
  s.dimension = D;
  s.markers.setZero(3, n);
  s.markers.template topRows<D>() = body.positions();
  if (electric != nullptr) {
    s.electric_force.setZero(3, n);
    s.electric_force.template topRows<D>() = electric->traction;
    if constexpr (D == 2) {
      Eigen::Vector2d total(0, 0);
      for (int k = 0; k < n; ++k) total += electric->load.col(k) * body.dl[k];
      s.electric_force_total = Eigen::Vector3d(total.x(), total.y(), 0.0);
    } else {
      // A plain loop: Eigen's vectorised reduction sums in an order that follows the array's
      // alignment, which moved this near-zero total (a neutral drop's) by 1e-15 between builds.
      Eigen::Vector3d total = Eigen::Vector3d::Zero();
      for (int k = 0; k < n; ++k) total += electric->load.col(k);
      s.electric_force_total = total;
    }
  } else {
    s.electric_force.resize(3, 0);
  }
  s.dxy = d.dxy;
  s.inclination = d.inclination;
  s.stresslet_xy = 0.0;
  if (units_.shear_rate > 0.0 && body.force.cols() == n) {
    // -sum sym(r F)_xy over the spread forces (membrane plus every force term), at the points
    // they were spread at.
    double sxy = 0.0;
    for (int k = 0; k < n; ++k) {
      const double rx = body.coupling_points()(0, k) - d.centroid.x();
      const double ry = body.coupling_points()(1, k) - d.centroid.y();
      sxy -= 0.5 * (rx * body.force(1, k) + ry * body.force(0, k));
    }
    s.stresslet_xy = sxy / (units_.viscosity * units_.shear_rate * std::pow(units_.radius, D));
  }
  s.tt_phase = tracked_.front().tracker.phase();
  if constexpr (D == 2) {
    const double initial_length = tracked_.front().initial_length;
    s.area = d.area;
    s.area_drift = RelativeAreaDrift(d.area, body.initial_measure);
    s.surface_drift = initial_length > 0.0 ? d.length / initial_length - 1.0 : 0.0;
  } else {
    s.area = d.volume;
    s.area_drift = d.volume / body.initial_measure - 1.0;
    s.surface_drift = d.area / body.initial_surface - 1.0;
    s.volume_corrected = body.volume_corrected;
    s.d_field = d.dz;
    // body.U: the vertex velocities of the last marker step (lattice units), none before it.
    s.surface_flow = body.U.cols() == n
                         ? MeasureMeridionalFlow(body.shape.mesh, body.U, d.centroid) *
                               units_.steps_per_time_unit / units_.radius
                         : 0.0;
  }
}

template <int D>
void DiagnosticsStage<D>::Reset() {
  for (std::size_t i = 0; i < data_.bodies.size(); ++i) {
    Body<D>& body = data_.bodies[i];
    Tracked& tracked = tracked_[i];
    const Shape d = MeasureBody(body);
    if constexpr (D == 2) {
      tracked.initial_length = d.length;
      body.tracked_point = 0;
      MarkerArcElements(body.shape.curve, body.dl);
    } else {
      // The tank-treading vertex: the one farthest along +x on the equator z = z_c.
      const Eigen::Matrix3Xd& x = body.positions();
      int best = 0;
      double best_score = -1e300;
      for (int k = 0; k < x.cols(); ++k) {
        const double score = (x(0, k) - d.centroid.x()) - 10.0 * std::abs(x(2, k) - d.centroid.z());
        if (score > best_score) {
          best_score = score;
          best = k;
        }
      }
      body.tracked_point = best;
      tracked.initial_min_angle = MeasureQuality(body.shape.mesh).min_angle_deg;
    }
    tracked.tracker = TankTreadingTracker(0);
    tracked.tracker.UpdateRelative(0.0, TrackedOffset(body, d), d.inclination);
    if (i == 0) {
      MeasureInto(d, *data_.state);
      data_.state->area_drift = 0.0;
    }
  }
}

template <int D>
void DiagnosticsStage<D>::Watch(long step, const Body<D>& body, const Tracked& tracked,
                                const Shape& d) const {
  const double limit = scene_.numerics.area_drift_limit;
  if constexpr (D == 2) {
    const double drift = RelativeAreaDrift(d.area, body.initial_measure);
    if (!std::isfinite(d.area) || std::abs(drift) > limit) {
      // The usual cause is a gap between markers through which the immersed boundary leaks:
      // name the spacing, and for a drop the cure (its markers are not material and bunch).
      data_.state->area_drift = drift;
      double smallest = 1e300, largest = 0.0;
      for (int k = 0; k < body.size(); ++k) {
        const double l = body.shape.curve.SegmentArcLength(k);
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
                         FormatValue(100.0 * limit) + "%, numerics.area_drift_limit)" + hint);
    }
  } else {
    // The watchdog sees the leak itself: the drift plus what the volume correction restored.
    const double drift = d.volume / body.initial_measure - 1.0 - body.volume_corrected;
    if (!std::isfinite(drift) || std::abs(drift) > limit) {
      // The usual cause is an edge longer than 2 h: the immersed boundary leaks through the gap.
      const MeshQuality q = MeasureQuality(body.shape.mesh);
      FailStep(step, "enclosed volume drifted by " + FormatValue(100.0 * drift) + "%" +
                         (body.volume_corrected != 0.0 ? " (before the volume correction)" : "") +
                         " (limit " + FormatValue(100.0 * limit) +
                         "%, numerics.area_drift_limit); " + q.Describe() +
                         (q.max_edge > 2.0 ? " (edges > 2 h leak: raise mesh_subdivisions)" : ""));
    }
    // Mesh-scale instability: vertices closer than a grid cell carry modes the immersed boundary
    // cannot see, which can grow until triangles fold (the 3D counterpart of the 2D markers'
    // sawtooth mode). Every 20 steps, a triangle angle below 5 degrees stops the run naming it,
    // before the fold becomes a NaN or a Mach blow-up.
    if (step % 20 == 0) {
      const MeshQuality q = MeasureQuality(body.shape.mesh);
      if (q.min_angle_deg < 5.0) {
        FailStep(step, "membrane mesh degenerating: smallest triangle angle " +
                           FormatValue(q.min_angle_deg) + " deg (initially " +
                           FormatValue(tracked.initial_min_angle) +
                           "): triangles folding (a mesh-scale instability: use fewer vertices per "
                           "grid cell, i.e. mesh_subdivisions lower or N higher, or more bending "
                           "E_b) or stretched beyond use (the mesh is not refined as it stretches: "
                           "lower Ca or raise mesh_subdivisions); " +
                           q.Describe());
      }
    }
  }
}

template <int D>
void DiagnosticsStage<D>::Run(long step) {
  for (std::size_t i = 0; i < data_.bodies.size(); ++i) {
    const Body<D>& body = data_.bodies[i];
    Shape d;
    try {
      d = MeasureBody(body);
    } catch (const std::exception& e) {
      FailStep(step, e.what());
    }
    Watch(step, body, tracked_[i], d);
    tracked_[i].tracker.UpdateRelative(data_.time, TrackedOffset(body, d), d.inclination);
    if (i == 0) MeasureInto(d, *data_.state);
  }
}

template <int D>
void DiagnosticsStage<D>::Save(CheckpointWriter& w) const {
  for (std::size_t i = 0; i < tracked_.size(); ++i) {
    if constexpr (D == 3) w.Pod(static_cast<std::int32_t>(data_.bodies[i].tracked_point));
    w.Pod(tracked_[i].tracker.snapshot());
  }
}

template <int D>
void DiagnosticsStage<D>::Restore(CheckpointReader& r) {
  for (std::size_t i = 0; i < tracked_.size(); ++i) {
    if constexpr (D == 3) data_.bodies[i].tracked_point = r.Pod<std::int32_t>();
    tracked_[i].tracker.Restore(r.Pod<TankTreadingTracker::Snapshot>());
  }
  SimulationState& s = *data_.state;
  MeasureInto(MeasureBody(data_.bodies.front()), s);
  s.max_mach = fluid_.MaxSpeed() / kLatticeSoundSpeed;
}

template class DiagnosticsStage<2>;
template class DiagnosticsStage<3>;

}  // namespace ehd
