// ehd_capsule_node: a thin roscpp layer over ehd::Simulation.
//
// Follows turtlesim: callbacks (dynamic_reconfigure, services) only record what was asked; the
// step loop applies the requests before the next step and publishes after it, all on one thread,
// so nothing needs a lock. Topics and parameters are private (~state, ~shape, ~markers, ~scene),
// so several copies run side by side in their own namespaces.
//
// The node records the bag itself (rosbag C++ API) when ~record is true: every published
// CapsuleState, shape, marker array and clock tick is written on the same thread that publishes
// it, so the bag holds exactly one CapsuleState per published step, and it is closed on finish,
// on Ctrl-C and when the simulation stops on an error.
#pragma once

#include <diagnostic_msgs/DiagnosticArray.h>
#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <std_srvs/Trigger.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ehd_capsule/Advance.h"
#include "ehd_capsule/CapsuleState.h"
#include "ehd_capsule/SimulationConfig.h"
#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/coupling/steady_state.h"
#include "ehd_capsule/ros/state_messages.h"
#include "ehd_capsule/scene/scene.h"

namespace ehd::ros_node {

class CapsuleNode {
 public:
  // Reads the private parameters, loads and builds the scene. Throws std::exception with a clear
  // message if the scene is invalid (main() logs it and exits non-zero).
  CapsuleNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  ~CapsuleNode();

  // Steps until ~steps is reached (returns 0) or ROS shuts down. A simulation error stops the
  // stepping; with ~exit_on_error (the default for a batch run, ~steps > 0) Run returns 1 at
  // once, else the node stays up for inspection and returns 1 at shutdown.
  int Run();

 private:
  enum class RunState { kRunning, kPaused, kFailed, kFinished };

  void ReadParameters();
  void BuildSimulation();
  void OpenBag();
  void CloseBag();
  std::string ActiveBagPath() const;  // <bag>.active while recording
  void OnReconfigure(ehd_capsule::SimulationConfig& config, uint32_t level);
  bool OnPause(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool OnResume(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool OnReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool OnAdvance(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool OnAdvanceBy(ehd_capsule::Advance::Request& req, ehd_capsule::Advance::Response& res);
  void ApplyPendingRequests();
  void StepOnce();
  void PublishState();
  void PublishSurfaceMesh();  // 3D: the latched triangles (and into the bag)
  void PublishDiagnostics(bool force);
  // One console line (step, t, D_xy, theta, area drift, steps/s) every ~progress_period wall
  // seconds while running (0: never), and a summary at the end of Run().
  void PrintProgress(bool force);
  // Warns with the memory and time estimate when the scene is too large to watch live.
  void WarnIfLarge() const;
  // The latest state on ~state_throttled, at most ~throttled_rate times per wall second.
  void PublishThrottled();
  // The coloured grid layer (~field_layer) on ~field, at most ~field_rate times per wall second.
  void PublishField(bool force);
  // world_frame -> frame_id (identity) on /tf_static, latched, so rviz has the frame.
  void PublishStaticTransform();
  void Fail(const std::string& reason);
  ros::Time StampNow() const;
  template <typename M>
  void Record(const std::string& topic, const M& msg, const ros::Time& stamp);

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;

  // Parameters.
  std::string scene_name_;
  std::vector<std::string> overrides_;
  long max_steps_ = 0;  // 0: run until shutdown
  int publish_every_ = 1;
  // The marker array (surface, section, arrows, text) with every n-th published state: 1 in 2D,
  // 10 in 3D by default (the surface's triangle list is most of a 3D bag).
  int markers_every_ = 1;
  std::string frame_id_ = "ehd";
  double force_arrow_scale_ = 1.0;
  bool velocity_arrows_ = false;
  int velocity_stride_ = 8;
  SurfaceColour surface_colour_ = SurfaceColour::kTraction;  // 3D surface colouring
  double max_step_rate_ = 0.0;    // steps per wall second, 0: as fast as possible
  double progress_period_ = 5.0;  // wall seconds between console progress lines, 0: none
  ros::WallTime last_progress_, run_start_;
  long last_progress_step_ = 0;
  bool record_ = false;
  std::string bag_path_;
  bool use_sim_time_ = false;
  bool overwrite_ = false;             // ~overwrite: replace an existing bag
  bool exit_on_error_ = false;         // ~exit_on_error (default: ~steps > 0)
  bool stop_on_record_error_ = false;  // ~on_record_error: pause (default) or stop
  std::string record_failure_;         // why recording stopped (empty: it did not)
  std::string base_bag_path_;          // ~bag as given; resets record to <stem>.<n>.bag
  int bag_serial_ = 0;
  bool publish_clock_ = true;     // ~publish_clock: this node owns /clock (with /use_sim_time)
  double throttled_rate_ = 20.0;  // ~throttled_rate, Hz of wall time
  double until_steady_ = 0.0;     // ~until_steady tolerance, 0: off
  std::unique_ptr<SteadyStateMonitor> steady_monitor_;
  ros::WallTime last_throttled_;
  long last_throttled_step_ = -1;
  std::string field_layer_name_ = "speed";  // ~field_layer: none, speed, potential, field
  FieldLayer field_layer_ = FieldLayer::kSpeed;
  int field_stride_ = 0;         // ~field_stride, cells per square (0: N / 64, at least 1)
  double field_rate_ = 2.0;      // ~field_rate, Hz of wall time
  double field_interval_ = 0.1;  // ~field_interval: at least this often in simulation time
  double last_field_time_ = -1e300;
  std::string world_frame_;  // ~world_frame, parent of frame_id in /tf_static
  ros::WallTime last_field_;
  long last_field_step_ = -1;

  Scene scene_;
  std::unique_ptr<Simulation> sim_;
  RunState run_state_ = RunState::kRunning;
  std::string failure_;

  // Requests recorded by callbacks, applied by the loop.
  std::optional<double> pending_ca_e_;
  std::optional<double> pending_ca_;
  bool pending_reset_ = false;
  long advance_remaining_ = 0;
  int advance_steps_ = 1;
  ehd_capsule::SimulationConfig config_;
  bool config_dirty_ = false;  // config_ must be pushed back to dynamic_reconfigure

  ros::Publisher state_pub_, shape_pub_, markers_pub_, scene_pub_, clock_pub_, diag_pub_;
  ros::Publisher throttled_pub_;                         // ~state_throttled
  ros::Publisher field_pub_;                             // ~field
  ros::Publisher tf_static_pub_;                         // /tf_static
  ros::Publisher surface_mesh_pub_, surface_state_pub_;  // 3D only
  ros::ServiceServer pause_srv_, resume_srv_, reset_srv_, advance_srv_, advance_by_srv_;
  std::unique_ptr<dynamic_reconfigure::Server<ehd_capsule::SimulationConfig>> reconfigure_;
  boost::recursive_mutex reconfigure_mutex_;

  rosbag::Bag bag_;
  bool bag_open_ = false;
  long published_states_ = 0;
  long states_since_markers_ = 0;  // published states since the last marker array

  ros::WallTime last_diag_;
  ros::WallTime rate_window_start_;
  long rate_window_steps_ = 0;
  double step_rate_ = 0.0;
};

}  // namespace ehd::ros_node
