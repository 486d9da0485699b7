// Steady-state detection for `--until-steady TOL`: the run is steady when, over the last unit of
// time (a window of length `window` in the scene's time unit, once the samples cover a full
// window), D_xy varied by less than TOL relative to itself and the inclination theta by less than
// TOL pi:
//   max D - min D < TOL max(|D|, dxy_floor),   max theta - min theta < TOL pi.
// The tolerance is relative so that a barely deformed shape (D ~ 1e-3, a drop in a weak field) is
// not called steady on its first overshoot, as an absolute tolerance did; dxy_floor (default 1e-3)
// keeps it meaningful for D -> 0. Samples must arrive with increasing time. Sliding-window
// minima/maxima with monotone deques: O(1) amortised per sample.
#pragma once

#include <deque>

namespace ehd {

class SteadyStateMonitor {
 public:
  static constexpr double kDefaultDxyFloor = 1e-3;
  explicit SteadyStateMonitor(double tolerance, double window = 1.0,
                              double dxy_floor = kDefaultDxyFloor);
  // Adds a sample; returns true once the window is covered and both ranges are below tolerance.
  bool Update(double time, double dxy, double inclination);
  bool steady() const { return steady_; }

 private:
  struct Sample {
    double t, value;
  };
  // Monotone deque: front is the min (or max) of the samples in the window.
  static void Push(std::deque<Sample>& q, double t, double v, bool keep_min);
  static void Expire(std::deque<Sample>& q, double t_cut);
  double tolerance_, window_, dxy_floor_;
  double first_time_ = 0.0;
  bool started_ = false;
  std::deque<Sample> dxy_min_, dxy_max_, theta_min_, theta_max_;
  bool steady_ = false;
};

}  // namespace ehd
