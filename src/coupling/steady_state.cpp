#include "ehd_capsule/coupling/steady_state.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {

SteadyStateMonitor::SteadyStateMonitor(double tolerance, double window, double dxy_floor)
    : tolerance_(tolerance), window_(window), dxy_floor_(dxy_floor) {
  if (!(tolerance > 0.0)) {
    throw std::invalid_argument("steady-state tolerance = " + std::to_string(tolerance) +
                                ": accepted > 0");
  }
  if (!(dxy_floor > 0.0)) {
    throw std::invalid_argument("steady-state D_xy floor = " + std::to_string(dxy_floor) +
                                ": accepted > 0");
  }
  if (!(window > 0.0)) {
    throw std::invalid_argument("steady-state window = " + std::to_string(window) +
                                ": accepted > 0");
  }
}

void SteadyStateMonitor::Push(std::deque<Sample>& q, double t, double v, bool keep_min) {
  while (!q.empty() && (keep_min ? q.back().value >= v : q.back().value <= v)) q.pop_back();
  q.push_back({t, v});
}

void SteadyStateMonitor::Expire(std::deque<Sample>& q, double t_cut) {
  while (!q.empty() && q.front().t < t_cut) q.pop_front();
}

bool SteadyStateMonitor::Update(double time, double dxy, double inclination) {
  if (!started_) {
    started_ = true;
    first_time_ = time;
  }
  Push(dxy_min_, time, dxy, true);
  Push(dxy_max_, time, dxy, false);
  Push(theta_min_, time, inclination, true);
  Push(theta_max_, time, inclination, false);
  const double t_cut = time - window_;
  for (auto* q : {&dxy_min_, &dxy_max_, &theta_min_, &theta_max_}) Expire(*q, t_cut);
  if (first_time_ > t_cut) return steady_ = false;
  const double dxy_scale = std::max(std::abs(dxy), dxy_floor_);
  return steady_ = (dxy_max_.front().value - dxy_min_.front().value < tolerance_ * dxy_scale &&
                    theta_max_.front().value - theta_min_.front().value < tolerance_ * M_PI);
}

}  // namespace ehd
