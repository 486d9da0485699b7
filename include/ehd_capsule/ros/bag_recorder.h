// The node's bag (rosbag C++ API, no ROS master needed: tested alone in
// test/ros_unit/bag_recorder_test.cpp).
//
// Written as <bag>.active and renamed to <bag> when closed, as `rosbag record` does: a bag left
// by a killed process (kill -9, power loss) keeps the .active name and is repaired with
// `rosbag reindex`. An existing bag is not overwritten unless asked to. A reset starts a new
// timeline in a numbered bag (<stem>.1.bag, .2.bag, ...). A write that fails (disk full, file
// size limit, I/O error) stops the recording: failure() says why, and the error callback runs.
#pragma once

#include <ros/message_traits.h>
#include <rosbag/bag.h>

#include <boost/make_shared.hpp>
#include <cerrno>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ehd::ros_node {

// The OS's reason for a failed write of the file at path: strerror(error), with what it means
// for a bag (the file size limit of ulimit -f, a full filesystem). error may be 0 (the C
// library's buffer failed earlier): then it is found from the limit and the free space; empty
// when nothing is known.
std::string OsReason(int error, const std::string& path);

// What a recording costs, measured on the bag being written (BagRecorder::SampleRate).
struct RecordingRate {
  double bytes_per_state = 0.0;   // all that is written per state: shape, markers, clock, ...
  double bytes_per_second = 0.0;  // of wall time
  double seconds = 0.0;           // the wall time measured over
  long states = 0;                // the states measured over
  double free_bytes = -1.0;       // free to this user on the bag's filesystem; < 0: unknown
  std::string directory;          // the bag's
};

struct RecordingReport {
  std::string info;     // "recording: 16.2 kB per state, 98.4 MB/s (...); 78.3 GB free on /tmp"
  std::string warning;  // empty, or that the disk fills within the run or within an hour
};
// states_left: the states still to be recorded (a run with ~steps), < 0 when the end is not
// known (a live run, ~until_steady): then the warning is for a disk full within an hour.
RecordingReport DescribeRecordingRate(const RecordingRate& rate, long states_left);
// The same warning from the first state's size alone (BagRecorder::FirstState, before a rate is
// measured: a disk can fill within the first second): the states left do not fit, or, when the
// end is not known, the free space holds fewer than kFewStates states. Empty when they fit.
constexpr long kFewStates = 10000;
std::string FirstStateWarning(const RecordingRate& first, long states_left);
// 16200 -> "16.2 kB", 1.18e9 -> "1.18 GB" (SI units, as df -H and ls --si).
std::string ByteSize(double bytes);

class BagRecorder {
 public:
  // resolve_name: the name a relative topic is recorded under (the node's resolved private
  // names, so a replay republishes them there); caller_id: the connection headers' callerid.
  BagRecorder(std::string bag_path, bool overwrite, std::string caller_id,
              std::function<std::string(const std::string&)> resolve_name);
  ~BagRecorder();  // Close(); never throws
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  // Opens path() as active_path(). Throws std::invalid_argument when the bag (or its .active)
  // exists and overwrite is false, rosbag::BagException when it cannot be opened.
  void Open();
  // Closes the bag and renames it to path(); logs the path and the states in it. A no-op when
  // no bag is open.
  void Close();
  // For a reset: opens the next bag of the series, <stem>.<n>.bag with n the first number above
  // the last whose bag (and .active) does not exist (any number with ~overwrite; the stem is the
  // bag as given, less ".bag"), then closes the one being written. Throws as Open(), with the
  // bag being written (if any) still open and recording.
  void OpenNext();
  // The path OpenNext would open.
  std::string NextPath() const;

  // A new bag's start (its header messages, first diagnostic and step-0 state) goes into chunks
  // of their own: `rosbag reindex` recovers only terminated chunks, and a recording that failed
  // within its first 768 kB chunk was recovered empty. StartWritten() goes back to rosbag's
  // chunk size for the rest.
  void StartWritten();

  bool is_open() const { return bag_ != nullptr; }
  const std::string& path() const { return path_; }  // the bag being (or last) recorded
  std::string active_path() const { return path_ + ".active"; }
  int serial() const { return serial_; }  // 0 for the bag as given, n for <stem>.<n>.bag
  // The states (CapsuleState) written into the bag now open (or last closed).
  long states() const { return states_; }
  // Around each state: BeginState before its first message (the clock), CountState after the
  // CapsuleState is written.
  void BeginState() { state_start_bytes_ = bytes_; }
  void CountState() { ++states_; }
  // Once per bag, right after its first state: that state's bytes (all its messages since
  // BeginState: clock, state, shape, markers, ...) as bytes_per_state, and the free space;
  // bytes_per_second 0 (not measured). nullopt before and after.
  std::optional<RecordingRate> FirstState();
  // The recording's cost, once per bag: from the first state counted to the first one at least
  // 1 s of wall time (wall_seconds, any epoch) later. Bytes are the messages' serialized sizes
  // plus rosbag's per-message record and index (within a few % of the file: rosbag writes in
  // 768 kB chunks, so the file's size is known only chunk by chunk). nullopt before and after.
  std::optional<RecordingRate> SampleRate(double wall_seconds);
  double bytes_written() const { return bytes_; }  // into the bag now open, estimated as above

  // Why the recording stopped (empty: it did not), with the OS's reason ("File too large (the
  // file size limit, ...)", "No space left on device"); cleared by Open / OpenNext.
  const std::string& failure() const { return failure_; }
  // Called once per failure, after the recording stopped, with failure().
  void set_on_error(std::function<void(const std::string&)> on_error) {
    on_error_ = std::move(on_error);
  }

  // Writes msg under topic (relative topics resolved) at stamp (a zero stamp, which rosbag
  // refuses, as 1 ns). Returns false when no bag is open or the write failed.
  template <typename M>
  bool Write(const std::string& topic, const M& msg, const ros::Time& stamp);
  // The same as a latched connection (`rosbag play` latches it again).
  template <typename M>
  bool WriteLatched(const std::string& topic, const M& msg, const ros::Time& stamp);

 private:
  void Fail(const std::exception& e, int error);  // error: errno right after the failure
  // Opens path + ".active" (throws rosbag::BagException) and resets the per-bag counts.
  std::unique_ptr<rosbag::Bag> OpenFile(const std::string& path) const;
  void StartCounts();
  bool Taken(const std::string& path) const;  // the bag or its .active exists
  int NextSerial() const;
  double FreeBytes(std::string& directory) const;
  std::string Resolve(const std::string& topic) const {
    return topic.empty() || topic.front() == '/' ? topic : resolve_name_(topic);
  }
  static ros::Time NonZero(const ros::Time& t) { return t.isZero() ? ros::Time(1e-9) : t; }

  std::string base_path_;  // the bag as given
  std::string path_;
  bool overwrite_;
  std::string caller_id_;
  std::function<std::string(const std::string&)> resolve_name_;
  std::function<void(const std::string&)> on_error_;
  std::unique_ptr<rosbag::Bag> bag_;
  std::vector<rosbag::Bag*> abandoned_;  // bags whose write failed: never closed (see Fail)
  int serial_ = 0;
  long states_ = 0;
  std::string failure_;
  double bytes_ = 0.0;
  // SampleRate's window: its start (the first state) and whether it was reported.
  long rate_states0_ = -1;
  double rate_bytes0_ = 0.0, rate_time0_ = 0.0;
  bool rate_reported_ = false;
  double state_start_bytes_ = 0.0;
  bool first_state_reported_ = false;
  // rosbag's bytes per message besides the message: the record's header (op, conn, time) and
  // length fields, and the chunk's index entry written at close.
  static constexpr double kRecordOverhead = 57.0;
};

template <typename M>
bool BagRecorder::Write(const std::string& topic, const M& msg, const ros::Time& stamp) {
  if (!bag_) return false;
  errno = 0;
  bytes_ += ros::serialization::serializationLength(msg) + kRecordOverhead;
  try {
    bag_->write(Resolve(topic), NonZero(stamp), msg);
  } catch (const std::exception& e) {
    Fail(e, errno);
    return false;
  }
  return true;
}

template <typename M>
bool BagRecorder::WriteLatched(const std::string& topic, const M& msg, const ros::Time& stamp) {
  if (!bag_) return false;
  const std::string name = Resolve(topic);
  auto header = boost::make_shared<ros::M_string>();
  (*header)["callerid"] = caller_id_;
  (*header)["latching"] = "1";
  (*header)["topic"] = name;
  (*header)["md5sum"] = ros::message_traits::MD5Sum<M>::value();
  (*header)["type"] = ros::message_traits::DataType<M>::value();
  (*header)["message_definition"] = ros::message_traits::Definition<M>::value();
  errno = 0;
  bytes_ += ros::serialization::serializationLength(msg) + kRecordOverhead;
  try {
    bag_->write(name, NonZero(stamp), msg, header);
  } catch (const std::exception& e) {
    Fail(e, errno);
    return false;
  }
  return true;
}

}  // namespace ehd::ros_node
