#include "ehd_capsule/ros/bag_recorder.h"

#include <ros/console.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
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

bool BagRecorder::Taken(const std::string& path) const {
  return std::ifstream(path).good() || std::ifstream(path + ".active").good();
}

namespace {
constexpr uint32_t kChunkBytes = 768 * 1024;  // rosbag's default
}  // namespace

std::unique_ptr<rosbag::Bag> BagRecorder::OpenFile(const std::string& path) const {
  auto bag = std::make_unique<rosbag::Bag>();
  bag->open(path + ".active", rosbag::bagmode::Write);
  bag->setChunkThreshold(0);  // each message of the start its own chunk (StartWritten)
  return bag;
}

void BagRecorder::StartWritten() {
  if (bag_) bag_->setChunkThreshold(kChunkBytes);
}

void BagRecorder::StartCounts() {
  states_ = 0;
  failure_.clear();
  bytes_ = 0.0;
  rate_states0_ = -1;
  rate_reported_ = false;
  state_start_bytes_ = 0.0;
  first_state_reported_ = false;
}

void BagRecorder::Open() {
  // An existing bag is not overwritten unless asked to (a new run used to replace the previous
  // one silently).
  if (!overwrite_ && Taken(path_)) {
    throw std::invalid_argument("~bag " + path_ +
                                " exists: choose another path or set ~overwrite true "
                                "(launch argument overwrite:=true)");
  }
  bag_ = OpenFile(path_);
  StartCounts();
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

namespace {

std::string NumberedPath(const std::string& base, int serial) {
  std::string stem = base;
  if (stem.size() > 4 && stem.compare(stem.size() - 4, 4, ".bag") == 0)
    stem.resize(stem.size() - 4);
  return stem + "." + std::to_string(serial) + ".bag";
}

}  // namespace

int BagRecorder::NextSerial() const {
  int serial = serial_ + 1;
  // An earlier run's <stem>.1.bag made the reset fail and the run go on unrecorded: take the
  // next free number instead (with ~overwrite the series is overwritten, as the bag itself).
  while (!overwrite_ && Taken(NumberedPath(base_path_, serial))) ++serial;
  return serial;
}

std::string BagRecorder::NextPath() const { return NumberedPath(base_path_, NextSerial()); }

void BagRecorder::OpenNext() {
  const int serial = NextSerial();
  const std::string next = NumberedPath(base_path_, serial);
  // Opened before the current bag is closed: if it cannot be (a removed directory, no space for
  // its header), the recording goes on in the bag it was in.
  std::unique_ptr<rosbag::Bag> bag = OpenFile(next);
  Close();
  serial_ = serial;
  path_ = next;
  bag_ = std::move(bag);
  StartCounts();
  ROS_INFO("ehd_capsule: recording to %s (as %s until closed)", path_.c_str(),
           active_path().c_str());
}

double BagRecorder::FreeBytes(std::string& directory) const {
  const std::string::size_type slash = path_.find_last_of('/');
  directory = slash == std::string::npos ? "." : path_.substr(0, std::max<size_t>(slash, 1));
  struct statvfs fs {};
  if (statvfs(directory.c_str(), &fs) != 0) return -1.0;
  return static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
}

std::optional<RecordingRate> BagRecorder::FirstState() {
  if (first_state_reported_ || !bag_ || states_ < 1) return std::nullopt;
  first_state_reported_ = true;
  RecordingRate rate;
  rate.states = 1;
  rate.bytes_per_state = bytes_ - state_start_bytes_;
  rate.free_bytes = FreeBytes(rate.directory);
  return rate;
}

std::optional<RecordingRate> BagRecorder::SampleRate(double wall_seconds) {
  if (rate_reported_ || !bag_ || states_ < 1) return std::nullopt;
  if (rate_states0_ < 0) {
    rate_states0_ = states_;
    rate_bytes0_ = bytes_;
    rate_time0_ = wall_seconds;
    return std::nullopt;
  }
  const double seconds = wall_seconds - rate_time0_;
  if (seconds < 1.0 || states_ <= rate_states0_) return std::nullopt;
  rate_reported_ = true;
  RecordingRate rate;
  rate.states = states_ - rate_states0_;
  rate.seconds = seconds;
  rate.bytes_per_state = (bytes_ - rate_bytes0_) / rate.states;
  rate.bytes_per_second = (bytes_ - rate_bytes0_) / seconds;
  rate.free_bytes = FreeBytes(rate.directory);
  return rate;
}

std::string ByteSize(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 999.5 && u < 5) {
    bytes /= 1000.0;
    ++u;
  }
  char text[32];
  std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
  return text;
}

namespace {

std::string Duration(double seconds) {
  char text[32];
  if (seconds < 90.0) {
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  } else if (seconds < 5400.0) {
    std::snprintf(text, sizeof text, "%.0f min", seconds / 60.0);
  } else {
    std::snprintf(text, sizeof text, "%.2g h", seconds / 3600.0);
  }
  return text;
}

}  // namespace

RecordingReport DescribeRecordingRate(const RecordingRate& rate, long states_left) {
  RecordingReport report;
  char text[400];
  std::snprintf(text, sizeof text,
                "recording: %s per state, %s/s (measured over the first %ld states, %.1f s)",
                ByteSize(rate.bytes_per_state).c_str(), ByteSize(rate.bytes_per_second).c_str(),
                rate.states, rate.seconds);
  report.info = text;
  if (rate.free_bytes < 0.0) {
    report.info += "; free space on " + rate.directory + " unknown";
    return report;
  }
  report.info += "; " + ByteSize(rate.free_bytes) + " free on " + rate.directory;
  const std::string advice = "publish_every:=N or max_step_rate:=R record less";
  const double fill_seconds =
      rate.bytes_per_second > 0.0 ? rate.free_bytes / rate.bytes_per_second : 1e300;
  if (states_left >= 0) {
    const double needed = rate.bytes_per_state * static_cast<double>(states_left);
    if (needed > rate.free_bytes) {
      std::snprintf(text, sizeof text,
                    "the bag will fill the disk before the run ends: the %ld states left need "
                    "about %s, %s free on %s (full in about %s at this rate); %s",
                    states_left, ByteSize(needed).c_str(), ByteSize(rate.free_bytes).c_str(),
                    rate.directory.c_str(), Duration(fill_seconds).c_str(), advice.c_str());
      report.warning = text;
    }
  } else if (fill_seconds < 3600.0) {
    std::snprintf(text, sizeof text, "at %s/s the bag fills the %s free on %s in about %s; %s",
                  ByteSize(rate.bytes_per_second).c_str(), ByteSize(rate.free_bytes).c_str(),
                  rate.directory.c_str(), Duration(fill_seconds).c_str(), advice.c_str());
    report.warning = text;
  }
  return report;
}

std::string FirstStateWarning(const RecordingRate& first, long states_left) {
  if (first.free_bytes < 0.0 || first.bytes_per_state <= 0.0) return "";
  const std::string advice = "publish_every:=N or max_step_rate:=R record less";
  char text[400];
  if (states_left >= 0) {
    const double needed = first.bytes_per_state * static_cast<double>(states_left);
    if (needed <= first.free_bytes) return "";
    std::snprintf(text, sizeof text,
                  "the bag will fill the disk before the run ends: the %ld states left need "
                  "about %s, %s free on %s (estimated from the first state, %s); %s",
                  states_left, ByteSize(needed).c_str(), ByteSize(first.free_bytes).c_str(),
                  first.directory.c_str(), ByteSize(first.bytes_per_state).c_str(), advice.c_str());
    return text;
  }
  const double fit = first.free_bytes / first.bytes_per_state;
  if (fit >= static_cast<double>(kFewStates)) return "";
  std::snprintf(text, sizeof text,
                "the %s free on %s hold only about %.0f states of the first state's size (%s); "
                "%s",
                ByteSize(first.free_bytes).c_str(), first.directory.c_str(), fit,
                ByteSize(first.bytes_per_state).c_str(), advice.c_str());
  return text;
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
