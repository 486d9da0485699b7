// Tank-treading phase / period / frequency f = 4 pi / (k T) (song2019 sec. 5.1) and tumbling
// detection from the unwrapped inclination; see tank_treading.h.
#include "ehd_capsule/diagnostics/tank_treading.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {
namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kTwoPi = 2.0 * kPi;

// Brings a - b into (-period/2, period/2].
double WrapDifference(double a, double b, double period) {
  double d = std::fmod(a - b, period);
  if (d > 0.5 * period) d -= period;
  if (d <= -0.5 * period) d += period;
  return d;
}

}  // namespace

TankTreadingTracker::TankTreadingTracker(int tracked_marker) : tracked_marker_(tracked_marker) {
  if (tracked_marker < 0) {
    throw std::invalid_argument("TankTreadingTracker: tracked_marker must be >= 0, got " +
                                std::to_string(tracked_marker));
  }
}

void TankTreadingTracker::Update(double time, const Eigen::Matrix2Xd& markers,
                                 const Eigen::Vector2d& centroid, double inclination) {
  if (tracked_marker_ >= markers.cols()) {
    throw std::invalid_argument("TankTreadingTracker: tracked marker " +
                                std::to_string(tracked_marker_) + " but only " +
                                std::to_string(markers.cols()) + " markers");
  }
  UpdateRelative(time, markers.col(tracked_marker_) - centroid, inclination);
}

void TankTreadingTracker::UpdateRelative(double time, const Eigen::Vector2d& r,
                                         double inclination) {
  if (samples_ > 0 && !(time > t_)) {
    throw std::invalid_argument("TankTreadingTracker: time must increase (got " +
                                std::to_string(time) + " after " + std::to_string(t_) + ")");
  }
  const double angle = std::atan2(r.y(), r.x());
  if (samples_ == 0) {
    t0_ = t_ = time;
    phase0_ = phase_ = angle;
    last_crossing_time_ = time;
  } else {
    double turn = angle - last_angle_;
    if (turn > kPi) turn -= kTwoPi;
    if (turn < -kPi) turn += kTwoPi;
    const double new_phase = phase_ + turn;
    // Crossing of phase0 + 2 pi n between the two samples (either direction).
    const double before = (phase_ - phase0_) / kTwoPi, after = (new_phase - phase0_) / kTwoPi;
    const int turns_before = static_cast<int>(std::trunc(before));
    const int turns_after = static_cast<int>(std::trunc(after));
    if (turns_after != turns_before && turns_after != 0) {
      const double level = turns_after * kTwoPi + phase0_;
      const double crossing = t_ + (time - t_) * (level - phase_) / (new_phase - phase_);
      period_ = crossing - last_crossing_time_;
      last_crossing_time_ = crossing;
      revolutions_ = turns_after;
    }
    phase_ = new_phase;
    t_ = time;
  }
  last_angle_ = angle;
  ++samples_;
  if (std::isfinite(inclination)) {
    theta_ =
        std::isfinite(theta_) ? theta_ + WrapDifference(inclination, theta_, kPi) : inclination;
    const int flips = static_cast<int>(std::floor(std::abs(theta_) / kPi + 0.5));
    if (flips > flips_) flips_ = flips;
    if (theta_ < -0.5 * kPi || theta_ > 0.5 * kPi) tumbling_ = true;
  }
}

TankTreadingTracker::Snapshot TankTreadingTracker::snapshot() const {
  Snapshot s;
  s.samples = samples_;
  s.t0 = t0_;
  s.t = t_;
  s.phase0 = phase0_;
  s.phase = phase_;
  s.last_angle = last_angle_;
  s.revolutions = revolutions_;
  s.last_crossing_time = last_crossing_time_;
  s.period = period_;
  s.theta = theta_;
  s.tumbling = tumbling_ ? 1 : 0;
  s.flips = flips_;
  return s;
}

void TankTreadingTracker::Restore(const Snapshot& s) {
  samples_ = s.samples;
  t0_ = s.t0;
  t_ = s.t;
  phase0_ = s.phase0;
  phase_ = s.phase;
  last_angle_ = s.last_angle;
  revolutions_ = s.revolutions;
  last_crossing_time_ = s.last_crossing_time;
  period_ = s.period;
  theta_ = s.theta;
  tumbling_ = s.tumbling != 0;
  flips_ = s.flips;
}

double TankTreadingTracker::frequency(double shear_rate) const {
  if (shear_rate == 0.0) throw std::invalid_argument("TankTreadingTracker: shear_rate is 0");
  return 4.0 * kPi / (std::abs(shear_rate) * period_);
}

double TankTreadingTracker::mean_angular_speed() const {
  if (samples_ < 2) return std::numeric_limits<double>::quiet_NaN();
  return (phase_ - phase0_) / (t_ - t0_);
}

}  // namespace ehd
