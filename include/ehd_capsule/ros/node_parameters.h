// The node's private parameters (~scene, ~steps, ~record, ...) as a plain struct: read from the
// parameter server by ReadNodeParameters, checked by ValidateNodeParameters (no ROS master
// needed, so it is tested alone: test/ros_unit/node_parameters_test.cpp).
#pragma once

#include <xmlrpcpp/XmlRpcValue.h>

#include <map>
#include <string>
#include <vector>

#include "ehd_capsule/ros/state_messages.h"

namespace ros {
class NodeHandle;
}

namespace ehd::ros_node {

// What the node does when writing the bag fails (disk full, file size limit, I/O error).
enum class RecordErrorAction {
  kPause,  // stop recording, pause the simulation (~resume continues unrecorded)
  kStop,   // stop recording and the simulation, as on a simulation error (~exit_on_error)
};

struct NodeParameters {
  std::string scene = "shear_field";
  std::vector<std::string> overrides;  // "key=value", from ~set, ~start_Ca_E, ~start_Ca
  long steps = 0;                      // 0: run until shutdown
  double until_steady = 0.0;           // tolerance, 0: off
  int publish_every = 1;
  // The marker array with every n-th published state; 0: 1 in 2D, 10 in 3D (the surface's
  // triangle list is most of a 3D bag).
  int markers_every = 0;
  std::string frame_id = "ehd";
  std::string world_frame = "world";  // parent of frame_id in /tf_static
  double force_arrow_scale = 1.0;
  bool velocity_arrows = false;
  int velocity_stride = 8;
  std::string surface_colour = "traction";  // ParseSurfaceColour
  std::string field_layer = "speed";        // ParseFieldLayer (needs the simulation)
  int field_stride = 0;                     // cells per square, 0: N / 64 (at least 1)
  double field_rate = 2.0;                  // Hz of wall time
  double field_interval = 0.1;              // at least this often in simulation time
  double max_step_rate = 0.0;               // steps per wall second, 0: as fast as possible
  double progress_period = 5.0;             // wall seconds between progress lines, 0: none
  double throttled_rate = 20.0;             // ~state_throttled, Hz of wall time
  bool record = false;
  std::string bag = "ehd_capsule.bag";  // absolute once read (ResolveNodePath)
  // ~working_directory: what a relative ~bag or scene path is resolved against (the launch files
  // pass the directory roslaunch was started in); empty: the node's own (rosrun: the caller's).
  std::string working_directory;
  bool overwrite = false;
  // ~on_record_error: "pause" or "stop"; default (ReadNodeParameters): stop for a batch run
  // (~steps or ~until_steady), pause for a live one.
  std::string on_record_error = "pause";
  bool exit_on_error = false;  // default: ~steps > 0
  int advance_steps = 1;
  bool publish_clock = true;  // this node owns /clock (with /use_sim_time)
  bool use_sim_time = false;  // /use_sim_time (global)

  bool batch() const { return steps > 0 || until_steady > 0.0; }
  RecordErrorAction record_error_action() const;
};

// Throws std::invalid_argument naming the parameter, the value and what is accepted; checks in
// the order the parameters are documented (the first problem is the one reported).
void ValidateNodeParameters(const NodeParameters& p);

// ~set (a dictionary of scene keys, e.g. {Ca: 0.1, N: 64}; a nested dictionary names a
// section's keys: {geometry: {half_width: 3}} is geometry.half_width=3) as "key=value"
// overrides; doubles as the shortest text that reads back the same. Throws
// std::invalid_argument for anything but a dictionary of numbers, booleans, strings and
// dictionaries.
std::vector<std::string> SceneOverrides(XmlRpc::XmlRpcValue& set);
// ~start_Ca_E / ~start_Ca (the launch arguments Ca_E and Ca; < 0: the scene's value) as
// overrides appended after ~set's.
std::vector<std::string> StartValueOverrides(double start_ca_e, double start_ca);

// The name:=value arguments of a command line (_name:=value, __log:=..., topic remappings) as
// name -> value.
std::map<std::string, std::string> CommandLineRemappings(const std::vector<std::string>& args);
// The private parameters a start takes from the parameter server without being told to: of
// server_names (the server's parameter names, as ros::param::getParamNames gives them), those in
// private_ns ("/ehd_capsule") that remappings (CommandLineRemappings of the node's command line)
// do not give as _name:=value, relative ("steps", "set/N"), sorted.
// dynamic_reconfigure's Ca_E, Ca and paused are left out (a start overwrites them with the
// scene's values). Empty when the node runs under roslaunch (a __log remapping): the launch files
// clear the private namespace first (clear_params), so what is there is the launch's.
std::vector<std::string> UnrequestedParameters(
    const std::vector<std::string>& server_names, const std::string& private_ns,
    const std::map<std::string, std::string>& remappings);

// A path parameter (~bag, a scene path) as an absolute, normalized path: a relative one against
// working_directory (~working_directory), or, when that is empty, against process_cwd, the
// node's own directory, unless the node runs under roslaunch (which starts it in ROS_HOME, not
// where the user is): then a relative path is refused with std::invalid_argument naming param.
std::string ResolveNodePath(const std::string& param, const std::string& path,
                            const std::string& working_directory, const std::string& process_cwd,
                            bool under_roslaunch);

// Reads every private parameter (and /use_sim_time), validates them and writes the effective
// scene, publish_every and frame_id back (so `rosparam get` shows what runs). Warns naming each
// parameter (and its value) of UnrequestedParameters: under rosrun, one left by an earlier run
// or set with rosparam would change the run silently.
NodeParameters ReadNodeParameters(ros::NodeHandle& private_nh, const ros::NodeHandle& nh);

}  // namespace ehd::ros_node
