// Tank-treading and tumbling tracker.
//
// Tank-treading (song2019 sec. 5.1, around line 1837): the membrane rotates about the enclosed
// fluid with period T; the normalised frequency is f = 4 pi / (k T) with k the shear rate, so a
// rigid circle turning with the fluid's vorticity (angular speed k/2) has f = 1.
// The tracker follows one material marker: its angle about the centroid, unwrapped in time
// (tt_phase, radians, counter-clockwise positive; in the shear u = (k y, 0) with k > 0 the
// membrane turns clockwise, so the phase decreases). T is the time the phase takes to change by
// 2 pi, measured between the last two crossings of multiples of 2 pi from the initial phase
// (crossing times linearly interpolated between samples).
//
// Tumbling: the inclination theta (in (-pi/2, pi/2], period pi) is unwrapped in time; the shape
// tumbles when the unwrapped theta leaves [-pi/2, pi/2] (it passes -pi/2 for k > 0), i.e. the
// long axis turns through the vertical instead of settling at a steady angle.
// Samples must be taken often enough that the marker turns by less than pi and theta by less than
// pi/2 between updates. The phase is unwrapped from the raw angle difference of two samples
// (turn = angle - last angle, brought into [-pi, pi]), not from the accumulated phase, so it loses
// no precision as |phase| grows.
#pragma once

#include <Eigen/Core>
#include <limits>

namespace ehd {

class TankTreadingTracker {
 public:
  explicit TankTreadingTracker(int tracked_marker = 0);

  // Records the tracked marker's angle about the centroid at `time`; if inclination is given
  // (finite), also unwraps it for tumbling detection. Times must increase.
  void Update(double time, const Eigen::Matrix2Xd& markers, const Eigen::Vector2d& centroid,
              double inclination = std::numeric_limits<double>::quiet_NaN());
  // The same from the tracked point's position relative to the centroid, projected on the shear
  // plane (x, y): what a 3D surface passes for its material vertex.
  void UpdateRelative(double time, const Eigen::Vector2d& relative_position,
                      double inclination = std::numeric_limits<double>::quiet_NaN());

  int tracked_marker() const { return tracked_marker_; }
  // Unwrapped angle of the tracked marker about the centroid (tt_phase), radians.
  double phase() const { return phase_; }
  // Number of full turns completed (sign: + counter-clockwise).
  int revolutions() const { return revolutions_; }
  // Duration of the last complete turn; NaN until two crossings of 2 pi multiples were seen
  // (the first crossing after the start counts from the initial phase, so one full turn suffices).
  double period() const { return period_; }
  // f = 4 pi / (k T); NaN without a period. Throws if shear_rate == 0.
  double frequency(double shear_rate) const;
  // Mean angular speed (phase - initial phase) / (time - initial time); NaN before two samples.
  double mean_angular_speed() const;

  // Unwrapped inclination (NaN if never given) and whether it has left [-pi/2, pi/2].
  double unwrapped_inclination() const { return theta_; }
  bool tumbling() const { return tumbling_; }
  // Number of half turns of the long axis (flips through the vertical) so far.
  int flips() const { return flips_; }

  // Everything the tracker has accumulated, for checkpoints (restored bit-for-bit).
  struct Snapshot {
    int samples = 0;
    double t0 = 0, t = 0, phase0 = 0, phase = 0, last_angle = 0;
    int revolutions = 0;
    double last_crossing_time = 0, period = 0, theta = 0;
    int tumbling = 0, flips = 0;
  };
  Snapshot snapshot() const;
  void Restore(const Snapshot& s);

 private:
  int tracked_marker_;
  int samples_ = 0;
  double t0_ = 0.0, t_ = 0.0;
  double phase0_ = 0.0, phase_ = 0.0;
  double last_angle_ = 0.0;  // raw angle of the last sample, in (-pi, pi]
  int revolutions_ = 0;
  double last_crossing_time_ = std::numeric_limits<double>::quiet_NaN();
  double period_ = std::numeric_limits<double>::quiet_NaN();
  double theta_ = std::numeric_limits<double>::quiet_NaN();
  bool tumbling_ = false;
  int flips_ = 0;
};

}  // namespace ehd
