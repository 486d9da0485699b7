#include "ehd_capsule/ros/bag_recorder.h"

#include <ros/console.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace ehd::ros_node {

BagRecorder::BagRecorder(std::string bag_path, bool overwrite, std::string caller_id,
                         std::function<std::string(const std::string&)> resolve_name)
    : base_path_(bag_path),
      path_(std::move(bag_path)),
      overwrite_(overwrite),
      caller_id_(std::move(caller_id)),
      resolve_name_(std::move(resolve_name)) {}

BagRecorder::~BagRecorder() {
  try {
    Close();
  } catch (const std::exception& e) {
    ROS_ERROR("ehd_capsule: closing the bag %s failed: %s", active_path().c_str(), e.what());
  }
}

void BagRecorder::Open() {
  // An existing bag is not overwritten unless asked to (a new run used to replace the previous
  // one silently).
  if (!overwrite_ && (std::ifstream(path_).good() || std::ifstream(active_path()).good())) {
    throw std::invalid_argument("~bag " + path_ +
                                " exists: choose another path or set ~overwrite true "
                                "(launch argument overwrite:=true)");
  }
  auto bag = std::make_unique<rosbag::Bag>();
  bag->open(active_path(), rosbag::bagmode::Write);
  bag_ = std::move(bag);
  states_ = 0;
  failure_.clear();
  ROS_INFO("ehd_capsule: recording to %s (as %s until closed)", path_.c_str(),
           active_path().c_str());
}

void BagRecorder::Close() {
  if (!bag_) return;
  bag_->close();
  bag_.reset();
  if (std::rename(active_path().c_str(), path_.c_str()) != 0) {
    ROS_ERROR("ehd_capsule: bag closed, but renaming %s to %s failed: %s", active_path().c_str(),
              path_.c_str(), std::strerror(errno));
    return;
  }
  ROS_INFO("ehd_capsule: bag %s closed with %ld states", path_.c_str(), states_);
}

void BagRecorder::OpenNext() {
  Close();
  ++serial_;
  std::string stem = base_path_;
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".bag") == 0)
    stem.resize(stem.size() - 4);
  path_ = stem + "." + std::to_string(serial_) + ".bag";
  Open();
}

std::string OsReason(int error, const std::string& path) {
  std::string reason;
  if (error != 0) reason = std::strerror(error);
  struct rlimit limit {};
  struct stat st {};
  const bool size_known = ::stat(path.c_str(), &st) == 0;
  if (error == EFBIG ||
      (error == 0 && size_known && getrlimit(RLIMIT_FSIZE, &limit) == 0 &&
       limit.rlim_cur != RLIM_INFINITY && static_cast<rlim_t>(st.st_size) >= limit.rlim_cur)) {
    if (reason.empty()) reason = std::strerror(EFBIG);
    if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
      reason += " (the file size limit, ulimit -f: " +
                std::to_string(static_cast<unsigned long long>(limit.rlim_cur)) + " bytes)";
    }
    return reason;
  }
  struct statvfs fs {};
  const std::string dir = path.substr(0, path.find_last_of('/') + 1);
  if (statvfs(dir.empty() ? "." : dir.c_str(), &fs) == 0 && fs.f_bavail == 0) {
    if (error == 0 || error == ENOSPC) reason = std::strerror(ENOSPC);
    reason += " (" + std::to_string(static_cast<unsigned long long>(fs.f_blocks) * fs.f_frsize) +
              "-byte filesystem full)";
  }
  return reason;
}

void BagRecorder::Fail(const std::exception& e, int error) {
  // Disk full, file size limit, I/O error: stop recording and tell the node, which says why in
  // an ERROR diagnostic and pauses or stops the simulation. rosbag cannot close a bag whose
  // index it cannot write (close() throws, and so would the destructor, at exit: status 134), so
  // the failed bag is left as it is, .active, to `rosbag reindex`, and its handle to the end of
  // the process.
  const std::string reason = OsReason(error, active_path());
  failure_ = std::string("writing the bag ") + active_path() +
             " failed: " + (reason.empty() ? "" : reason + "; rosbag: ") + e.what();
  abandoned_.push_back(bag_.release());
  if (on_error_) on_error_(failure_);
}

}  // namespace ehd::ros_node
