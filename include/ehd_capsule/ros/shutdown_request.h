// A clean end on every outside request: SIGINT (Ctrl-C, roslaunch), SIGTERM (kill, timeout,
// systemd, docker, roslaunch's escalation) and the master's shutdown call (`rosnode kill`, a
// node of the same name) only set a flag; the run loop sees it between two steps and ends as at
// the end of ~steps: summary, final diagnostic, bag closed. roscpp's own handlers would shut
// ROS (and rosconsole) down first, so that nothing of the end reached the console.
#pragma once

#include <string>

namespace ehd::ros_node {

// SIGINT and SIGTERM handlers: call before ros::init (with ros::init_options::NoSigintHandler).
// A second signal of the same kind ends the process at once (the default action).
void InstallSignalHandlers();
// Replaces roscpp's "shutdown" XML-RPC call: after the first NodeHandle (ros::start binds it).
void InstallShutdownCallback();
// Until this is called (when the run loop starts) a request shuts ROS down at once, as roscpp
// does (so that Ctrl-C ends a node still waiting for its master); after it, the loop ends.
void HandleShutdownInTheLoop();
// Whether an end was requested, and why ("SIGINT", "SIGTERM", "shutdown request: <reason>").
bool ShutdownRequested();
std::string ShutdownReason();

}  // namespace ehd::ros_node
