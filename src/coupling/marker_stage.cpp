// The marker stage (coupling/stages/marker_stage.h).
#include "ehd_capsule/coupling/stages/marker_stage.h"

#include <algorithm>
#include <cstdint>
#include <sstream>

#include "ehd_capsule/coupling/retracted_points.h"
#include "ehd_capsule/geometry/mesh_relaxation.h"

namespace ehd {
namespace {

MarkerIntegrator IntegratorOf(const Scene& scene) {
  return scene.numerics.integrator == MarkerTimeScheme::kAdamsBashforth2
             ? MarkerIntegrator::kAdamsBashforth2
             : MarkerIntegrator::kForwardEuler;
}

}  // namespace

template <int D>
MarkerStage<D>::MarkerStage(const Scene& scene, const Grid<D>& grid,
                            const ImmersedBoundaryTransfer<D>& ib, StepData<D>& data,
                            const FluidOf<D>& fluid)
    : scene_(scene), grid_(grid), ib_(ib), data_(data), fluid_(fluid) {
  for (const Body<D>& body : data.bodies) {
    advectors_.emplace_back(IntegratorOf(scene));
    if constexpr (D == 2) {
      filters_.push_back(std::make_unique<SawtoothFilter>(
          std::clamp((static_cast<int>(body.initial.cols()) - 1) / 2, 1, 8)));
    } else if (scene.numerics.marker_filter_every > 0) {
      filters_.push_back(std::make_unique<MeshScaleFilter>(body.shape.mesh,  // the rest mesh
                                                           scene.numerics.mesh_filter_order));
    } else {
      filters_.push_back(nullptr);
    }
  }
}

template <int D>
std::string MarkerStage<D>::Describe() const {
  std::ostringstream out;
  out << (D == 3 && scene_.membrane == MembraneKind::kDrop
              ? "interpolate u at the vertices, move them with its normal part and the mean (a "
                "drop's vertices are not material), "
          : D == 3 ? "interpolate u at the vertices, "
                   : "interpolate u, ")
      << (advectors_.front().scheme() == MarkerIntegrator::kAdamsBashforth2 ? "Adams-Bashforth 2"
                                                                            : "forward Euler");
  if (scene_.numerics.ib_retraction > 0.0) {
    out << ", u interpolated at the points retracted " << scene_.numerics.ib_retraction << " h"
        << (scene_.numerics.ib_extrapolate_velocity != 0
                ? " and extrapolated to the points by the body's velocity gradient"
                : "")
        << ", its net flux through the membrane removed";
  }
  if (D == 2 && scene_.numerics.redistribute_markers > 0.0) {
    out << ", re-spaced evenly when max/min spacing > " << scene_.numerics.redistribute_markers;
  }
  const Filter* filter = filters_.front().get();
  if (scene_.numerics.marker_filter_every > 0 && filter != nullptr) {
    out << (D == 2 ? ", sawtooth filter (order " : ", mesh-scale filter of the deformation (order ")
        << filter->order() << ") every " << scene_.numerics.marker_filter_every << " steps";
  }
  if (scene_.numerics.volume_correction_every > 0) {
    out << ", the enclosed volume restored to its initial value (a uniform normal displacement) "
           "every "
        << scene_.numerics.volume_correction_every << " steps";
  }
  if (scene_.numerics.relax_mesh_every > 0) {
    out << ", vertices relaxed along the surface every " << scene_.numerics.relax_mesh_every
        << " steps";
  }
  return out.str();
}

template <int D>
void MarkerStage<D>::Reset() {
  for (PointAdvector<D>& a : advectors_) a.Reset();
  redistributions_ = 0;
}

template <int D>
void MarkerStage<D>::Run(long step) {
  for (std::size_t i = 0; i < data_.bodies.size(); ++i) {
    Move(step, static_cast<int>(i), data_.bodies[i]);
  }
}

template <int D>
void MarkerStage<D>::Move(long step, int index, Body<D>& body) {
  const double retraction = scene_.numerics.ib_retraction * grid_.h;
  if (retraction > 0.0) {
    // The points the spread stage retracted this step (coupling/retracted_points.h): the
    // positions have not moved since.
    if (body.coupling.cols() != body.size())
      RetractAlongNormals(body.shape, retraction, body.coupling);
    ib_.Interpolate(VelocityOf<D>(fluid_), body.coupling, body.U);
    if (scene_.numerics.ib_extrapolate_velocity != 0) {
      try {
        ExtrapolateToPoints(body.coupling, body.positions(), body.U);
      } catch (const std::exception& e) {
        FailStep(step, e.what());
      }
    }
    RemoveEnclosedMeasureRate(body.shape, body.U);
  } else {
    ib_.Interpolate(VelocityOf<D>(fluid_), body.positions(), body.U);
  }
  scratch_ = body.positions();
  PointAdvector<D>& advector = advectors_[index];
  if constexpr (D == 3) {
    if (scene_.membrane == MembraneKind::kDrop) {
      advector.Advance(DropVertexVelocity(body.shape.mesh, body.U), 1.0, scratch_);
    } else {
      advector.Advance(body.U, 1.0, scratch_);
    }
  } else {
    advector.Advance(body.U, 1.0, scratch_);
  }
  const int every = scene_.numerics.marker_filter_every;
  if (every > 0 && step % every == 0 && filters_[index]) filters_[index]->Apply(scratch_);
  if constexpr (D == 3) {
    const int volume_every = scene_.numerics.volume_correction_every;
    if (volume_every > 0 && step % volume_every == 0 && scratch_.allFinite()) {
      // The immersed boundary's leak (its interpolated velocity is not exactly divergence-free
      // at the surface) changes the enclosed volume slowly; an incompressible inside keeps it.
      const auto& triangles = body.shape.mesh.triangles();
      const double before = EnclosedVolume(scratch_, triangles);
      try {
        RestoreEnclosedVolume(triangles, body.initial_measure, scratch_);
      } catch (const std::exception& e) {
        FailStep(step, std::string("volume correction failed: ") + e.what());
      }
      body.volume_corrected += (body.initial_measure - before) / body.initial_measure;
    }
  }
  if (scene_.has_shear()) {
    if constexpr (D == 2) {
      WrapCurveIntoDomain(grid_, scratch_);
    } else {
      WrapSurfaceIntoDomain(grid_, {ib_.periodic(0), ib_.periodic(1), ib_.periodic(2)}, scratch_);
    }
  }
  if (!scratch_.allFinite()) {
    FailStep(step, std::string(BodyShape<D>::kPointName) + " position is not finite (NaN/Inf)");
  }
  CheckInside(step, scratch_);
  try {
    body.shape.SetPositions(scratch_);
  } catch (const std::exception& e) {
    FailStep(step, std::string("membrane curve is degenerate: ") + e.what());
  }
  if constexpr (D == 2) {
    if (scene_.numerics.redistribute_markers > 0.0) RedistributeBunchedMarkers(index, body);
  } else {
    const int relax_every = scene_.numerics.relax_mesh_every;
    if (relax_every > 0 && step % relax_every == 0) {
      RelaxMeshTangentially(body.shape.mesh, 1, 0.5, grid_.h);
    }
  }
}

template <int D>
void MarkerStage<D>::CheckInside(long step, const PointsOf<D>& x) const {
  // Along a bounded axis the kernel's support must stay inside: a point within 2 h of a wall
  // loses part of its spread force (immersed_boundary.h).
  const double margin = 2.0 * grid_.h;
  for (int k = 0; k < x.cols(); ++k) {
    for (int a = 0; a < D; ++a) {
      if (ib_.periodic(a)) continue;
      const double v = x(a, k), lo = grid_.origin(a),
                   hi = grid_.origin(a) + grid_.extent(a) * grid_.h;
      if (v < lo + margin || v > hi - margin) {
        const std::string axis(1, "xyz"[a]);
        FailStep(step, std::string(BodyShape<D>::kPointName) + " " + std::to_string(k) + " at " +
                           axis + " = " + FormatValue(v) + " is within 2h of the wall " + axis +
                           " = " + FormatValue(v < 0 ? lo : hi) +
                           " (the membrane left the domain)");
      }
    }
  }
}

template <int D>
void MarkerStage<D>::RedistributeBunchedMarkers(int index, Body<D>& body) {
  if constexpr (D == 2) {
    // Drops (numerics.redistribute_markers = r): when the largest / smallest segment exceeds r,
    // re-space the markers evenly in the curve's (chord-length) parameter from marker 0, which
    // stays where it is (it carries tt_phase). The AB2 velocity history and every per-marker
    // state registered in StepData::on_points_resampled (the electric warm start G) are carried
    // over by the curve's periodic spline; the potential is re-solved at the next step.
    const ClosedCurve& curve = body.shape.curve;
    const int n = body.size();
    double shortest = curve.SegmentArcLength(0), longest = shortest;
    for (int k = 1; k < n; ++k) {
      const double l = curve.SegmentArcLength(k);
      shortest = std::min(shortest, l);
      longest = std::max(longest, l);
    }
    if (!(longest > scene_.numerics.redistribute_markers * shortest)) return;
    const double s0 = curve.knot(0), period = curve.period();
    auto new_parameter = [&](int k) { return s0 + period * k / n; };
    const typename StepData<D>::Resample resample = [&](std::vector<double>& v) {
      const PeriodicCubicSpline f = curve.FitScalar(v);
      for (int k = 0; k < n; ++k) v[k] = f.Value(new_parameter(k));
    };
    if (Eigen::Matrix2Xd* previous = advectors_[index].mutable_previous_velocity()) {
      std::vector<double> values(n);
      for (int c = 0; c < 2; ++c) {
        for (int k = 0; k < n; ++k) values[k] = (*previous)(c, k);
        resample(values);
        for (int k = 0; k < n; ++k) (*previous)(c, k) = values[k];
      }
    }
    for (const auto& listener : data_.on_points_resampled) listener(index, resample);
    Eigen::Matrix2Xd x(2, n);
    x.col(0) = body.positions().col(0);
    for (int k = 1; k < n; ++k) x.col(k) = curve.At(new_parameter(k)).position;
    body.shape.SetPositions(x);
    ++redistributions_;
  } else {
    (void)index;
    (void)body;
  }
}

template <int D>
void MarkerStage<D>::Save(CheckpointWriter& w) const {
  for (std::size_t i = 0; i < advectors_.size(); ++i) {
    w.Mat(advectors_[i].previous_velocity());
    w.Pod(static_cast<std::int32_t>(advectors_[i].has_previous_velocity()));
    if constexpr (D == 2) {
      w.Pod(redistributions_);
    } else if (scene_.numerics.volume_correction_every > 0) {
      w.Pod(data_.bodies[i].volume_corrected);
    }
  }
}

template <int D>
void MarkerStage<D>::Restore(CheckpointReader& r) {
  for (std::size_t i = 0; i < advectors_.size(); ++i) {
    const PointsOf<D> previous = r.Mat<D>();
    const bool has_previous = r.Pod<std::int32_t>() != 0;
    if (has_previous && previous.cols() != data_.bodies[i].size()) {
      r.Fail(std::string(BodyShape<D>::kPointName) + " velocity count differs");
    }
    advectors_[i].SetPreviousVelocity(previous, has_previous);
    if constexpr (D == 2) {
      redistributions_ = r.Pod<long>();
    } else if (scene_.numerics.volume_correction_every > 0) {
      data_.bodies[i].volume_corrected = r.Pod<double>();
    }
  }
}

template class MarkerStage<2>;
template class MarkerStage<3>;

}  // namespace ehd
