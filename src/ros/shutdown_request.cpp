#include "ehd_capsule/ros/shutdown_request.h"

#include <ros/ros.h>
#include <ros/xmlrpc_manager.h>

#include <atomic>
#include <csignal>
#include <mutex>

namespace ehd::ros_node {

namespace {

volatile std::sig_atomic_t g_signal = 0;  // the first signal received
std::atomic<bool> g_shutdown_call{false};
std::atomic<bool> g_loop_running{false};
std::mutex g_reason_mutex;
std::string g_reason;  // of the shutdown call

extern "C" void OnSignal(int signal) {
  if (g_signal == 0) g_signal = signal;
  std::signal(signal, SIG_DFL);                 // a second one ends the process
  if (!g_loop_running) ros::requestShutdown();  // roscpp's own handler does just this
}

void OnShutdownCall(XmlRpc::XmlRpcValue& params, XmlRpc::XmlRpcValue& result) {
  std::string reason = "no reason given";
  if (params.getType() == XmlRpc::XmlRpcValue::TypeArray && params.size() > 1 &&
      params[1].getType() == XmlRpc::XmlRpcValue::TypeString) {
    reason = static_cast<std::string>(params[1]);
  }
  {
    std::lock_guard<std::mutex> lock(g_reason_mutex);
    if (g_reason.empty()) g_reason = reason;
  }
  g_shutdown_call = true;
  if (!g_loop_running) ros::requestShutdown();
  result = ros::xmlrpc::responseInt(1, "", 0);
}

}  // namespace

void InstallSignalHandlers() {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
}

void InstallShutdownCallback() {
  ros::XMLRPCManager::instance()->unbind("shutdown");
  ros::XMLRPCManager::instance()->bind("shutdown", OnShutdownCall);
}

void HandleShutdownInTheLoop() { g_loop_running = true; }

bool ShutdownRequested() { return g_signal != 0 || g_shutdown_call; }

std::string ShutdownReason() {
  if (g_signal == SIGINT) return "SIGINT";
  if (g_signal == SIGTERM) return "SIGTERM";
  if (g_shutdown_call) {
    std::lock_guard<std::mutex> lock(g_reason_mutex);
    return "shutdown request: " + g_reason;
  }
  return "";
}

}  // namespace ehd::ros_node
