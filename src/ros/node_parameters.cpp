#include "ehd_capsule/ros/node_parameters.h"

#include <ros/ros.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace ehd::ros_node {

RecordErrorAction NodeParameters::record_error_action() const {
  return on_record_error == "stop" ? RecordErrorAction::kStop : RecordErrorAction::kPause;
}

void ValidateNodeParameters(const NodeParameters& p) {
  if (p.steps < 0)
    throw std::invalid_argument("~steps must be >= 0 (got " + std::to_string(p.steps) + ")");
  if (p.publish_every < 1) {
    throw std::invalid_argument("~publish_every must be >= 1 (got " +
                                std::to_string(p.publish_every) + ")");
  }
  if (p.markers_every < 0) {
    throw std::invalid_argument(
        "~markers_every must be >= 1, or 0 for the default (1 in 2D, 10 "
        "in 3D); got " +
        std::to_string(p.markers_every));
  }
  if (p.velocity_stride < 1) throw std::invalid_argument("~velocity_stride must be >= 1");
  ParseSurfaceColour(p.surface_colour);  // throws naming ~surface_colour
  if (p.world_frame.empty() || p.world_frame == p.frame_id) {
    throw std::invalid_argument("~world_frame ('" + p.world_frame +
                                "') must be a frame name other than ~frame_id");
  }
  if (p.field_stride < 0) throw std::invalid_argument("~field_stride must be >= 0 (0: automatic)");
  if (!(p.field_interval > 0.0)) {
    throw std::invalid_argument("~field_interval must be > 0 (units of simulation time)");
  }
  if (!(p.field_rate > 0.0))
    throw std::invalid_argument("~field_rate must be > 0 (Hz of wall time)");
  if (p.on_record_error != "pause" && p.on_record_error != "stop") {
    throw std::invalid_argument("~on_record_error must be pause or stop (got '" +
                                p.on_record_error + "')");
  }
  if (p.until_steady < 0.0) throw std::invalid_argument("~until_steady must be >= 0");
  if (!(p.throttled_rate > 0.0)) {
    throw std::invalid_argument("~throttled_rate must be > 0 (Hz of wall time)");
  }
}

std::vector<std::string> SceneOverrides(XmlRpc::XmlRpcValue& set) {
  if (set.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    throw std::invalid_argument("~set must be a dictionary of scene keys, e.g. {Ca: 0.1}");
  }
  std::vector<std::string> overrides;
  std::function<void(const std::string&, XmlRpc::XmlRpcValue&)> add =
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
              add(key, v);
              continue;
            default:
              throw std::invalid_argument("~set/" + key +
                                          ": only numbers, booleans, strings and dictionaries");
          }
          overrides.push_back(key + "=" + value.str());
        }
      };
  add("", set);
  return overrides;
}

std::vector<std::string> StartValueOverrides(double start_ca_e, double start_ca) {
  std::vector<std::string> overrides;
  const std::pair<const char*, double> values[] = {{"Ca_E", start_ca_e}, {"Ca", start_ca}};
  for (const auto& [key, v] : values) {
    if (v >= 0.0) {
      std::ostringstream value;
      value << v;
      overrides.push_back(std::string(key) + "=" + value.str());
    }
  }
  return overrides;
}

std::map<std::string, std::string> CommandLineRemappings(const std::vector<std::string>& args) {
  std::map<std::string, std::string> remappings;
  for (const std::string& arg : args) {
    const size_t pos = arg.find(":=");
    if (pos != std::string::npos && pos > 0) remappings[arg.substr(0, pos)] = arg.substr(pos + 2);
  }
  return remappings;
}

std::vector<std::string> UnrequestedParameters(
    const std::vector<std::string>& server_names, const std::string& private_ns,
    const std::map<std::string, std::string>& remappings) {
  std::vector<std::string> names;
  if (remappings.count("__log") > 0) return names;  // roslaunch: cleared by clear_params
  const std::string prefix = private_ns + "/";
  for (const std::string& full : server_names) {
    if (full.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string name = full.substr(prefix.size());
    if (name.empty() || name == "Ca_E" || name == "Ca" || name == "paused") continue;
    if (remappings.count("_" + name) > 0) continue;  // given as _name:=value
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

std::string ResolveNodePath(const std::string& param, const std::string& path,
                            const std::string& working_directory, const std::string& process_cwd,
                            bool under_roslaunch) {
  const std::filesystem::path given(path);
  if (given.is_absolute()) return given.lexically_normal().string();
  std::string base = working_directory;
  if (base.empty()) {
    if (under_roslaunch) {
      throw std::invalid_argument(
          param + " '" + path + "' is relative, and roslaunch runs the node in ROS_HOME (" +
          process_cwd +
          "), not where it was started: give an absolute path, or ~working_directory (the "
          "package's launch files pass $(env PWD))");
    }
    base = process_cwd;
  }
  if (!std::filesystem::path(base).is_absolute()) {
    throw std::invalid_argument("~working_directory '" + base + "' must be an absolute path");
  }
  return (std::filesystem::path(base) / given).lexically_normal().string();
}

namespace {

// The process's own command line as name:=value remappings (ros::init took them out of argv,
// and ros::names keeps no _name or __name remapping).
std::map<std::string, std::string> OwnRemappings() {
  std::ifstream cmdline("/proc/self/cmdline", std::ios::binary);
  std::vector<std::string> args;
  for (std::string arg; std::getline(cmdline, arg, '\0');) args.push_back(arg);
  return CommandLineRemappings(args);
}

std::string ParameterText(XmlRpc::XmlRpcValue& v) {
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeDouble: {
      char text[32];
      const auto end = std::to_chars(text, text + sizeof text, static_cast<double>(v));
      return std::string(text, end.ptr);
    }
    case XmlRpc::XmlRpcValue::TypeInt:
      return std::to_string(static_cast<int>(v));
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return static_cast<bool>(v) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeString:
      return static_cast<std::string>(v);
    case XmlRpc::XmlRpcValue::TypeStruct:
      return v.size() == 0 ? "{}" : "{...}";
    default:
      return "(" + v.toXml() + ")";
  }
}

// Under rosrun, the private parameters left on the server by an earlier run (or set with
// rosparam) are taken as if given: say which, with their values.
void WarnUnrequestedParameters(const ros::NodeHandle& pnh) {
  std::vector<std::string> server_names;
  if (!ros::param::getParamNames(server_names)) return;
  const std::vector<std::string> names =
      UnrequestedParameters(server_names, pnh.getNamespace(), OwnRemappings());
  if (names.empty()) return;
  std::string list;
  for (const std::string& name : names) {
    XmlRpc::XmlRpcValue value;
    if (!pnh.getParam(name, value)) continue;
    list += (list.empty() ? "~" : ", ~") + name + " = " + ParameterText(value);
  }
  ROS_WARN(
      "ehd_capsule: taken from the parameter server, not from this command line (left by an "
      "earlier run or set with rosparam; `rosparam delete %s` clears them): %s",
      pnh.getNamespace().c_str(), list.c_str());
}

}  // namespace

NodeParameters ReadNodeParameters(ros::NodeHandle& pnh, const ros::NodeHandle& nh) {
  WarnUnrequestedParameters(pnh);
  NodeParameters p;
  pnh.param<std::string>("scene", p.scene, "shear_field");
  int steps = 0;
  pnh.param("steps", steps, 0);
  p.steps = steps;
  pnh.param("publish_every", p.publish_every, 1);
  pnh.param("markers_every", p.markers_every, 0);
  pnh.param<std::string>("frame_id", p.frame_id, "ehd");
  pnh.param("force_arrow_scale", p.force_arrow_scale, 1.0);
  pnh.param("velocity_arrows", p.velocity_arrows, false);
  pnh.param("velocity_stride", p.velocity_stride, 8);
  pnh.param<std::string>("surface_colour", p.surface_colour, "traction");
  pnh.param<std::string>("world_frame", p.world_frame, "world");
  pnh.param<std::string>("field_layer", p.field_layer, "speed");
  pnh.param("field_stride", p.field_stride, 0);
  pnh.param("field_rate", p.field_rate, 2.0);
  pnh.param("field_interval", p.field_interval, 0.1);
  pnh.param("max_step_rate", p.max_step_rate, 0.0);
  pnh.param("record", p.record, false);
  pnh.param<std::string>("bag", p.bag, "ehd_capsule.bag");
  pnh.param("overwrite", p.overwrite, false);
  pnh.param("advance_steps", p.advance_steps, 1);
  pnh.param("progress_period", p.progress_period, 5.0);
  // ~until_steady TOL > 0: stop (like reaching ~steps) once D_xy and theta are steady to TOL
  // over a unit of time (relative, as `ehd_sim run --until-steady`).
  pnh.param("until_steady", p.until_steady, 0.0);
  // With /use_sim_time, this node publishes /clock unless told not to: with several simulation
  // nodes, exactly one should own the clock (two clocks jump back and forth).
  pnh.param("publish_clock", p.publish_clock, true);
  // ~state_throttled: the latest state at most this often in wall time (plots, UIs: ~state runs
  // at thousands of messages per second of sim time, which rqt_plot and rospy cannot follow).
  pnh.param("throttled_rate", p.throttled_rate, 20.0);
  // A batch run (~steps or ~until_steady) ends on a simulation error with exit status 1; a live
  // run stays up for inspection (~reset starts over) unless ~exit_on_error is true.
  pnh.param("exit_on_error", p.exit_on_error, p.batch());
  // A failed bag write stops a batch run (~steps, ~until_steady: it must not wait paused for an
  // operator who is not there) and pauses a live one.
  pnh.param<std::string>("on_record_error", p.on_record_error, p.batch() ? "stop" : "pause");
  nh.param("/use_sim_time", p.use_sim_time, false);
  pnh.param<std::string>("working_directory", p.working_directory, "");
  ValidateNodeParameters(p);
  // Relative paths: against the caller's directory, never silently under ROS_HOME.
  std::error_code ec;
  const std::string cwd = std::filesystem::current_path(ec).string();
  const bool under_roslaunch = OwnRemappings().count("__log") > 0;
  const bool scene_is_path =
      p.scene.find('/') != std::string::npos ||
      (p.scene.size() > 5 && p.scene.compare(p.scene.size() - 5, 5, ".yaml") == 0);
  if (scene_is_path) {
    p.scene = ResolveNodePath("~scene", p.scene, p.working_directory, cwd, under_roslaunch);
  }
  if (p.record) p.bag = ResolveNodePath("~bag", p.bag, p.working_directory, cwd, under_roslaunch);

  XmlRpc::XmlRpcValue set;
  if (pnh.getParam("set", set)) p.overrides = SceneOverrides(set);
  // Not ~Ca_E / ~Ca: those are dynamic_reconfigure's own and stay on a running master from one
  // launch to the next.
  double start_ca_e = -1.0, start_ca = -1.0;
  pnh.param("start_Ca_E", start_ca_e, -1.0);
  pnh.param("start_Ca", start_ca, -1.0);
  for (std::string& o : StartValueOverrides(start_ca_e, start_ca)) p.overrides.push_back(o);

  // Write the effective settings back so `rosparam get` shows what runs (turtlesim does too).
  pnh.setParam("scene", p.scene);
  pnh.setParam("publish_every", p.publish_every);
  pnh.setParam("frame_id", p.frame_id);
  if (p.record) pnh.setParam("bag", p.bag);
  return p;
}

}  // namespace ehd::ros_node
