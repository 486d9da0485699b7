#include "ehd_capsule/ros/node_publishers.h"

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PolygonStamped.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>

namespace ehd::ros_node {

namespace {

tf2_msgs::TFMessage StaticTransform(const NodeParameters& p) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time(0);
  t.header.frame_id = p.world_frame;
  t.child_frame_id = p.frame_id;
  t.transform.rotation.w = 1.0;
  tf2_msgs::TFMessage message;
  message.transforms.push_back(t);
  return message;
}

}  // namespace

NodePublishers::NodePublishers(ros::NodeHandle& nh, ros::NodeHandle& pnh,
                               const NodeParameters& params, const Simulation& sim,
                               BagRecorder* recorder)
    : params_(params), sim_(sim), recorder_(recorder) {
  settings_ =
      StateMessageSettings{params.frame_id, params.force_arrow_scale, params.velocity_arrows,
                           params.velocity_stride, ParseSurfaceColour(params.surface_colour)};
  field_layer_ = ParseFieldLayer(params.field_layer, sim);
  field_stride_ = params.field_stride > 0 ? params.field_stride : std::max(1, sim.scene().N / 64);
  markers_every_ = params.markers_every > 0 ? params.markers_every : sim.dimension() == 3 ? 10 : 1;

  state_pub_ = pnh.advertise<ehd_capsule::CapsuleState>("state", 1000);
  // Latched: while paused nothing new is published, and a late subscriber (`rostopic echo -n1`
  // after ~advance_by) waited for ever.
  throttled_pub_ = pnh.advertise<ehd_capsule::CapsuleState>("state_throttled", 10, /*latch=*/true);
  field_pub_ = pnh.advertise<visualization_msgs::MarkerArray>("field", 2);
  tf_static_pub_ = nh.advertise<tf2_msgs::TFMessage>("/tf_static", 1, /*latch=*/true);
  shape_pub_ = pnh.advertise<geometry_msgs::PolygonStamped>("shape", 10);
  markers_pub_ = pnh.advertise<visualization_msgs::MarkerArray>("markers", 10);
  scene_pub_ = pnh.advertise<std_msgs::String>("scene", 1, /*latch=*/true);
  diag_pub_ = nh.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  if (sim.dimension() == 3) {
    surface_mesh_pub_ = pnh.advertise<ehd_capsule::SurfaceMesh>("surface_mesh", 1, /*latch=*/true);
    surface_state_pub_ = pnh.advertise<ehd_capsule::SurfaceState>("surface_state", 1000);
  }
  if (params.use_sim_time && params.publish_clock) {
    clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 100);
  }
}

ros::Time NodePublishers::StampNow() const {
  if (params_.use_sim_time) return ros::Time(std::max(sim_.state().time, 0.0));
  return ros::Time::now();
}

void NodePublishers::StartClocks() {
  rate_window_start_ = last_diag_ = ros::WallTime::now();
  rate_window_steps_ = 0;
}

void NodePublishers::PublishScene() {
  std_msgs::String scene_msg;
  scene_msg.data = sim_.scene().yaml_text;
  scene_pub_.publish(scene_msg);
}

void NodePublishers::PublishStaticTransform() { tf_static_pub_.publish(StaticTransform(params_)); }

void NodePublishers::RecordBagHeader() {
  if (!recorder_) return;
  // The frame's static transform and the scene, as latched connections (as they are
  // published), so `rosbag play` latches them again: rviz has the frame, and a tool that
  // subscribes late the scene.
  recorder_->WriteLatched("/tf_static", StaticTransform(params_), StampNow());
  std_msgs::String scene_msg;
  scene_msg.data = sim_.scene().yaml_text;
  recorder_->WriteLatched("scene", scene_msg, StampNow());
}

void NodePublishers::PublishSurfaceMesh() {
  if (sim_.dimension() != 3) return;
  const ehd_capsule::SurfaceMesh mesh = MakeSurfaceMesh(sim_, settings_, StampNow());
  surface_mesh_pub_.publish(mesh);
  if (recorder_) recorder_->WriteLatched("surface_mesh", mesh, StampNow());
}

void NodePublishers::PublishState() {
  const ros::Time stamp = StampNow();
  if (recorder_) recorder_->BeginState();
  // The clock goes with the states (at publish_every 100 it used to be 40% of a bag, published
  // every step), and only from the node that owns it (~publish_clock).
  if (params_.use_sim_time && params_.publish_clock) {
    rosgraph_msgs::Clock clock;
    clock.clock = stamp;
    clock_pub_.publish(clock);
    Record("/clock", clock, clock.clock);
  }
  const ehd_capsule::CapsuleState state = MakeCapsuleState(sim_, settings_, stamp);
  const geometry_msgs::PolygonStamped shape = MakeShape(sim_, settings_, stamp);
  state_pub_.publish(state);
  shape_pub_.publish(shape);
  if (recorder_ && recorder_->Write("state", state, stamp)) recorder_->CountState();
  Record("shape", shape, stamp);
  if (sim_.dimension() == 3) {
    const ehd_capsule::SurfaceState surface = MakeSurfaceState(sim_, settings_, stamp);
    surface_state_pub_.publish(surface);
    Record("surface_state", surface, stamp);
  }
  // The marker array with the first state and every markers_every-th after it.
  if (states_since_markers_ == 0) {
    const visualization_msgs::MarkerArray markers = MakeMarkerArray(sim_, settings_, stamp);
    markers_pub_.publish(markers);
    Record("markers", markers, stamp);
  }
  if (++states_since_markers_ >= markers_every_) states_since_markers_ = 0;
}

void NodePublishers::PublishThrottled() {
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_throttled_).toSec() < 1.0 / params_.throttled_rate) return;
  if (sim_.state().step == last_throttled_step_) return;  // nothing new (paused, finished)
  last_throttled_ = now;
  last_throttled_step_ = sim_.state().step;
  throttled_pub_.publish(MakeCapsuleState(sim_, settings_, StampNow()));
}

void NodePublishers::PublishField(bool force) {
  if (field_layer_ == FieldLayer::kNone) return;
  const ros::WallTime now = ros::WallTime::now();
  // At most ~field_rate per wall second for a live view, and at least every ~field_interval of
  // simulation time, so a fast run's bag replays with the layer moving along.
  const bool wall_due = (now - last_field_).toSec() >= 1.0 / params_.field_rate;
  const bool sim_due = sim_.state().time - last_field_time_ >= params_.field_interval;
  if (!force && !wall_due && !sim_due) return;
  if (!force && sim_.state().step == last_field_step_) return;
  last_field_ = now;
  last_field_step_ = sim_.state().step;
  last_field_time_ = sim_.state().time;
  const ros::Time stamp = StampNow();
  const visualization_msgs::MarkerArray field =
      MakeFieldLayer(sim_, field_layer_, field_stride_, settings_, stamp);
  field_pub_.publish(field);
  Record("field", field, stamp);
}

void NodePublishers::PublishDiagnostics(bool force, const RunStatus& run) {
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
  status.hardware_id = params_.scene;
  status.level = run.error ? status.ERROR : status.OK;
  status.message = run.message;
  if (!run.refused.empty() && !run.error) {
    // A refused live value, visible to whoever changed it (dynamic_reconfigure's caller gets
    // the kept value back; `dynparam set` says nothing).
    status.level = status.WARN;
    status.message += "; " + run.refused;
  }
  const SimulationState& s = sim_.state();
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
  if (!run.refused.empty()) add("refused", run.refused);
  if (recorder_ && !recorder_->failure().empty() && status.level != status.ERROR) {
    status.level = status.ERROR;
    status.message = recorder_->failure();
  }
  array.status.push_back(status);
  diag_pub_.publish(array);
  // In the bag too, so that it tells why it ended (a failure is recorded before it is closed).
  Record("/diagnostics", array, StampNow());
}

}  // namespace ehd::ros_node
