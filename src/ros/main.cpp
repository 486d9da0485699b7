// ehd_capsule_node: owns an ehd::Simulation, steps it and publishes its state (see
// include/ehd_capsule/ros/capsule_node.h). An invalid scene or parameter is a clear FATAL log and
// exit code 1; a simulation error later stops the stepping but keeps the node up. SIGINT,
// SIGTERM and `rosnode kill` end the run cleanly (shutdown_request.h).
#include <ros/ros.h>

#include <csignal>
#include <cstdio>

#include "ehd_capsule/lbm/openmp_wait.h"
#include "ehd_capsule/ros/capsule_node.h"
#include "ehd_capsule/ros/shutdown_request.h"

int main(int argc, char** argv) {
  // rosconsole writes with fprintf: to a pipe (scripts/run's tee, a CI log, `| grep`) stdout
  // would be block-buffered and the progress lines would come all at once when the node exits.
  // One line at a time, in a terminal and through a pipe alike.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::setvbuf(stderr, nullptr, _IOLBF, 0);
  ehd::RestartWithPassiveOpenMpWait(argv);  // lbm/openmp_wait.h
  // A file size limit (ulimit -f) would kill the process on the bag write that exceeds it; with
  // SIGXFSZ ignored the write fails instead and the node handles it like a full disk.
  std::signal(SIGXFSZ, SIG_IGN);
  ehd::ros_node::InstallSignalHandlers();
  ros::init(argc, argv, "ehd_capsule", ros::init_options::NoSigintHandler);
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  ehd::ros_node::InstallShutdownCallback();
  int status = 1;
  {
    std::unique_ptr<ehd::ros_node::CapsuleNode> node;
    try {
      node = std::make_unique<ehd::ros_node::CapsuleNode>(nh, pnh);
    } catch (const std::exception& e) {
      ROS_FATAL("ehd_capsule: cannot start: %s", e.what());
      return 1;
    }
    status = node->Run();
  }
  ros::shutdown();
  return status;
}
