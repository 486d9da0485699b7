// Everything the node publishes, and records into its bag with the same message: ~state,
// ~shape, ~markers (every ~markers_every-th state), 3D ~surface_state and the latched
// ~surface_mesh, the latched ~state_throttled (wall-clock rate), ~field (wall-clock rate and
// simulation interval), the latched ~scene and /tf_static, /clock (with /use_sim_time) and
// /diagnostics. The messages themselves are made by state_messages.h; this class decides when, and
// keeps the publishers and the rate bookkeeping.
#pragma once

#include <ros/ros.h>

#include <string>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/ros/bag_recorder.h"
#include "ehd_capsule/ros/node_parameters.h"
#include "ehd_capsule/ros/state_messages.h"

namespace ehd::ros_node {

// The run's state as /diagnostics reports it.
struct RunStatus {
  bool error = false;
  std::string message;  // running, paused, finished, or the failure
  // The last refused live value ("refused Ca_E = 100: ...; Ca_E stays 0.6"), until a later
  // change is accepted or the run is reset: a WARN status (unless an error) and the key
  // "refused".
  std::string refused;
};

class NodePublishers {
 public:
  // Advertises every topic. recorder may be null (not recording); it must outlive this.
  NodePublishers(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParameters& params,
                 const Simulation& sim, BagRecorder* recorder);

  // Simulation time with /use_sim_time, else the wall clock.
  ros::Time StampNow() const;

  // The latched ~scene (the scene's YAML, overrides applied) and /tf_static (world_frame ->
  // frame_id, identity, so rviz has the frame).
  void PublishScene();
  void PublishStaticTransform();
  // What every bag starts with: /tf_static, then ~scene, both as latched connections (so
  // `rosbag play` latches them again for a late subscriber).
  void RecordBagHeader();
  // 3D: the latched triangles, published and recorded as a latched connection (again after a
  // reset); nothing in 2D.
  void PublishSurfaceMesh();
  // One published state: /clock (with /use_sim_time and ~publish_clock), ~state, ~shape, 3D
  // ~surface_state, and ~markers with the first state and every markers_every-th after it.
  void PublishState();
  // After a reset the marker array comes with the next state again.
  void RestartMarkers() { states_since_markers_ = 0; }
  // The latest state on ~state_throttled, at most ~throttled_rate times per wall second;
  // latched, so a subscriber that comes while the run is paused (`rostopic echo -n1` after
  // ~advance_by) gets the state it stands at.
  void PublishThrottled();
  // The coloured layer on ~field, at most ~field_rate times per wall second and at least every
  // ~field_interval of simulation time; force: now (a failure, the end).
  void PublishField(bool force);
  bool field_is_current() const { return sim_.state().step == last_field_step_; }
  // Once a wall second (force: now): step rate, GMRES, drifts, Ca, Ca_E, and the run's status
  // (ERROR with the recording failure, if any).
  void PublishDiagnostics(bool force, const RunStatus& status);
  // Counted for the step rate in the diagnostics.
  void CountStep() { ++rate_window_steps_; }
  // Starts the step-rate window and the throttles' wall clock.
  void StartClocks();

 private:
  template <typename M>
  void Record(const std::string& topic, const M& msg, const ros::Time& stamp) {
    if (recorder_) recorder_->Write(topic, msg, stamp);
  }

  const NodeParameters& params_;
  const Simulation& sim_;
  BagRecorder* recorder_;
  StateMessageSettings settings_;
  FieldLayer field_layer_ = FieldLayer::kSpeed;
  int field_stride_ = 1;
  int markers_every_ = 1;

  ros::Publisher state_pub_, shape_pub_, markers_pub_, scene_pub_, clock_pub_, diag_pub_;
  ros::Publisher throttled_pub_, field_pub_, tf_static_pub_;
  ros::Publisher surface_mesh_pub_, surface_state_pub_;  // 3D only

  long states_since_markers_ = 0;  // published states since the last marker array
  ros::WallTime last_throttled_;
  long last_throttled_step_ = -1;
  ros::WallTime last_field_;
  long last_field_step_ = -1;
  double last_field_time_ = -1e300;
  ros::WallTime last_diag_, rate_window_start_;
  long rate_window_steps_ = 0;
  double step_rate_ = 0.0;
};

}  // namespace ehd::ros_node
