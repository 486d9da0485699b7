#include "ehd_capsule/ros/capsule_node.h"

#include <geometry_msgs/PolygonStamped.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <boost/make_shared.hpp>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>

#include "ehd_capsule/ros/state_messages.h"

namespace ehd::ros_node {

CapsuleNode::CapsuleNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), pnh_(private_nh) {
  ReadParameters();
  BuildSimulation();
  field_layer_ = ParseFieldLayer(field_layer_name_, *sim_);
  if (field_stride_ == 0) field_stride_ = std::max(1, sim_->scene().N / 64);
  if (markers_every_ == 0) markers_every_ = sim_->dimension() == 3 ? 10 : 1;

  state_pub_ = pnh_.advertise<ehd_capsule::CapsuleState>("state", 1000);
  throttled_pub_ = pnh_.advertise<ehd_capsule::CapsuleState>("state_throttled", 10);
  field_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("field", 2);
  tf_static_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf_static", 1, /*latch=*/true);
  PublishStaticTransform();
  shape_pub_ = pnh_.advertise<geometry_msgs::PolygonStamped>("shape", 10);
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 10);
  scene_pub_ = pnh_.advertise<std_msgs::String>("scene", 1, /*latch=*/true);
  diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  if (sim_->dimension() == 3) {
    surface_mesh_pub_ = pnh_.advertise<ehd_capsule::SurfaceMesh>("surface_mesh", 1, /*latch=*/true);
    surface_state_pub_ = pnh_.advertise<ehd_capsule::SurfaceState>("surface_state", 1000);
  }
  if (use_sim_time_ && publish_clock_) {
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 100);
  }

  pause_srv_ = pnh_.advertiseService("pause", &CapsuleNode::OnPause, this);
  resume_srv_ = pnh_.advertiseService("resume", &CapsuleNode::OnResume, this);
  reset_srv_ = pnh_.advertiseService("reset", &CapsuleNode::OnReset, this);
  advance_srv_ = pnh_.advertiseService("advance", &CapsuleNode::OnAdvance, this);
  advance_by_srv_ = pnh_.advertiseService("advance_by", &CapsuleNode::OnAdvanceBy, this);

  // The dynamic_reconfigure defaults are the scene's values, not the .cfg's.
  config_.Ca_E = sim_->state().ca_e;
  config_.Ca = sim_->state().ca;
  config_.publish_every = publish_every_;
  config_.paused = false;
  config_.advance_steps = advance_steps_;
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<ehd_capsule::SimulationConfig>>(
      reconfigure_mutex_, pnh_);
  reconfigure_->updateConfig(config_);
  reconfigure_->setCallback(
      [this](ehd_capsule::SimulationConfig& c, uint32_t level) { OnReconfigure(c, level); });

  std_msgs::String scene_msg;
  scene_msg.data = scene_.yaml_text;
  scene_pub_.publish(scene_msg);
  OpenBag();
  Record("scene", scene_msg, StampNow());
  PublishSurfaceMesh();

  ROS_INFO_STREAM("ehd_capsule: scene '" << scene_name_ << "'\n"
                                         << DescribeUnits(scene_, sim_->units())
                                         << sim_->Pipeline());
  WarnIfLarge();
  if (max_steps_ > 0) {
    ROS_INFO("ehd_capsule: will stop after %ld steps (t = %g %s)", max_steps_,
             max_steps_ * sim_->units().dt, sim_->units().time_unit.c_str());
  }
}

void CapsuleNode::WarnIfLarge() const {
  // Estimates from this machine kind's measured costs (docs/validation_ehd.md sec. 5,
  // docs/lbm.md): ~250 bytes of fluid state per cell (populations, moments, force, viscosity,
  // potential), and ~18 ns per cell and step for the whole coupled step on one core.
  const double cells = static_cast<double>(scene_.N) * scene_.N;
  const double bytes = 250.0 * cells;
  const double seconds_per_step = 18e-9 * cells;
  const double steps_per_unit = sim_->units().steps_per_time_unit;
  const double seconds_per_unit = seconds_per_step * steps_per_unit;
  if (bytes > 1e9 || seconds_per_unit > 600.0) {
    ROS_WARN(
        "ehd_capsule: large run: N = %d needs about %.2g GB and %.2g s per step; one time unit "
        "(%s) is %.3g steps, about %.3g h of wall time. Lower N (set:=\"{N: ...}\") for a live "
        "view.",
        scene_.N, bytes / 1e9, seconds_per_step, sim_->units().time_unit.c_str(), steps_per_unit,
        seconds_per_unit / 3600.0);
  }
}

CapsuleNode::~CapsuleNode() { CloseBag(); }

void CapsuleNode::ReadParameters() {
  pnh_.param<std::string>("scene", scene_name_, "shear_field");
  int steps = 0;
  pnh_.param("steps", steps, 0);
  if (steps < 0)
    throw std::invalid_argument("~steps must be >= 0 (got " + std::to_string(steps) + ")");
  max_steps_ = steps;
  pnh_.param("publish_every", publish_every_, 1);
  if (publish_every_ < 1) {
    throw std::invalid_argument("~publish_every must be >= 1 (got " +
                                std::to_string(publish_every_) + ")");
  }
  pnh_.param("markers_every", markers_every_, 0);
  if (markers_every_ < 0) {
    throw std::invalid_argument(
        "~markers_every must be >= 1, or 0 for the default (1 in 2D, 10 "
        "in 3D); got " +
        std::to_string(markers_every_));
  }
  pnh_.param<std::string>("frame_id", frame_id_, "ehd");
  pnh_.param("force_arrow_scale", force_arrow_scale_, 1.0);
  pnh_.param("velocity_arrows", velocity_arrows_, false);
  pnh_.param("velocity_stride", velocity_stride_, 8);
  if (velocity_stride_ < 1) throw std::invalid_argument("~velocity_stride must be >= 1");
  std::string surface_colour;
  pnh_.param<std::string>("surface_colour", surface_colour, "traction");
  surface_colour_ = ParseSurfaceColour(surface_colour);
  pnh_.param<std::string>("world_frame", world_frame_, "world");
  if (world_frame_.empty() || world_frame_ == frame_id_) {
    throw std::invalid_argument("~world_frame ('" + world_frame_ +
                                "') must be a frame name other than ~frame_id");
  }
  pnh_.param<std::string>("field_layer", field_layer_name_, "speed");
  pnh_.param("field_stride", field_stride_, 0);
  if (field_stride_ < 0) throw std::invalid_argument("~field_stride must be >= 0 (0: automatic)");
  pnh_.param("field_rate", field_rate_, 2.0);
  pnh_.param("field_interval", field_interval_, 0.1);
  if (!(field_interval_ > 0.0)) {
    throw std::invalid_argument("~field_interval must be > 0 (units of simulation time)");
  }
  if (!(field_rate_ > 0.0))
    throw std::invalid_argument("~field_rate must be > 0 (Hz of wall time)");
  pnh_.param("max_step_rate", max_step_rate_, 0.0);
  pnh_.param("record", record_, false);
  pnh_.param<std::string>("bag", bag_path_, "ehd_capsule.bag");
  base_bag_path_ = bag_path_;
  pnh_.param("overwrite", overwrite_, false);
  std::string on_record_error;
  pnh_.param<std::string>("on_record_error", on_record_error, "pause");
  if (on_record_error != "pause" && on_record_error != "stop") {
    throw std::invalid_argument("~on_record_error must be pause or stop (got '" + on_record_error +
                                "')");
  }
  stop_on_record_error_ = on_record_error == "stop";
  // A batch run (~steps > 0) ends on a simulation error with exit status 1; a live run (steps 0)
  // stays up for inspection (~reset starts over) unless ~exit_on_error is true.
  pnh_.param("exit_on_error", exit_on_error_, max_steps_ > 0);
  pnh_.param("advance_steps", advance_steps_, 1);
  pnh_.param("progress_period", progress_period_, 5.0);
  // ~until_steady TOL > 0: stop (like reaching ~steps) once D_xy and theta are steady to TOL
  // over a unit of time (relative, as `ehd_sim run --until-steady`).
  pnh_.param("until_steady", until_steady_, 0.0);
  if (until_steady_ < 0.0) throw std::invalid_argument("~until_steady must be >= 0");
  if (until_steady_ > 0.0) steady_monitor_ = std::make_unique<SteadyStateMonitor>(until_steady_);
  // With /use_sim_time, this node publishes /clock unless told not to: with several simulation
  // nodes, exactly one should own the clock (two clocks jump back and forth).
  pnh_.param("publish_clock", publish_clock_, true);
  // ~state_throttled: the latest state at most this often in wall time (plots, UIs: ~state runs
  // at thousands of messages per second of sim time, which rqt_plot and rospy cannot follow).
  pnh_.param("throttled_rate", throttled_rate_, 20.0);
  if (!(throttled_rate_ > 0.0)) {
    throw std::invalid_argument("~throttled_rate must be > 0 (Hz of wall time)");
  }
  nh_.param("/use_sim_time", use_sim_time_, false);

  // Scene overrides: ~set is a dictionary of scene keys, e.g. {Ca: 0.1, N: 64}; a nested
  // dictionary names a section's keys, {geometry: {half_width: 3}} = geometry.half_width=3.
  overrides_.clear();
  XmlRpc::XmlRpcValue set;
  if (pnh_.getParam("set", set)) {
    if (set.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      throw std::invalid_argument("~set must be a dictionary of scene keys, e.g. {Ca: 0.1}");
    }
    std::function<void(const std::string&, XmlRpc::XmlRpcValue&)> add_overrides =
        [&](const std::string& prefix, XmlRpc::XmlRpcValue& dict) {
          for (auto it = dict.begin(); it != dict.end(); ++it) {
            const std::string key = prefix.empty() ? it->first : prefix + "." + it->first;
            std::ostringstream value;
            XmlRpc::XmlRpcValue& v = it->second;
            switch (v.getType()) {
              case XmlRpc::XmlRpcValue::TypeDouble: {
                char text[32];  // shortest text that reads back as the same double
                const auto end = std::to_chars(text, text + sizeof text, static_cast<double>(v));
                value << std::string(text, end.ptr);
                break;
              }
              case XmlRpc::XmlRpcValue::TypeInt:
                value << static_cast<int>(v);
                break;
              case XmlRpc::XmlRpcValue::TypeBoolean:
                value << (static_cast<bool>(v) ? "true" : "false");
                break;
              case XmlRpc::XmlRpcValue::TypeString:
                value << static_cast<std::string>(v);
                break;
              case XmlRpc::XmlRpcValue::TypeStruct:
                add_overrides(key, v);
                continue;
              default:
                throw std::invalid_argument("~set/" + key +
                                            ": only numbers, booleans, strings and dictionaries");
            }
            overrides_.push_back(key + "=" + value.str());
          }
        };
    add_overrides("", set);
  }
  // ~start_Ca_E / ~start_Ca (the launch files' Ca_E and Ca arguments; < 0 or unset: the scene's
  // value) override the scene like ~set. Not ~Ca_E / ~Ca: those are dynamic_reconfigure's own
  // and stay on a running master from one launch to the next.
  for (const char* key : {"Ca_E", "Ca"}) {
    double v = -1.0;
    pnh_.param(std::string("start_") + key, v, -1.0);
    if (v >= 0.0) {
      std::ostringstream value;
      value << v;
      overrides_.push_back(std::string(key) + "=" + value.str());
    }
  }
  // Write the effective settings back so `rosparam get` shows what runs (turtlesim does too).
  pnh_.setParam("scene", scene_name_);
  pnh_.setParam("publish_every", publish_every_);
  pnh_.setParam("frame_id", frame_id_);
}

void CapsuleNode::BuildSimulation() {
  scene_ = LoadScene(scene_name_, overrides_);
  sim_ = std::make_unique<Simulation>(scene_);
}

void CapsuleNode::OpenBag() {
  if (!record_) return;
  // An existing bag is not overwritten unless ~overwrite is true (a new run used to replace the
  // previous one silently).
  if (!overwrite_ && (std::ifstream(bag_path_).good() || std::ifstream(ActiveBagPath()).good())) {
    throw std::invalid_argument("~bag " + bag_path_ +
                                " exists: choose another path or set ~overwrite true "
                                "(launch argument overwrite:=true)");
  }
  // Written as <bag>.active and renamed to <bag> when closed, as `rosbag record` does: a bag
  // left by a killed process (kill -9, power loss) keeps the .active name and is repaired with
  // `rosbag reindex`.
  bag_.open(ActiveBagPath(), rosbag::bagmode::Write);
  bag_open_ = true;
  ROS_INFO("ehd_capsule: recording to %s (as %s until closed)", bag_path_.c_str(),
           ActiveBagPath().c_str());
  // The frame's static transform, as a latched connection so `rosbag play` latches it again and
  // rviz has the frame on replay.
  geometry_msgs::TransformStamped t;
  t.header.frame_id = world_frame_;
  t.child_frame_id = frame_id_;
  t.transform.rotation.w = 1.0;
  tf2_msgs::TFMessage message;
  message.transforms.push_back(t);
  auto header = boost::make_shared<ros::M_string>();
  (*header)["callerid"] = ros::this_node::getName();
  (*header)["latching"] = "1";
  (*header)["topic"] = "/tf_static";
  (*header)["md5sum"] = ros::message_traits::MD5Sum<tf2_msgs::TFMessage>::value();
  (*header)["type"] = ros::message_traits::DataType<tf2_msgs::TFMessage>::value();
  (*header)["message_definition"] = ros::message_traits::Definition<tf2_msgs::TFMessage>::value();
  bag_.write("/tf_static", StampNow().isZero() ? ros::Time(1e-9) : StampNow(), message, header);
}

std::string CapsuleNode::ActiveBagPath() const { return bag_path_ + ".active"; }

void CapsuleNode::CloseBag() {
  if (!bag_open_) return;
  bag_.close();
  bag_open_ = false;
  if (std::rename(ActiveBagPath().c_str(), bag_path_.c_str()) != 0) {
    ROS_ERROR("ehd_capsule: bag closed, but renaming %s to %s failed: %s", ActiveBagPath().c_str(),
              bag_path_.c_str(), std::strerror(errno));
    return;
  }
  ROS_INFO("ehd_capsule: bag %s closed with %ld states", bag_path_.c_str(), published_states_);
}

template <typename M>
void CapsuleNode::Record(const std::string& topic, const M& msg, const ros::Time& stamp) {
  if (!bag_open_) return;
  // Topics are recorded under the node's resolved names so a replay republishes them there.
  const std::string name = topic.front() == '/' ? topic : pnh_.resolveName(topic);
  try {
    bag_.write(name, stamp.isZero() ? ros::Time(1e-9) : stamp, msg);
  } catch (const std::exception& e) {
    // Disk full, file size limit, I/O error: stop recording (close what can be closed), say
    // why in an ERROR diagnostic, pause or stop the simulation (~on_record_error), and exit
    // non-zero at the end.
    record_failure_ = std::string("writing the bag ") + ActiveBagPath() + " failed: " + e.what();
    ROS_ERROR("ehd_capsule: %s; recording stopped at step %ld", record_failure_.c_str(),
              sim_->state().step);
    bag_open_ = false;
    try {
      bag_.close();
    } catch (const std::exception& close_error) {
      ROS_ERROR("ehd_capsule: closing the bag failed too: %s", close_error.what());
    }
    if (stop_on_record_error_) {
      Fail(record_failure_);
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
}

ros::Time CapsuleNode::StampNow() const {
  if (use_sim_time_) return ros::Time(std::max(sim_->state().time, 0.0));
  return ros::Time::now();
}

void CapsuleNode::OnReconfigure(ehd_capsule::SimulationConfig& config, uint32_t /*level*/) {
  // Record only; the loop applies before the next step.
  if (config.Ca_E != config_.Ca_E) pending_ca_e_ = config.Ca_E;
  if (config.Ca != config_.Ca) pending_ca_ = config.Ca;
  if (config.publish_every != config_.publish_every) {
    publish_every_ = config.publish_every;
    ROS_INFO("ehd_capsule: publish_every = %d from step %ld", publish_every_, sim_->state().step);
  }
  if (config.paused != config_.paused && run_state_ != RunState::kFailed &&
      run_state_ != RunState::kFinished) {
    run_state_ = config.paused ? RunState::kPaused : RunState::kRunning;
    ROS_INFO("ehd_capsule: %s at step %ld", config.paused ? "paused" : "resumed",
             sim_->state().step);
  }
  advance_steps_ = config.advance_steps;
  // Ca_E and Ca stay at their applied values until the loop accepts them.
  const double ca_e = config_.Ca_E, ca = config_.Ca;
  config_ = config;
  config_.Ca_E = ca_e;
  config_.Ca = ca;
}

bool CapsuleNode::OnPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  if (run_state_ == RunState::kFailed || run_state_ == RunState::kFinished) {
    res.success = false;
    res.message = "simulation is not running: " + (failure_.empty() ? "finished" : failure_);
    return true;
  }
  run_state_ = RunState::kPaused;
  config_.paused = true;
  config_dirty_ = true;
  res.success = true;
  res.message = "paused at step " + std::to_string(sim_->state().step);
  ROS_INFO("ehd_capsule: %s", res.message.c_str());
  return true;
}

bool CapsuleNode::OnResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
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
  res.message = "resumed at step " + std::to_string(sim_->state().step);
  ROS_INFO("ehd_capsule: %s", res.message.c_str());
  return true;
}

bool CapsuleNode::OnReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  pending_reset_ = true;
  res.success = true;
  res.message = "reset queued; applied before the next step";
  return true;
}

bool CapsuleNode::OnAdvance(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  if (run_state_ != RunState::kPaused) {
    res.success = false;
    res.message = "advance works while paused (call ~pause first)";
    return true;
  }
  advance_remaining_ += advance_steps_;
  res.success = true;
  res.message = "advancing " + std::to_string(advance_steps_) + " steps from step " +
                std::to_string(sim_->state().step);
  return true;
}

bool CapsuleNode::OnAdvanceBy(ehd_capsule::Advance::Request& req,
                              ehd_capsule::Advance::Response& res) {
  if (req.steps < 1) {
    res.success = false;
    res.message = "steps must be >= 1 (got " + std::to_string(req.steps) + ")";
    return true;
  }
  if (run_state_ != RunState::kPaused) {
    res.success = false;
    res.message = "advance works while paused (call ~pause first)";
    return true;
  }
  advance_remaining_ += req.steps;
  res.success = true;
  res.message = "advancing " + std::to_string(req.steps) + " steps from step " +
                std::to_string(sim_->state().step);
  return true;
}

void CapsuleNode::ApplyPendingRequests() {
  if (pending_reset_) {
    pending_reset_ = false;
    sim_->Reset();
    advance_remaining_ = 0;
    states_since_markers_ = 0;
    if (run_state_ == RunState::kFailed || run_state_ == RunState::kFinished) {
      run_state_ = config_.paused ? RunState::kPaused : RunState::kRunning;
      failure_.clear();
    }
    config_.Ca_E = sim_->state().ca_e;
    config_.Ca = sim_->state().ca;
    config_dirty_ = true;
    ROS_INFO("ehd_capsule: reset to the initial state of scene '%s'", scene_name_.c_str());
    if (record_) {
      // A new timeline starts at t = 0: a new bag, numbered (<stem>.1.bag, .2.bag, ...), so no
      // bag holds two timelines; recording resumes after a failure too.
      CloseBag();
      ++bag_serial_;
      std::string stem = base_bag_path_;
      if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".bag") == 0) {
        stem.resize(stem.size() - 4);
      }
      bag_path_ = stem + "." + std::to_string(bag_serial_) + ".bag";
      try {
        OpenBag();
        std_msgs::String scene_msg;
        scene_msg.data = scene_.yaml_text;
        Record("scene", scene_msg, StampNow());
        record_failure_.clear();
      } catch (const std::exception& e) {
        ROS_ERROR("ehd_capsule: cannot record after the reset: %s", e.what());
      }
    }
    PublishSurfaceMesh();
  }
  const long next_step = sim_->state().step + 1;
  if (pending_ca_e_) {
    const double value = *pending_ca_e_;
    pending_ca_e_.reset();
    try {
      sim_->SetCaE(value);
      config_.Ca_E = value;
      ROS_INFO("ehd_capsule: Ca_E = %g from step %ld", value, next_step);
    } catch (const std::exception& e) {
      ROS_ERROR("ehd_capsule: refused Ca_E = %g: %s (Ca_E stays %g)", value, e.what(),
                config_.Ca_E);
    }
    config_dirty_ = true;
  }
  if (pending_ca_) {
    const double value = *pending_ca_;
    pending_ca_.reset();
    try {
      sim_->SetCa(value);
      config_.Ca = value;
      ROS_INFO("ehd_capsule: Ca = %g from step %ld", value, next_step);
    } catch (const std::exception& e) {
      ROS_ERROR("ehd_capsule: refused Ca = %g: %s (Ca stays %g)", value, e.what(), config_.Ca);
    }
    config_dirty_ = true;
  }
  if (config_dirty_) {
    config_dirty_ = false;
    config_.publish_every = publish_every_;
    reconfigure_->updateConfig(config_);
  }
}

void CapsuleNode::Fail(const std::string& reason) {
  run_state_ = RunState::kFailed;
  failure_ = reason;
  ROS_ERROR("ehd_capsule: simulation stopped at step %ld: %s", sim_->state().step, reason.c_str());
  if (exit_on_error_) {
    ROS_ERROR("ehd_capsule: exiting with status 1 (~exit_on_error)");
  } else {
    ROS_ERROR("ehd_capsule: the node stays up for inspection; call ~reset to start over");
  }
  PublishDiagnostics(true);
  PublishField(true);  // the layer of the state the run stopped at
  CloseBag();
}

void CapsuleNode::StepOnce() {
  try {
    sim_->Step();
  } catch (const std::exception& e) {
    Fail(e.what());
    return;
  }
  ++rate_window_steps_;
  const long step = sim_->state().step;
  if (step % publish_every_ == 0) PublishState();
  if (max_steps_ > 0 && step >= max_steps_) {
    run_state_ = RunState::kFinished;
    ROS_INFO("ehd_capsule: reached %ld steps (t = %g); stopping", step, sim_->state().time);
  }
  if (steady_monitor_ &&
      steady_monitor_->Update(sim_->state().time, sim_->state().dxy, sim_->state().inclination)) {
    run_state_ = RunState::kFinished;
    ROS_INFO("ehd_capsule: steady to %g at t = %g (D_xy = %.5f, theta/pi = %.4f); stopping",
             until_steady_, sim_->state().time, sim_->state().dxy,
             sim_->state().inclination / M_PI);
  }
}

void CapsuleNode::PublishStaticTransform() {
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time(0);
  t.header.frame_id = world_frame_;
  t.child_frame_id = frame_id_;
  t.transform.rotation.w = 1.0;
  tf2_msgs::TFMessage message;
  message.transforms.push_back(t);
  tf_static_pub_.publish(message);
}

void CapsuleNode::PublishField(bool force) {
  if (field_layer_ == FieldLayer::kNone) return;
  const ros::WallTime now = ros::WallTime::now();
  // At most ~field_rate per wall second for a live view, and at least every ~field_interval of
  // simulation time, so a fast run's bag replays with the layer moving along.
  const bool wall_due = (now - last_field_).toSec() >= 1.0 / field_rate_;
  const bool sim_due = sim_->state().time - last_field_time_ >= field_interval_;
  if (!force && !wall_due && !sim_due) return;
  if (!force && sim_->state().step == last_field_step_) return;
  last_field_ = now;
  last_field_step_ = sim_->state().step;
  last_field_time_ = sim_->state().time;
  const StateMessageSettings settings{frame_id_, force_arrow_scale_, velocity_arrows_,
                                      velocity_stride_, surface_colour_};
  const ros::Time stamp = StampNow();
  const visualization_msgs::MarkerArray field =
      MakeFieldLayer(*sim_, field_layer_, field_stride_, settings, stamp);
  field_pub_.publish(field);
  Record("field", field, stamp);
}

void CapsuleNode::PublishThrottled() {
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_throttled_).toSec() < 1.0 / throttled_rate_) return;
  if (sim_->state().step == last_throttled_step_) return;  // nothing new (paused, finished)
  last_throttled_ = now;
  last_throttled_step_ = sim_->state().step;
  const StateMessageSettings settings{frame_id_, force_arrow_scale_, velocity_arrows_,
                                      velocity_stride_, surface_colour_};
  throttled_pub_.publish(MakeCapsuleState(*sim_, settings, StampNow()));
}

void CapsuleNode::PrintProgress(bool force) {
  if (progress_period_ <= 0.0 && !force) return;
  const ros::WallTime now = ros::WallTime::now();
  if (!force && (now - last_progress_).toSec() < progress_period_) return;
  const SimulationState& s = sim_->state();
  const double wall = (now - last_progress_).toSec();
  const double rate = wall > 0.0 ? (s.step - last_progress_step_) / wall : 0.0;
  ROS_INFO(
      "ehd_capsule: step %ld  t = %.4g %s  D_xy = %.5f  theta/pi = %.4f  area drift = "
      "%.2e  %.0f steps/s",
      s.step, s.time, sim_->units().time_unit.c_str(), s.dxy, s.inclination / M_PI, s.area_drift,
      rate);
  last_progress_ = now;
  last_progress_step_ = s.step;
}

void CapsuleNode::PublishState() {
  const ros::Time stamp = StampNow();
  // The clock goes with the states (at publish_every 100 it used to be 40% of a bag, published
  // every step), and only from the node that owns it (~publish_clock).
  if (use_sim_time_ && publish_clock_) {
    rosgraph_msgs::Clock clock;
    clock.clock = stamp;
    clock_pub_.publish(clock);
    Record("/clock", clock, clock.clock);
  }
  const StateMessageSettings settings{frame_id_, force_arrow_scale_, velocity_arrows_,
                                      velocity_stride_, surface_colour_};
  const ehd_capsule::CapsuleState state = MakeCapsuleState(*sim_, settings, stamp);
  const geometry_msgs::PolygonStamped shape = MakeShape(*sim_, settings, stamp);
  state_pub_.publish(state);
  shape_pub_.publish(shape);
  ++published_states_;
  if (bag_open_) {
    Record("state", state, stamp);
    Record("shape", shape, stamp);
  }
  if (sim_->dimension() == 3) {
    const ehd_capsule::SurfaceState surface = MakeSurfaceState(*sim_, settings, stamp);
    surface_state_pub_.publish(surface);
    if (bag_open_) Record("surface_state", surface, stamp);
  }
  // The marker array with the first state and every markers_every-th after it.
  if (states_since_markers_ == 0) {
    const visualization_msgs::MarkerArray markers = MakeMarkerArray(*sim_, settings, stamp);
    markers_pub_.publish(markers);
    if (bag_open_) Record("markers", markers, stamp);
  }
  if (++states_since_markers_ >= markers_every_) states_since_markers_ = 0;
}

void CapsuleNode::PublishSurfaceMesh() {
  if (sim_->dimension() != 3) return;
  const StateMessageSettings settings{frame_id_, force_arrow_scale_, velocity_arrows_,
                                      velocity_stride_, surface_colour_};
  const ehd_capsule::SurfaceMesh mesh = MakeSurfaceMesh(*sim_, settings, StampNow());
  surface_mesh_pub_.publish(mesh);
  Record("surface_mesh", mesh, StampNow());
}

void CapsuleNode::PublishDiagnostics(bool force) {
  const ros::WallTime now = ros::WallTime::now();
  if (!force && (now - last_diag_).toSec() < 1.0) return;
  const double window = (now - rate_window_start_).toSec();
  if (window > 0.0) step_rate_ = rate_window_steps_ / window;
  rate_window_start_ = now;
  rate_window_steps_ = 0;
  last_diag_ = now;

  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  diagnostic_msgs::DiagnosticStatus status;
  status.name = ros::this_node::getName() + ": simulation";  // distinct per node
  status.hardware_id = scene_name_;
  const SimulationState& s = sim_->state();
  switch (run_state_) {
    case RunState::kRunning:
      status.level = status.OK;
      status.message = "running";
      break;
    case RunState::kPaused:
      status.level = status.OK;
      status.message = "paused";
      break;
    case RunState::kFinished:
      status.level = status.OK;
      status.message = "finished";
      break;
    case RunState::kFailed:
      status.level = status.ERROR;
      status.message = failure_;
      break;
  }
  auto add = [&status](const std::string& key, const std::string& value) {
    diagnostic_msgs::KeyValue kv;
    kv.key = key;
    kv.value = value;
    status.values.push_back(kv);
  };
  add("step", std::to_string(s.step));
  add("time", std::to_string(s.time));
  add("step_rate_hz", std::to_string(step_rate_));
  add("gmres_iterations", std::to_string(s.gmres_iterations));
  add("gmres_residual", std::to_string(s.gmres_residual));
  add("area_drift", std::to_string(s.area_drift));
  add("max_mach", std::to_string(s.max_mach));
  add("Ca_E", std::to_string(s.ca_e));
  add("Ca", std::to_string(s.ca));
  if (!record_failure_.empty() && status.level != status.ERROR) {
    status.level = status.ERROR;
    status.message = record_failure_;
  }
  array.status.push_back(status);
  diag_pub_.publish(array);
  // In the bag too, so that it tells why it ended (a failure is recorded before it is closed).
  Record("/diagnostics", array, StampNow());
}

int CapsuleNode::Run() {
  rate_window_start_ = last_diag_ = last_progress_ = run_start_ = ros::WallTime::now();
  ros::WallTime next_step_time = ros::WallTime::now();
  while (ros::ok()) {
    ros::spinOnce();
    ApplyPendingRequests();
    PublishDiagnostics(false);
    if (run_state_ == RunState::kRunning) PrintProgress(false);
    PublishThrottled();
    PublishField(false);
    if (run_state_ == RunState::kFinished) break;
    if (run_state_ == RunState::kFailed && exit_on_error_) break;
    const bool may_step = run_state_ == RunState::kRunning ||
                          (run_state_ == RunState::kPaused && advance_remaining_ > 0);
    if (!may_step) {
      ros::WallDuration(0.01).sleep();
      continue;
    }
    if (max_step_rate_ > 0.0) {
      const ros::WallTime now = ros::WallTime::now();
      if (now < next_step_time) (next_step_time - now).sleep();
      next_step_time = std::max(now, next_step_time) + ros::WallDuration(1.0 / max_step_rate_);
    }
    StepOnce();
    if (run_state_ == RunState::kPaused && advance_remaining_ > 0) {
      if (--advance_remaining_ == 0) {
        ROS_INFO("ehd_capsule: advanced to step %ld (paused)", sim_->state().step);
      }
    }
  }
  PublishDiagnostics(true);
  {
    const SimulationState& st = sim_->state();
    const double wall = (ros::WallTime::now() - run_start_).toSec();
    ROS_INFO(
        "ehd_capsule: summary: %s after %ld steps, t = %.4g %s: D_xy = %.5f, theta/pi = "
        "%.4f, area drift = %.2e; %.1f s wall (%.0f steps/s)",
        run_state_ == RunState::kFailed ? "stopped on an error" : "ran", st.step, st.time,
        sim_->units().time_unit.c_str(), st.dxy, st.inclination / M_PI, st.area_drift, wall,
        wall > 0 ? st.step / wall : 0.0);
  }
  if (sim_->state().step != last_field_step_) PublishField(true);  // the final state's layer
  CloseBag();
  // Exit status: 1 if the simulation stopped on an error (even when the node was shut down
  // afterwards), 0 otherwise; main() returns 1 for an invalid scene or parameter.
  return run_state_ == RunState::kFailed || !record_failure_.empty() ? 1 : 0;
}

}  // namespace ehd::ros_node
