// Stage 5 of the coupled step: interpolate u^{n+1} to the markers (song2019 eq. (104)), move them
// (eq. (105) forward Euler, or Adams-Bashforth 2), remove the sawtooth mode every
// numerics.marker_filter_every steps, wrap the curve periodically, check that it stayed inside
// the walls, and for drops re-space bunched markers (numerics.redistribute_markers).
#include <algorithm>
#include <sstream>

#include "ehd_capsule/coupling/capsule_stages_2d.h"

namespace ehd {
namespace {

MarkerIntegrator IntegratorOf(const Scene& scene) {
  return scene.numerics.integrator == MarkerTimeScheme::kAdamsBashforth2
             ? MarkerIntegrator::kAdamsBashforth2
             : MarkerIntegrator::kForwardEuler;
}

}  // namespace

MarkerStage2D::MarkerStage2D(const Scene& scene, const Grid2D& grid, const ImmersedBoundary& ib,
                             MembraneMarkers2D& body, const LatticeBoltzmann2D& fluid,
                             ElectricStage2D* electric)
    : scene_(scene),
      grid_(grid),
      ib_(ib),
      body_(body),
      fluid_(fluid),
      electric_(electric),
      advector_(IntegratorOf(scene)),
      sawtooth_(std::clamp((static_cast<int>(body.initial.cols()) - 1) / 2, 1, 8)) {}

std::string MarkerStage2D::Describe() const {
  std::ostringstream out;
  out << "interpolate u, "
      << (advector_.scheme() == MarkerIntegrator::kAdamsBashforth2 ? "Adams-Bashforth 2"
                                                                   : "forward Euler");
  if (scene_.numerics.redistribute_markers > 0.0) {
    out << ", re-spaced evenly when max/min spacing > " << scene_.numerics.redistribute_markers;
  }
  if (scene_.numerics.marker_filter_every > 0) {
    out << ", sawtooth filter (order " << sawtooth_.order() << ") every "
        << scene_.numerics.marker_filter_every << " steps";
  }
  return out.str();
}

void MarkerStage2D::Reset() {
  advector_.Reset();
  redistributions_ = 0;
}

void MarkerStage2D::Run(long step) {
  ib_.Interpolate(fluid_.ux(), fluid_.uy(), body_.X, body_.U);
  advector_.Advance(body_.U, 1.0, body_.X);
  if (scene_.numerics.marker_filter_every > 0 && step % scene_.numerics.marker_filter_every == 0) {
    sawtooth_.Apply(body_.X);
  }
  if (scene_.has_shear()) WrapCurveIntoDomain(grid_, body_.X);

  if (!body_.X.allFinite()) FailStep(step, "marker position is not finite (NaN/Inf)");
  const double margin = 2.0 * grid_.h;
  for (int k = 0; k < body_.X.cols(); ++k) {
    const double y = body_.X(1, k);
    if (y < grid_.y0 + margin || y > grid_.y_max() - margin) {
      FailStep(step, "marker " + std::to_string(k) + " at y = " + FormatValue(y) +
                         " is within 2h of the wall y = " +
                         FormatValue(y < 0 ? grid_.y0 : grid_.y_max()) +
                         " (the membrane left the domain)");
    }
    if (!scene_.has_shear()) {
      const double x = body_.X(0, k);
      if (x < grid_.x0 + margin || x > grid_.x_max() - margin) {
        FailStep(step, "marker " + std::to_string(k) + " at x = " + FormatValue(x) +
                           " is within 2h of the side wall (the membrane left the domain)");
      }
    }
  }
  try {
    body_.curve.Update(body_.X);
  } catch (const std::exception& e) {
    FailStep(step, std::string("membrane curve is degenerate: ") + e.what());
  }
  if (scene_.numerics.redistribute_markers > 0.0) RedistributeBunchedMarkers();
}

void MarkerStage2D::RedistributeBunchedMarkers() {
  // Drops (numerics.redistribute_markers = r): when the largest / smallest segment exceeds r,
  // re-space the markers evenly in the curve's (chord-length) parameter from marker 0, which stays
  // where it is (it carries tt_phase). The AB2 velocity history and the electric warm start G are
  // carried over by the curve's periodic spline; the potential is re-solved at the next step.
  const ClosedCurve& curve = body_.curve;
  const int n = static_cast<int>(body_.X.cols());
  double shortest = curve.SegmentArcLength(0), longest = shortest;
  for (int k = 1; k < n; ++k) {
    const double l = curve.SegmentArcLength(k);
    shortest = std::min(shortest, l);
    longest = std::max(longest, l);
  }
  if (!(longest > scene_.numerics.redistribute_markers * shortest)) return;
  const double s0 = curve.knot(0), period = curve.period();
  auto new_parameter = [&](int k) { return s0 + period * k / n; };
  auto resample = [&](std::vector<double>& v) {
    const PeriodicCubicSpline f = curve.FitScalar(v);
    for (int k = 0; k < n; ++k) v[k] = f.Value(new_parameter(k));
  };
  if (Eigen::Matrix2Xd* previous = advector_.mutable_previous_velocity()) {
    std::vector<double> values(n);
    for (int c = 0; c < 2; ++c) {
      for (int k = 0; k < n; ++k) values[k] = (*previous)(c, k);
      resample(values);
      for (int k = 0; k < n; ++k) (*previous)(c, k) = values[k];
    }
  }
  if (electric_ != nullptr) electric_->Respaced(resample);
  Eigen::Matrix2Xd x(2, n);
  x.col(0) = body_.X.col(0);
  for (int k = 1; k < n; ++k) x.col(k) = curve.At(new_parameter(k)).position;
  body_.X = x;
  body_.curve.Update(body_.X);
  ++redistributions_;
}

void MarkerStage2D::Save(CheckpointWriter& w) const {
  w.Mat(advector_.previous_velocity());
  w.Pod(static_cast<std::int32_t>(advector_.has_previous_velocity()));
  w.Pod(redistributions_);
}

void MarkerStage2D::Restore(CheckpointReader& r) {
  const Eigen::Matrix2Xd previous = r.Mat<2>();
  const bool has_previous = r.Pod<std::int32_t>() != 0;
  if (has_previous && previous.cols() != body_.X.cols()) r.Fail("marker velocity count differs");
  advector_.SetPreviousVelocity(previous, has_previous);
  redistributions_ = r.Pod<long>();
}

}  // namespace ehd
