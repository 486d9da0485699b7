// The node's bag recorder without a ROS master (the rosbag C++ API needs none): .active while
// open, renamed when closed, no silent overwrite, numbered bags after a reset with the states
// counted per bag, topics recorded under their resolved names, latched connections.
#include "ehd_capsule/ros/bag_recorder.h"

#include <gtest/gtest.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
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

}  // namespace
}  // namespace ehd::ros_node
