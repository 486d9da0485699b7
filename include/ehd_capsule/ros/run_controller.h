// The node's run controller: the step loop, the run states (running, paused, failed, finished),
// the operator's requests (~pause, ~resume, ~advance, ~advance_by, ~reset, dynamic_reconfigure's
// Ca_E, Ca, publish_every, paused, advance_steps), the progress lines and the summary.
//
// Follows turtlesim: callbacks run in ros::spinOnce on the loop's thread, between two steps, so
// nothing needs a lock. A live Ca or Ca_E is handed to Simulation::SetCa / SetCaE at once (the
// one pending-change queue: it takes effect at the next step, or is refused with the reason,
// and the configuration handed back keeps the value the node runs with); a reset is applied in
// its service call, which answers whether it was done.
#pragma once

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include <memory>
#include <string>

#include "ehd_capsule/Advance.h"
#include "ehd_capsule/SimulationConfig.h"
#include "ehd_capsule/coupling/shown_measures.h"
#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/coupling/steady_state.h"
#include "ehd_capsule/ros/bag_recorder.h"
#include "ehd_capsule/ros/node_parameters.h"
#include "ehd_capsule/ros/node_publishers.h"

namespace ehd::ros_node {

// The measures shown: coupling/shown_measures.h (shared with ehd_sim run).
using ehd::MeasuresOf;
using ehd::ShownMeasures;

// "step 120  t = 0.3 1/k  D_xy = 0.12345  theta/pi = 0.2500  area drift = 1.00e-05  500 steps/s"
// (3D: "... D_z = 0.01234  volume drift = ...")
std::string FormatProgressLine(const SimulationState& s, const ShownMeasures& m,
                               const std::string& time_unit, double steps_per_second);
// The steps the summary's rate is over: those since the start or the last reset, and the wall
// time spent stepping them (paused time not counted; the steps of ~advance are).
struct SteppingTime {
  long steps = 0;
  double seconds = 0.0;
  bool after_reset = false;
};
// "summary: ran after 120 steps, t = 0.3 1/k: D_xy = ..., theta/pi = ..., area drift = ...;
// 610.0 s wall, 120 steps in 1.0 s of stepping (120 steps/s)" (" since the last reset" after
// one); how: "ran", "stopped on an error", ...
std::string FormatSummary(const std::string& how, const SimulationState& s, const ShownMeasures& m,
                          const std::string& time_unit, double wall_seconds,
                          const SteppingTime& stepping);

// The wall time of the loop's stepping iterations: Mark(now) at the top of each iteration adds
// the time since the previous mark if that iteration stepped; Restart at the start and a reset.
class SteppingClock {
 public:
  void Restart(double now) {
    seconds_ = 0.0;
    last_ = now;
    stepping_ = false;
  }
  void Mark(double now) {
    if (stepping_) seconds_ += now - last_;
    last_ = now;
    stepping_ = false;
  }
  void set_stepping(bool stepping) { stepping_ = stepping; }  // the iteration since Mark
  double seconds() const { return seconds_; }

 private:
  double seconds_ = 0.0, last_ = 0.0;
  bool stepping_ = false;
};

// What the node accepts for the live values (Simulation::SetCaE / SetCa): the ranges
// dynamic_reconfigure shows (rqt_reconfigure's sliders). Ca_E: [0, electric.max_Ca_E], [0, 0]
// without a field; Ca: (0, min(max_Ca, the wall Mach limit)] (min is 0, itself refused), the
// scene's Ca as both ends without shear.
struct LiveValueRanges {
  double ca_e_min = 0.0, ca_e_max = 0.0, ca_min = 0.0, ca_max = 0.0;
};
LiveValueRanges AcceptedLiveValues(const Simulation& sim);
// The memory and time estimate of a scene too large to watch live; empty when it is not.
std::string LargeRunWarning(const Scene& scene, const LatticeUnits& units);

class RunController {
 public:
  // kFinished: reached ~steps or ~until_steady; kStopped: ended from outside (SIGINT, SIGTERM,
  // rosnode kill).
  enum class RunState { kRunning, kPaused, kFailed, kFinished, kStopped };

  // Advertises the services and the dynamic_reconfigure server (its defaults: the scene's Ca_E
  // and Ca). recorder may be null; it and the others must outlive this.
  RunController(ros::NodeHandle& pnh, const NodeParameters& params, Simulation& sim,
                NodePublishers& publishers, BagRecorder* recorder);

  // Steps until ~steps (or ~until_steady) is reached, an end is requested (SIGINT, SIGTERM,
  // rosnode kill: shutdown_request.h) or ROS shuts down; a simulation error stops
  // the stepping, and with ~exit_on_error ends the loop at once. Prints the summary, publishes
  // the final diagnostics and field, closes the bag. Returns the exit status: 1 when the
  // simulation stopped on an error or the recording failed, else 0. A node that published
  // /clock deletes /use_sim_time at the end (a kept roscore kept simulation time).
  int Run();

  RunState run_state() const { return run_state_; }

 private:
  void OnReconfigure(ehd_capsule::SimulationConfig& config, uint32_t level);
  bool OnPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool OnResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool OnReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool OnAdvance(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool OnAdvanceBy(ehd_capsule::Advance::Request& req, ehd_capsule::Advance::Response& res);
  bool StartAdvance(long steps, std::string& message);
  void ApplyPendingRequests();
  void ResetRun();
  void PublishStartState();  // step 0: at the start and after a reset
  void RestoreWallTime();    // at the end: /use_sim_time deleted when this node was the clock
  void StepOnce();
  void Fail(const std::string& reason);
  void OnRecordError(const std::string& reason);
  void PrintProgress(bool force);
  void ReportRecordingRate();  // once per bag, from its first second (BagRecorder::SampleRate)
  void PublishDiagnostics(bool force);
  RunStatus Status() const;

  const NodeParameters& params_;
  Simulation& sim_;
  NodePublishers& pub_;
  BagRecorder* recorder_;

  RunState run_state_ = RunState::kRunning;
  std::string failure_;
  std::string end_reason_;  // why it finished or stopped ("reached 60 steps", "SIGTERM")
  int publish_every_ = 1;   // ~publish_every, live via dynamic_reconfigure
  std::unique_ptr<SteadyStateMonitor> steady_monitor_;

  // Requests recorded by callbacks, applied by the loop.
  long advance_remaining_ = 0;
  int advance_steps_ = 1;
  ehd_capsule::SimulationConfig config_;
  bool config_dirty_ = false;     // config_ must be pushed back to dynamic_reconfigure
  bool diagnostics_due_ = false;  // a refusal (or its end) to publish now
  std::string last_refusal_;      // RunStatus::refused

  ros::ServiceServer pause_srv_, resume_srv_, reset_srv_, advance_srv_, advance_by_srv_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ehd_capsule::SimulationConfig>> reconfigure_;

  ros::WallTime last_progress_, run_start_;
  SteppingClock stepping_clock_;  // since the start or the last reset
  long steps_since_reset_ = 0;
  bool after_reset_ = false;
  long last_progress_step_ = 0;
};

}  // namespace ehd::ros_node
