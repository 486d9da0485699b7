// ehd_capsule_node: a thin roscpp layer over ehd::Simulation, composed of
//   NodeParameters (node_parameters.h)  the private parameters, read and checked;
//   BagRecorder    (bag_recorder.h)     the bag (~record), with .active naming and numbering;
//   NodePublishers (node_publishers.h)  every topic, and the same messages into the bag;
//   RunController  (run_controller.h)   the step loop, run states, services, progress lines.
// Topics and parameters are private (~state, ~shape, ~markers, ~scene), so several copies run
// side by side in their own namespaces. The bag is written on the thread that publishes, so it
// holds exactly one CapsuleState per published step; it is closed on finish, on Ctrl-C and when
// the simulation stops on an error.
#pragma once

#include <ros/ros.h>

#include <memory>

#include "ehd_capsule/coupling/simulation.h"
#include "ehd_capsule/ros/bag_recorder.h"
#include "ehd_capsule/ros/node_parameters.h"
#include "ehd_capsule/ros/node_publishers.h"
#include "ehd_capsule/ros/run_controller.h"

namespace ehd::ros_node {

class CapsuleNode {
 public:
  // Reads the private parameters, loads and builds the scene, opens the bag. Throws
  // std::exception with a clear message if a parameter or the scene is invalid (main() logs it
  // and exits non-zero).
  CapsuleNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

  // RunController::Run: 0 at the end of ~steps or on shutdown, 1 after a simulation error or a
  // recording failure.
  int Run() { return controller_->Run(); }

 private:
  ros::NodeHandle nh_, pnh_;
  NodeParameters params_;
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<BagRecorder> recorder_;  // null unless ~record
  std::unique_ptr<NodePublishers> publishers_;
  std::unique_ptr<RunController> controller_;
};

}  // namespace ehd::ros_node
