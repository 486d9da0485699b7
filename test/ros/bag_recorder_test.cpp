// The node's bag recorder without a ROS master (the rosbag C++ API needs none): .active while
// open, renamed when closed, no silent overwrite, numbered bags after a reset with the states
// counted per bag, topics recorded under their resolved names, latched connections.
#include "ehd_capsule/ros/bag_recorder.h"

#include <gtest/gtest.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

namespace ehd::ros_node {
namespace {

namespace fs = std::filesystem;

class BagRecorderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir[] = "/tmp/ehd_bag_recorder_test.XXXXXX";
    ASSERT_NE(mkdtemp(dir), nullptr);
    dir_ = dir;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  static BagRecorder Make(const std::string& path, bool overwrite = false) {
    return BagRecorder(path, overwrite, "/ehd_test",
                       [](const std::string& topic) { return "/ns/" + topic; });
  }
  static std_msgs::String Text(const std::string& text) {
    std_msgs::String m;
    m.data = text;
    return m;
  }
  // Messages per topic of a closed bag.
  static std::map<std::string, int> Topics(const std::string& path) {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    rosbag::View view(bag);
    std::map<std::string, int> count;
    for (const rosbag::MessageInstance& m : view) ++count[m.getTopic()];
    return count;
  }

  fs::path dir_;
};

TEST_F(BagRecorderTest, ActiveWhileOpenRenamedWhenClosed) {
  const std::string path = Path("run.bag");
  BagRecorder rec = Make(path);
  EXPECT_FALSE(rec.is_open());
  rec.Open();
  EXPECT_TRUE(rec.is_open());
  EXPECT_TRUE(fs::exists(path + ".active"));
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(rec.Write("state", Text("a"), ros::Time(1.0)));
  rec.CountState();
  EXPECT_TRUE(rec.Write("state", Text("b"), ros::Time(0)));  // a zero stamp is taken as 1 ns
  rec.CountState();
  EXPECT_TRUE(rec.Write("/diagnostics", Text("c"), ros::Time(2.0)));
  EXPECT_EQ(rec.states(), 2);
  rec.Close();
  EXPECT_FALSE(rec.is_open());
  EXPECT_FALSE(fs::exists(path + ".active"));
  ASSERT_TRUE(fs::exists(path));
  const auto topics = Topics(path);
  EXPECT_EQ(topics.at("/ns/state"), 2);  // relative names resolved
  EXPECT_EQ(topics.at("/diagnostics"), 1);
  EXPECT_FALSE(rec.Write("state", Text("d"), ros::Time(3.0))) << "written after Close";
  EXPECT_TRUE(rec.failure().empty());
}

TEST_F(BagRecorderTest, RefusesAnExistingBagUnlessOverwrite) {
  const std::string path = Path("old.bag");
  std::ofstream(path) << "an earlier run";
  BagRecorder rec = Make(path);
  try {
    rec.Open();
    FAIL() << "an existing bag was opened";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("exists"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_FALSE(rec.is_open());
  std::ifstream in(path);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "an earlier run");
  // A stale .active counts as existing too.
  fs::remove(path);
  std::ofstream(path + ".active") << "killed";
  EXPECT_THROW(Make(path).Open(), std::invalid_argument);
  BagRecorder again = Make(path, /*overwrite=*/true);
  again.Open();
  again.Close();
  EXPECT_EQ(Topics(path).size(), 0u);
}

TEST_F(BagRecorderTest, ResetsRecordNumberedBagsCountedPerBag) {
  const std::string path = Path("series.bag");
  BagRecorder rec = Make(path);
  rec.Open();
  for (int i = 0; i < 3; ++i) {
    rec.Write("state", Text("x"), ros::Time(1.0 + i));
    rec.CountState();
  }
  rec.OpenNext();
  EXPECT_TRUE(fs::exists(path));
  EXPECT_EQ(rec.path(), Path("series.1.bag"));
  EXPECT_EQ(rec.serial(), 1);
  EXPECT_EQ(rec.states(), 0);
  rec.Write("state", Text("y"), ros::Time(1.0));
  rec.CountState();
  EXPECT_EQ(rec.states(), 1);
  rec.OpenNext();
  EXPECT_EQ(rec.path(), Path("series.2.bag"));
  rec.Close();
  EXPECT_EQ(Topics(path).at("/ns/state"), 3);
  EXPECT_EQ(Topics(Path("series.1.bag")).at("/ns/state"), 1);
  EXPECT_TRUE(fs::exists(Path("series.2.bag")));
}

// Issue #44: an earlier run's <stem>.1.bag made ~reset fail and the run go on unrecorded. The
// next free number is taken; with ~overwrite the series is overwritten as the bag itself.
TEST_F(BagRecorderTest, ResetTakesTheNextFreeNumber) {
  const std::string path = Path("again.bag");
  std::ofstream(Path("again.1.bag")) << "an earlier run";
  std::ofstream(Path("again.2.bag.active")) << "killed";
  BagRecorder rec = Make(path);
  rec.Open();
  EXPECT_EQ(rec.NextPath(), Path("again.3.bag"));
  rec.OpenNext();
  EXPECT_EQ(rec.path(), Path("again.3.bag"));
  EXPECT_EQ(rec.serial(), 3);
  EXPECT_TRUE(rec.is_open());
  EXPECT_TRUE(rec.Write("state", Text("x"), ros::Time(1.0)));
  rec.OpenNext();
  EXPECT_EQ(rec.path(), Path("again.4.bag"));
  rec.Close();
  std::ifstream in(Path("again.1.bag"));
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "an earlier run");
  EXPECT_EQ(Topics(Path("again.3.bag")).at("/ns/state"), 1);
  BagRecorder over = Make(Path("over.bag"), /*overwrite=*/true);
  std::ofstream(Path("over.1.bag")) << "an earlier run";
  over.Open();
  EXPECT_EQ(over.NextPath(), Path("over.1.bag"));
  over.Close();
}

// A next bag that cannot be opened (its directory gone) leaves the recording where it was: the
// reset is refused, and nothing goes unrecorded.
TEST_F(BagRecorderTest, ANextBagThatCannotBeOpenedKeepsTheRecording) {
  const fs::path sub = dir_ / "sub";
  fs::create_directory(sub);
  const std::string path = (sub / "run.bag").string();
  BagRecorder rec = Make(path);
  rec.Open();
  rec.Write("state", Text("a"), ros::Time(1.0));
  rec.CountState();
  fs::rename(sub, dir_ / "moved");  // the open file moves along
  EXPECT_THROW(rec.OpenNext(), rosbag::BagException);
  EXPECT_TRUE(rec.is_open());
  EXPECT_EQ(rec.path(), path);
  EXPECT_EQ(rec.serial(), 0);
  EXPECT_EQ(rec.states(), 1);
  EXPECT_TRUE(rec.Write("state", Text("b"), ros::Time(2.0)));
  rec.CountState();
  fs::rename(dir_ / "moved", sub);
  rec.Close();
  EXPECT_EQ(Topics(path).at("/ns/state"), 2);
}

TEST_F(BagRecorderTest, LatchedConnection) {
  const std::string path = Path("latched.bag");
  BagRecorder rec = Make(path);
  rec.Open();
  rec.WriteLatched("/tf_static", Text("frame"), ros::Time(0));
  rec.Close();
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  ASSERT_EQ(view.size(), 1u);
  const rosbag::ConnectionInfo* c = view.getConnections().front();
  EXPECT_EQ(c->topic, "/tf_static");
  ASSERT_TRUE(c->header);
  EXPECT_EQ(c->header->at("latching"), "1");
  EXPECT_EQ(c->header->at("callerid"), "/ehd_test");
}

// A write over the file size limit (ulimit -f, as a full disk): the recording stops with the OS's
// reason, the error callback runs once, later writes are refused, and neither closing nor
// destroying the recorder throws (rosbag's close of such a bag does: status 134 at exit).
TEST_F(BagRecorderTest, WriteFailureStopsTheRecordingWithTheOsReason) {
  const std::string path = Path("limited.bag");
  std::signal(SIGXFSZ, SIG_IGN);  // as the node: the write fails instead of killing the process
  struct rlimit saved {};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  std::vector<std::string> errors;
  {
    BagRecorder rec = Make(path);
    rec.set_on_error([&errors](const std::string& why) { errors.push_back(why); });
    rec.Open();
    struct rlimit limit = saved;
    limit.rlim_cur = 64 * 1024;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
    const std_msgs::String big = Text(std::string(4096, 'x'));
    int written = 0;
    while (written < 1000 && rec.Write("state", big, ros::Time(1.0 + written))) ++written;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &saved), 0);
    EXPECT_LT(written, 1000) << "the file size limit was never hit";
    EXPECT_FALSE(rec.is_open());
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_EQ(errors[0], rec.failure());
    EXPECT_NE(rec.failure().find("writing the bag " + path + ".active failed"), std::string::npos)
        << rec.failure();
    EXPECT_NE(rec.failure().find(std::strerror(EFBIG)), std::string::npos) << rec.failure();
    EXPECT_NE(rec.failure().find("ulimit -f"), std::string::npos) << rec.failure();
    EXPECT_FALSE(rec.Write("state", big, ros::Time(2000.0)));
    EXPECT_EQ(errors.size(), 1u);
    EXPECT_NO_THROW(rec.Close());
  }  // destroyed without an exception
  EXPECT_TRUE(fs::exists(path + ".active")) << "the failed bag keeps its .active name";
  EXPECT_FALSE(fs::exists(path));
}

// The measured cost of a recording: bytes per state within a few % of the closed file, per
// second over the wall time given, free space of the bag's filesystem; once per bag.
TEST_F(BagRecorderTest, SampleRateMeasuresTheBagOnceFromItsFirstSecond) {
  const std::string path = Path("rate.bag");
  BagRecorder rec = Make(path);
  rec.Open();
  rec.StartWritten();  // rosbag's chunks from here (the start has chunks of its own)
  EXPECT_FALSE(rec.SampleRate(100.0));  // no state yet
  const std::string payload(10000, 'x');
  double t = 100.0;
  std::optional<RecordingRate> rate;
  for (int i = 0; i < 400 && !rate; ++i) {
    rec.Write("state", Text(payload), ros::Time(1.0 + i));
    rec.Write("shape", Text(payload.substr(0, 2000)), ros::Time(1.0 + i));
    rec.CountState();
    rate = rec.SampleRate(t);
    t += 1.0 / 256;  // 256 states per second (exact in binary)
  }
  ASSERT_TRUE(rate);
  EXPECT_EQ(rate->states, 256);
  EXPECT_NEAR(rate->seconds, 1.0, 1e-9);
  EXPECT_NEAR(rate->bytes_per_state, 12000.0, 300.0);
  EXPECT_NEAR(rate->bytes_per_second, 256 * rate->bytes_per_state, 1e-6 * rate->bytes_per_second);
  EXPECT_EQ(rate->directory, dir_.string());
  EXPECT_GT(rate->free_bytes, 0.0);
  EXPECT_FALSE(rec.SampleRate(t + 10.0));  // once
  const long states = rec.states();
  rec.Close();
  const double file_per_state = static_cast<double>(fs::file_size(path)) / states;
  EXPECT_NEAR(rate->bytes_per_state, file_per_state, 0.03 * file_per_state);
  // A new bag (a reset) is measured again.
  rec.OpenNext();
  rec.Write("state", Text(payload), ros::Time(1.0));
  rec.CountState();
  EXPECT_FALSE(rec.SampleRate(200.0));
  rec.Write("state", Text(payload), ros::Time(2.0));
  rec.CountState();
  EXPECT_TRUE(rec.SampleRate(201.5));
}

TEST(RecordingRate, ReportsTheCostAndWarnsBeforeTheDiskFills) {
  RecordingRate rate;
  rate.bytes_per_state = 16100;
  rate.bytes_per_second = 98.4e6;
  rate.seconds = 1.0;
  rate.states = 6100;
  rate.free_bytes = 78.3e9;
  rate.directory = "/tmp";
  RecordingReport r = DescribeRecordingRate(rate, 1000);  // 16 MB left: fits
  EXPECT_EQ(r.info,
            "recording: 16.1 kB per state, 98.4 MB/s (measured over the first 6100 states, 1.0 "
            "s); 78.3 GB free on /tmp");
  EXPECT_EQ(r.warning, "");
  r = DescribeRecordingRate(rate, 10000000);  // 161 GB left: does not fit
  EXPECT_NE(r.warning.find("the bag will fill the disk before the run ends: the 10000000 states "
                           "left need about 161 GB, 78.3 GB free on /tmp (full in about 13 min"),
            std::string::npos)
      << r.warning;
  r = DescribeRecordingRate(rate, -1);  // a live run: full within the hour
  EXPECT_NE(r.warning.find("at 98.4 MB/s the bag fills the 78.3 GB free on /tmp in about 13 min"),
            std::string::npos)
      << r.warning;
  rate.bytes_per_second = 1e6;  // 22 h to fill: no warning
  EXPECT_EQ(DescribeRecordingRate(rate, -1).warning, "");
  rate.free_bytes = -1;
  EXPECT_NE(DescribeRecordingRate(rate, -1).info.find("free space on /tmp unknown"),
            std::string::npos);
}

// Issue #44: a disk that fills before the first rate measurement (1 s) gave no warning. The
// first state's size (all its messages since BeginState) gives one at once.
TEST_F(BagRecorderTest, FirstStateSizeWarnsBeforeARateIsMeasured) {
  BagRecorder rec = Make(Path("first.bag"));
  rec.Open();
  rec.WriteLatched("scene", Text(std::string(5000, 's')), ros::Time(0));  // not the state's
  EXPECT_FALSE(rec.FirstState());
  rec.BeginState();
  rec.Write("state", Text(std::string(10000, 'x')), ros::Time(1.0));
  rec.CountState();
  rec.Write("markers", Text(std::string(2000, 'm')), ros::Time(1.0));
  const std::optional<RecordingRate> first = rec.FirstState();
  ASSERT_TRUE(first);
  EXPECT_NEAR(first->bytes_per_state, 12000.0, 300.0);
  EXPECT_EQ(first->directory, dir_.string());
  EXPECT_GT(first->free_bytes, 0.0);
  EXPECT_FALSE(rec.FirstState());  // once per bag
  rec.Close();

  RecordingRate r;
  r.bytes_per_state = 12000;
  r.free_bytes = 1.2e9;  // 100000 states
  r.directory = "/data";
  EXPECT_EQ(FirstStateWarning(r, 1000), "");
  EXPECT_NE(FirstStateWarning(r, 1000000)
                .find("the bag will fill the disk before the run ends: the 1000000 states left "
                      "need about 12 GB, 1.2 GB free on /data (estimated from the first state, "
                      "12 kB)"),
            std::string::npos)
      << FirstStateWarning(r, 1000000);
  EXPECT_EQ(FirstStateWarning(r, -1), "");  // a live run: room for 100000 states
  r.free_bytes = 12e6;                      // 1000 states
  EXPECT_NE(FirstStateWarning(r, -1).find("the 12 MB free on /data hold only about 1000 states"),
            std::string::npos)
      << FirstStateWarning(r, -1);
  r.free_bytes = -1;  // unknown
  EXPECT_EQ(FirstStateWarning(r, 1000000), "");
}

TEST(RecordingRate, ByteSize) {
  EXPECT_EQ(ByteSize(57), "57 B");
  EXPECT_EQ(ByteSize(16100), "16.1 kB");
  EXPECT_EQ(ByteSize(227000), "227 kB");
  EXPECT_EQ(ByteSize(1.18e9), "1.18 GB");
}

TEST(OsReason, NamesTheLimitOrTheFullDisk) {
  EXPECT_NE(OsReason(EFBIG, "/nonexistent/x.bag").find(std::strerror(EFBIG)), std::string::npos);
  EXPECT_EQ(OsReason(ENOSPC, "/tmp/x.bag").find(std::strerror(ENOSPC)), 0u);
  EXPECT_EQ(OsReason(0, "/tmp/no_such_file.bag"), "");  // nothing known
}

}  // namespace
}  // namespace ehd::ros_node
