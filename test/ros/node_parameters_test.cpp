// The node's parameters without a ROS master: the checks of ValidateNodeParameters (each names
// the parameter) and the scene overrides made of ~set, ~start_Ca_E and ~start_Ca.
#include "ehd_capsule/ros/node_parameters.h"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace ehd::ros_node {
namespace {

// The message of the std::invalid_argument that Validate throws for p ("" when it accepts p).
std::string Refusal(const NodeParameters& p) {
  try {
    ValidateNodeParameters(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(NodeParameters, DefaultsAreValid) {
  const NodeParameters p;
  EXPECT_EQ(Refusal(p), "");
  EXPECT_EQ(p.scene, "shear_field");
  EXPECT_EQ(p.bag, "ehd_capsule.bag");
  EXPECT_FALSE(p.batch());
  EXPECT_EQ(p.record_error_action(), RecordErrorAction::kPause);
}

TEST(NodeParameters, EachInvalidValueIsRefusedNamingTheParameter) {
  const std::pair<std::function<void(NodeParameters&)>, std::string> cases[] = {
      {[](NodeParameters& p) { p.steps = -1; }, "~steps"},
      {[](NodeParameters& p) { p.publish_every = 0; }, "~publish_every"},
      {[](NodeParameters& p) { p.markers_every = -2; }, "~markers_every"},
      {[](NodeParameters& p) { p.velocity_stride = 0; }, "~velocity_stride"},
      {[](NodeParameters& p) { p.surface_colour = "bogus"; }, "surface_colour"},
      {[](NodeParameters& p) { p.world_frame = "ehd"; }, "~world_frame"},
      {[](NodeParameters& p) { p.world_frame = ""; }, "~world_frame"},
      {[](NodeParameters& p) { p.field_stride = -1; }, "~field_stride"},
      {[](NodeParameters& p) { p.field_interval = 0; }, "~field_interval"},
      {[](NodeParameters& p) { p.field_rate = -1; }, "~field_rate"},
      {[](NodeParameters& p) { p.on_record_error = "ignore"; }, "~on_record_error"},
      {[](NodeParameters& p) { p.until_steady = -1e-3; }, "~until_steady"},
      {[](NodeParameters& p) { p.throttled_rate = 0; }, "~throttled_rate"},
  };
  for (const auto& [change, name] : cases) {
    NodeParameters p;
    change(p);
    const std::string refusal = Refusal(p);
    EXPECT_NE(refusal.find(name), std::string::npos) << name << ": '" << refusal << "'";
  }
}

TEST(NodeParameters, RecordErrorAction) {
  NodeParameters p;
  p.on_record_error = "stop";
  EXPECT_EQ(p.record_error_action(), RecordErrorAction::kStop);
  p.on_record_error = "pause";
  EXPECT_EQ(p.record_error_action(), RecordErrorAction::kPause);
}

TEST(NodeParameters, SceneOverridesFromANestedDictionary) {
  XmlRpc::XmlRpcValue set;
  set["Ca"] = 0.1;  // the shortest text that reads back the same double
  set["N"] = 64;
  set["flag"] = true;
  set["name"] = std::string("x");
  set["geometry"]["half_width"] = 3;
  const std::vector<std::string> o = SceneOverrides(set);
  // XmlRpc keeps a struct's keys sorted.
  const std::vector<std::string> expected = {"Ca=0.1", "N=64", "flag=true", "geometry.half_width=3",
                                             "name=x"};
  EXPECT_EQ(o, expected);
}

TEST(NodeParameters, SceneOverridesRefuseWhatIsNotADictionary) {
  XmlRpc::XmlRpcValue number(3.5);
  EXPECT_THROW(SceneOverrides(number), std::invalid_argument);
  XmlRpc::XmlRpcValue set;
  set["list"][0] = 1;  // an array
  try {
    SceneOverrides(set);
    FAIL() << "an array was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("~set/list"), std::string::npos) << e.what();
  }
}

TEST(NodeParameters, StartValuesBelowZeroKeepTheScenes) {
  EXPECT_TRUE(StartValueOverrides(-1, -1).empty());
  EXPECT_EQ(StartValueOverrides(0.3, -1), std::vector<std::string>{"Ca_E=0.3"});
  const std::vector<std::string> both = {"Ca_E=0", "Ca=0.05"};
  EXPECT_EQ(StartValueOverrides(0.0, 0.05), both);
}

TEST(NodeParameters, UnrequestedParametersAreThoseNotOnTheCommandLine) {
  const std::vector<std::string> server = {"/ehd_capsule/steps",   "/ehd_capsule/set/Ca_E",
                                           "/ehd_capsule/set/N",   "/ehd_capsule/scene",
                                           "/ehd_capsule/Ca_E",    "/ehd_capsule/paused",
                                           "/other/ehd_capsule/x", "/ehd_capsule_2/steps",
                                           "/use_sim_time",        "/ehd_capsule/progress_period"};
  // rosrun ehd_capsule ehd_capsule_node _scene:=shear_field _progress_period:=0 state:=s
  const std::map<std::string, std::string> rosrun = CommandLineRemappings(
      {"/x/ehd_capsule_node", "_scene:=shear_field", "_progress_period:=0", "state:=s", ":=y"});
  EXPECT_EQ(rosrun, (std::map<std::string, std::string>{
                        {"_scene", "shear_field"}, {"_progress_period", "0"}, {"state", "s"}}));
  EXPECT_EQ(UnrequestedParameters(server, "/ehd_capsule", rosrun),
            (std::vector<std::string>{"set/Ca_E", "set/N", "steps"}));
  EXPECT_TRUE(UnrequestedParameters({"/ehd_capsule/Ca", "/ehd_capsule/scene"}, "/ehd_capsule",
                                    {{"_scene", "x"}})
                  .empty());
  // roslaunch (it passes __log:=...) clears the namespace first: nothing to report.
  EXPECT_TRUE(
      UnrequestedParameters(server, "/ehd_capsule", {{"__name", "ehd_capsule"}, {"__log", "f"}})
          .empty());
}

TEST(NodeParameters, RelativePathsAreTakenFromTheCallersDirectory) {
  // roslaunch: against ~working_directory (the launch files pass $(optenv PWD)), not ROS_HOME.
  EXPECT_EQ(ResolveNodePath("~bag", "runs/a.bag", "/home/u/work", "/home/u/.ros", true),
            "/home/u/work/runs/a.bag");
  EXPECT_EQ(ResolveNodePath("~bag", "./a.bag", "/home/u/work/", "/home/u/.ros", true),
            "/home/u/work/a.bag");
  EXPECT_EQ(ResolveNodePath("~bag", "/data/a.bag", "/home/u/work", "/home/u/.ros", true),
            "/data/a.bag");
  // rosrun: the node runs in the caller's directory.
  EXPECT_EQ(ResolveNodePath("~bag", "../a.bag", "", "/home/u/work", false), "/home/u/a.bag");
  // roslaunch without ~working_directory: refused, naming the parameter and ROS_HOME.
  try {
    ResolveNodePath("~bag", "a.bag", "", "/home/u/.ros", true);
    FAIL() << "a relative ~bag under roslaunch without ~working_directory was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("~bag 'a.bag' is relative"), std::string::npos) << what;
    EXPECT_NE(what.find("ROS_HOME (/home/u/.ros)"), std::string::npos) << what;
  }
  EXPECT_THROW(ResolveNodePath("~bag", "a.bag", "work", "/", false), std::invalid_argument);
}

}  // namespace
}  // namespace ehd::ros_node
