#include "ehd_capsule/ros/run_controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ehd_capsule/ros/shutdown_request.h"

namespace ehd::ros_node {

std::string FormatProgressLine(const SimulationState& s, const ShownMeasures& m,
                               const std::string& time_unit, double steps_per_second) {
  char head[96], tail[48];
  std::snprintf(head, sizeof head, "step %ld  t = %.4g %s  ", s.step, s.time, time_unit.c_str());
  std::snprintf(tail, sizeof tail, "  %.0f steps/s", steps_per_second);
  return head + FormatMeasures(s, m, "  ") + tail;
}

std::string FormatSummary(const std::string& how, const SimulationState& s, const ShownMeasures& m,
                          const std::string& time_unit, double wall_seconds,
                          const SteppingTime& stepping) {
  char head[160], tail[160];
  std::snprintf(head, sizeof head, "summary: %s after %ld steps, t = %.4g %s: ", how.c_str(),
                s.step, s.time, time_unit.c_str());
  // The rate of the steps since the last reset over the time spent stepping them: wall time
  // since the start, and paused time, used to be counted too ("610.0 s wall (14 steps/s)").
  std::snprintf(tail, sizeof tail,
                "; %.1f s wall, %ld steps in %.1f s of stepping%s (%.0f steps/s)", wall_seconds,
                stepping.steps, stepping.seconds,
                stepping.after_reset ? " since the last reset" : "",
                stepping.seconds > 0 ? stepping.steps / stepping.seconds : 0.0);
  return head + FormatMeasures(s, m, ", ") + tail;
}

LiveValueRanges AcceptedLiveValues(const Simulation& sim) {
  const Scene& scene = sim.scene();
  const LatticeUnits& u = sim.units();
  LiveValueRanges r;
  r.ca_e_max = sim.has_electric_field() ? scene.electric.max_ca_e : 0.0;
  if (scene.has_shear()) {
    // Simulation::SetCa's limits: max_Ca and the wall Mach number k L / c_s <= max_mach, with
    // k = Ca T / (mu a); a hair below the latter so that its end is itself accepted.
    const double mach_limit = scene.numerics.max_mach * kLatticeSoundSpeed / u.half_width *
                              u.viscosity * u.radius / u.tension * (1.0 - 1e-12);
    r.ca_max = std::min(scene.max_Ca, mach_limit);
  } else {
    r.ca_min = r.ca_max = sim.state().ca;
  }
  return r;
}

std::string LargeRunWarning(const Scene& scene, const LatticeUnits& units) {
  // Estimates from this machine kind's measured costs (docs/validation_ehd.md sec. 5,
  // docs/lbm.md): ~250 bytes of fluid state per cell (populations, moments, force, viscosity,
  // potential), and ~18 ns per cell and step for the whole coupled step on one core.
  const double cells = static_cast<double>(scene.N) * scene.N;
  const double bytes = 250.0 * cells;
  const double seconds_per_step = 18e-9 * cells;
  const double steps_per_unit = units.steps_per_time_unit;
  const double seconds_per_unit = seconds_per_step * steps_per_unit;
  if (!(bytes > 1e9 || seconds_per_unit > 600.0)) return "";
  char text[400];
  std::snprintf(text, sizeof text,
                "large run: N = %d needs about %.2g GB and %.2g s per step; one time unit (%s) is "
                "%.3g steps, about %.3g h of wall time. Lower N (set:=\"{N: ...}\") for a live "
                "view.",
                scene.N, bytes / 1e9, seconds_per_step, units.time_unit.c_str(), steps_per_unit,
                seconds_per_unit / 3600.0);
  return text;
}

RunController::RunController(ros::NodeHandle& pnh, const NodeParameters& params, Simulation& sim,
                             NodePublishers& publishers, BagRecorder* recorder)
    : params_(params),
      sim_(sim),
      pub_(publishers),
      recorder_(recorder),
      publish_every_(params.publish_every),
      advance_steps_(params.advance_steps) {
  if (params.until_steady > 0.0) {
    steady_monitor_ = std::make_unique<SteadyStateMonitor>(params.until_steady);
  }
  if (recorder_) {
    recorder_->set_on_error([this](const std::string& reason) { OnRecordError(reason); });
  }
  pause_srv_ = pnh.advertiseService("pause", &RunController::OnPause, this);
  resume_srv_ = pnh.advertiseService("resume", &RunController::OnResume, this);
  reset_srv_ = pnh.advertiseService("reset", &RunController::OnReset, this);
  advance_srv_ = pnh.advertiseService("advance", &RunController::OnAdvance, this);
  advance_by_srv_ = pnh.advertiseService("advance_by", &RunController::OnAdvanceBy, this);

  // The dynamic_reconfigure values and defaults are the scene's, not the .cfg's, and so are the
  // ranges shown (rqt_reconfigure's sliders). The .cfg's own ranges stay wide: the server clamps
  // a request to them before the node sees it, and a value outside the scene's range must be
  // refused with what was asked for, not applied as the range's end.
  config_.Ca_E = sim_.state().ca_e;
  config_.Ca = sim_.state().ca;
  config_.publish_every = publish_every_;
  config_.paused = false;
  config_.advance_steps = advance_steps_;
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<ehd_capsule::SimulationConfig>>(
      reconfigure_mutex_, pnh);
  ehd_capsule::SimulationConfig min, max, dflt;
  reconfigure_->getConfigMin(min);
  reconfigure_->getConfigMax(max);
  const LiveValueRanges ranges = AcceptedLiveValues(sim_);
  min.Ca_E = ranges.ca_e_min;
  max.Ca_E = ranges.ca_e_max;
  min.Ca = ranges.ca_min;
  max.Ca = ranges.ca_max;
  dflt = config_;
  reconfigure_->setConfigMin(min);
  reconfigure_->setConfigMax(max);
  reconfigure_->setConfigDefault(dflt);
  reconfigure_->updateConfig(config_);
  reconfigure_->setCallback(
      [this](ehd_capsule::SimulationConfig& c, uint32_t level) { OnReconfigure(c, level); });
}

void RunController::OnReconfigure(ehd_capsule::SimulationConfig& config, uint32_t /*level*/) {
  // Ca_E and Ca go to the simulation's queue (applied at the next step, or refused now). The
  // configuration handed back (the service's response, parameter_updates, the parameter
  // server) is what the node runs with: a refused value is replaced by the kept one, so
  // update_configuration and `dynparam get` show it, and /diagnostics says why.
  const long next_step = sim_.state().step + 1;
  std::string refused;
  bool accepted = false;
  const auto apply = [&](const char* name, double wanted, double& kept,
                         void (Simulation::*set)(double)) {
    if (wanted == kept) return;
    try {
      (sim_.*set)(wanted);
      kept = wanted;
      accepted = true;
      ROS_INFO("ehd_capsule: %s = %g from step %ld", name, wanted, next_step);
    } catch (const std::exception& e) {
      char text[512];
      std::snprintf(text, sizeof text, "refused %s = %g: %s (%s stays %g)", name, wanted, e.what(),
                    name, kept);
      ROS_ERROR("ehd_capsule: %s", text);
      refused += (refused.empty() ? "" : "; ") + std::string(text);
    }
  };
  apply("Ca_E", config.Ca_E, config_.Ca_E, &Simulation::SetCaE);
  apply("Ca", config.Ca, config_.Ca, &Simulation::SetCa);
  if (!refused.empty()) {
    last_refusal_ = refused;
    diagnostics_due_ = true;
  } else if (accepted && !last_refusal_.empty()) {
    last_refusal_.clear();
    diagnostics_due_ = true;
  }
  if (config.publish_every != config_.publish_every) {
    publish_every_ = config.publish_every;
    ROS_INFO("ehd_capsule: publish_every = %d from step %ld", publish_every_, sim_.state().step);
  }
  if (config.paused != config_.paused && run_state_ != RunState::kFailed &&
      run_state_ != RunState::kFinished) {
    run_state_ = config.paused ? RunState::kPaused : RunState::kRunning;
    ROS_INFO("ehd_capsule: %s at step %ld", config.paused ? "paused" : "resumed",
             sim_.state().step);
  }
  advance_steps_ = config.advance_steps;
  const double ca_e = config_.Ca_E, ca = config_.Ca;
  config_ = config;
  config_.Ca_E = ca_e;
  config_.Ca = ca;
  config_.publish_every = publish_every_;
  config_.paused = run_state_ == RunState::kPaused;  // not after a failure or the end
  config = config_;
}

bool RunController::OnPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  if (run_state_ == RunState::kFailed || run_state_ == RunState::kFinished) {
    res.success = false;
    res.message = "simulation is not running: " + (failure_.empty() ? "finished" : failure_);
    return true;
  }
  run_state_ = RunState::kPaused;
  config_.paused = true;
  config_dirty_ = true;
  res.success = true;
  res.message = "paused at step " + std::to_string(sim_.state().step);
  ROS_INFO("ehd_capsule: %s", res.message.c_str());
  return true;
}

bool RunController::OnResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  if (run_state_ != RunState::kPaused) {
    res.success = false;
    res.message =
        run_state_ == RunState::kRunning ? "already running" : "cannot resume: " + failure_;
    return true;
  }
  run_state_ = RunState::kRunning;
  config_.paused = false;
  config_dirty_ = true;
  res.success = true;
  res.message = "resumed at step " + std::to_string(sim_.state().step);
  ROS_INFO("ehd_capsule: %s", res.message.c_str());
  return true;
}

bool RunController::OnReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  // Applied here, between two steps (callbacks run on the loop's thread), so that the answer
  // says whether it was done. While recording, the new timeline's bag is opened first: if it
  // cannot be, the reset is refused and the recording goes on where it was (it used to go on
  // unrecorded, with only a log line).
  if (recorder_) {
    const std::string next = recorder_->NextPath();
    try {
      recorder_->OpenNext();
    } catch (const std::exception& e) {
      res.success = false;
      res.message = "reset refused: cannot record the new timeline in " + next + ": " + e.what();
      res.message += recorder_->is_open() ? "; still recording to " + recorder_->active_path()
                                          : "; not recording (" + recorder_->failure() + ")";
      ROS_ERROR("ehd_capsule: %s", res.message.c_str());
      return true;
    }
  }
  ResetRun();
  res.success = true;
  res.message = "reset to the initial state of scene '" + params_.scene + "'";
  if (recorder_) res.message += "; recording to " + recorder_->path();
  return true;
}

bool RunController::StartAdvance(long steps, std::string& message) {
  if (run_state_ != RunState::kPaused) {
    message = "advance works while paused (call ~pause first)";
    return false;
  }
  advance_remaining_ += steps;
  message = "advancing " + std::to_string(steps) + " steps from step " +
            std::to_string(sim_.state().step);
  return true;
}

bool RunController::OnAdvance(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  res.success = StartAdvance(advance_steps_, res.message);
  return true;
}

bool RunController::OnAdvanceBy(ehd_capsule::Advance::Request& req,
                                ehd_capsule::Advance::Response& res) {
  if (req.steps < 1) {
    res.success = false;
    res.message = "steps must be >= 1 (got " + std::to_string(req.steps) + ")";
    return true;
  }
  res.success = StartAdvance(req.steps, res.message);
  return true;
}

void RunController::ResetRun() {
  sim_.Reset();
  advance_remaining_ = 0;
  pub_.RestartMarkers();
  if (run_state_ == RunState::kFailed || run_state_ == RunState::kFinished) {
    run_state_ = config_.paused ? RunState::kPaused : RunState::kRunning;
    failure_.clear();
  }
  config_.Ca_E = sim_.state().ca_e;
  config_.Ca = sim_.state().ca;
  config_dirty_ = true;
  last_refusal_.clear();
  steps_since_reset_ = 0;
  after_reset_ = true;
  stepping_clock_.Restart(ros::WallTime::now().toSec());
  ROS_INFO("ehd_capsule: reset to the initial state of scene '%s'", params_.scene.c_str());
  // A new timeline starts at t = 0 in a new bag (OnReset opened it: <stem>.<n>.bag), so no bag
  // holds two timelines; it starts as the first one does.
  if (recorder_ && recorder_->is_open()) pub_.RecordBagHeader();
  pub_.PublishSurfaceMesh();
  PublishStartState();
}

void RunController::PublishStartState() {
  // The bag's first diagnostic (a bag whose recording fails in its first second used to hold
  // none), then the state the timeline starts from, step 0, like every published step: a
  // replay or a plot starts at t = 0. These and the bag's header are in chunks of their own,
  // so `rosbag reindex` recovers them from a bag whose writing failed.
  PublishDiagnostics(true);
  pub_.PublishState();
  if (recorder_) {
    ReportRecordingRate();
    recorder_->StartWritten();
  }
}

void RunController::ApplyPendingRequests() {
  if (diagnostics_due_) {
    diagnostics_due_ = false;
    PublishDiagnostics(true);
  }
  if (config_dirty_) {
    config_dirty_ = false;
    config_.publish_every = publish_every_;
    reconfigure_->updateConfig(config_);
  }
}

RunStatus RunController::Status() const {
  RunStatus status;
  status.refused = last_refusal_;
  switch (run_state_) {
    case RunState::kRunning:
      status.message = "running";
      break;
    case RunState::kPaused:
      status.message = "paused";
      break;
    case RunState::kFinished:
      status.message = end_reason_.empty() ? "finished" : "finished: " + end_reason_;
      break;
    case RunState::kStopped:
      status.message = "stopped: " + end_reason_;
      break;
    case RunState::kFailed:
      status.error = true;
      status.message = failure_;
      break;
  }
  return status;
}

void RunController::PublishDiagnostics(bool force) { pub_.PublishDiagnostics(force, Status()); }

void RunController::Fail(const std::string& reason) {
  run_state_ = RunState::kFailed;
  failure_ = reason;
  ROS_ERROR("ehd_capsule: simulation stopped at step %ld: %s", sim_.state().step, reason.c_str());
  if (params_.exit_on_error) {
    ROS_ERROR("ehd_capsule: exiting with status 1 (~exit_on_error)");
  } else {
    ROS_ERROR("ehd_capsule: the node stays up for inspection; call ~reset to start over");
  }
  PublishDiagnostics(true);
  pub_.PublishField(true);  // the layer of the state the run stopped at
  if (recorder_) recorder_->Close();
}

void RunController::OnRecordError(const std::string& reason) {
  ROS_ERROR("ehd_capsule: %s; recording stopped at step %ld", reason.c_str(), sim_.state().step);
  if (params_.record_error_action() == RecordErrorAction::kStop) {
    Fail(reason);
  } else if (run_state_ == RunState::kRunning) {
    run_state_ = RunState::kPaused;
    config_.paused = true;
    config_dirty_ = true;
    ROS_ERROR(
        "ehd_capsule: simulation paused (~on_record_error: pause); ~resume continues "
        "without recording");
  }
  PublishDiagnostics(true);
}

void RunController::StepOnce() {
  try {
    sim_.Step();
  } catch (const std::exception& e) {
    Fail(e.what());
    return;
  }
  pub_.CountStep();
  ++steps_since_reset_;
  const SimulationState& s = sim_.state();
  if (s.step % publish_every_ == 0) {
    pub_.PublishState();
    if (recorder_) ReportRecordingRate();
  }
  if (params_.steps > 0 && s.step >= params_.steps) {
    run_state_ = RunState::kFinished;
    end_reason_ = "reached " + std::to_string(s.step) + " steps";
    ROS_INFO("ehd_capsule: reached %ld steps (t = %g); stopping", s.step, s.time);
  }
  if (steady_monitor_ && steady_monitor_->Update(s.time, s.dxy, s.inclination)) {
    run_state_ = RunState::kFinished;
    char reason[96];
    std::snprintf(reason, sizeof reason, "steady to %g at t = %g", params_.until_steady, s.time);
    end_reason_ = reason;
    ROS_INFO("ehd_capsule: steady to %g at t = %g (D_xy = %.5f, theta/pi = %.4f); stopping",
             params_.until_steady, s.time, s.dxy, s.inclination / M_PI);
  }
}

void RunController::ReportRecordingRate() {
  long states_left = -1;  // a live run or ~until_steady: the end is not known
  if (params_.steps > 0) {
    states_left = std::max(0L, (params_.steps - sim_.state().step) / publish_every_);
  }
  // From the first state's size at once: a disk that fills within the first second (before a
  // rate is measured) used to fill without a warning.
  if (const std::optional<RecordingRate> first = recorder_->FirstState()) {
    const std::string warning = FirstStateWarning(*first, states_left);
    if (!warning.empty()) ROS_WARN("ehd_capsule: %s", warning.c_str());
  }
  const std::optional<RecordingRate> rate = recorder_->SampleRate(ros::WallTime::now().toSec());
  if (!rate) return;
  const RecordingReport report = DescribeRecordingRate(*rate, states_left);
  ROS_INFO("ehd_capsule: %s", report.info.c_str());
  if (!report.warning.empty()) ROS_WARN("ehd_capsule: %s", report.warning.c_str());
}

void RunController::PrintProgress(bool force) {
  if (params_.progress_period <= 0.0 && !force) return;
  const ros::WallTime now = ros::WallTime::now();
  if (!force && (now - last_progress_).toSec() < params_.progress_period) return;
  const SimulationState& s = sim_.state();
  const double wall = (now - last_progress_).toSec();
  const double rate = wall > 0.0 ? (s.step - last_progress_step_) / wall : 0.0;
  ROS_INFO("ehd_capsule: %s",
           FormatProgressLine(s, MeasuresOf(sim_.scene()), sim_.units().time_unit, rate).c_str());
  last_progress_ = now;
  last_progress_step_ = s.step;
}

void RunController::RestoreWallTime() {
  // The launch files set /use_sim_time for this node's clock; on a kept roscore it stayed true
  // after the run, so a later plain `rostopic echo` waited for a /clock nobody publishes and
  // `rostopic hz` gave rates in simulation time. The clock's owner takes it back (a fresh
  // master has none).
  if (!params_.use_sim_time || !params_.publish_clock) return;
  if (ros::param::del("/use_sim_time")) {
    ROS_INFO("ehd_capsule: /use_sim_time deleted (this node's /clock has stopped)");
  }
}

int RunController::Run() {
  pub_.StartClocks();
  last_progress_ = run_start_ = ros::WallTime::now();
  stepping_clock_.Restart(run_start_.toSec());
  ros::WallTime next_step_time = ros::WallTime::now();
  HandleShutdownInTheLoop();  // SIGINT, SIGTERM, rosnode kill: end below, between two steps
  PublishStartState();
  while (ros::ok() && !ShutdownRequested()) {
    stepping_clock_.Mark(ros::WallTime::now().toSec());
    ros::spinOnce();
    ApplyPendingRequests();
    PublishDiagnostics(false);
    if (run_state_ == RunState::kRunning) PrintProgress(false);
    pub_.PublishThrottled();
    pub_.PublishField(false);
    if (run_state_ == RunState::kFinished) break;
    if (run_state_ == RunState::kFailed && params_.exit_on_error) break;
    const bool may_step = run_state_ == RunState::kRunning ||
                          (run_state_ == RunState::kPaused && advance_remaining_ > 0);
    if (!may_step) {
      ros::WallDuration(0.01).sleep();
      continue;
    }
    stepping_clock_.set_stepping(true);
    if (params_.max_step_rate > 0.0) {
      const ros::WallTime now = ros::WallTime::now();
      if (now < next_step_time) (next_step_time - now).sleep();
      next_step_time =
          std::max(now, next_step_time) + ros::WallDuration(1.0 / params_.max_step_rate);
    }
    StepOnce();
    if (run_state_ == RunState::kPaused && advance_remaining_ > 0) {
      if (--advance_remaining_ == 0) {
        ROS_INFO("ehd_capsule: advanced to step %ld (paused)", sim_.state().step);
      }
    }
  }
  std::string how = "ran";
  if (run_state_ == RunState::kFailed) {
    how = "stopped on an error";
  } else if (run_state_ != RunState::kFinished) {
    // Ended from outside: the final diagnostic says so (in the bag too).
    run_state_ = RunState::kStopped;
    end_reason_ = ShutdownRequested() ? ShutdownReason() : "ROS shut down";
    how = "stopped (" + end_reason_ + ")";
    ROS_INFO("ehd_capsule: %s at step %ld; stopping", end_reason_.c_str(), sim_.state().step);
  }
  PublishDiagnostics(true);
  const ros::WallTime end = ros::WallTime::now();
  stepping_clock_.Mark(end.toSec());
  const SteppingTime stepping{steps_since_reset_, stepping_clock_.seconds(), after_reset_};
  ROS_INFO("ehd_capsule: %s",
           FormatSummary(how, sim_.state(), MeasuresOf(sim_.scene()), sim_.units().time_unit,
                         (end - run_start_).toSec(), stepping)
               .c_str());
  if (!pub_.field_is_current()) pub_.PublishField(true);  // the final state's layer
  if (recorder_) recorder_->Close();
  RestoreWallTime();
  // Exit status: 1 if the simulation stopped on an error (even when the node was shut down
  // afterwards) or the recording failed, 0 otherwise; main() returns 1 for an invalid scene or
  // parameter.
  const bool record_failed = recorder_ && !recorder_->failure().empty();
  return run_state_ == RunState::kFailed || record_failed ? 1 : 0;
}

}  // namespace ehd::ros_node
