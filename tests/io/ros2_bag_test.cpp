// ROS 2 bags over their storages: detection, a folder's files in metadata.yaml's order, topics
// and messages across split files of either storage.
#include "rgbdvo/io/ros2_bag.hpp"

#include <catch2/catch.hpp>
#include <fstream>

#include "rgbdvo/io/mcap_writer.hpp"
#include "rgbdvo/io/rosbag2_sqlite.hpp"
#include "test_support.hpp"

using namespace rgbdvo;

TEST_CASE("ROS 2 bag files and folders detected, a folder read in metadata.yaml's order") {
  const std::string dir = test::MakeTempDir("ros2_bag_files");
  {
    McapWriter mcap(dir + "/b_10.mcap");
    const uint16_t a = mcap.AddChannel("/a", "sensor_msgs/msg/Image");
    mcap.Write(a, 5, {1});
    mcap.Close();
    Rosbag2SqliteWriter db(dir + "/b_2.db3");
    const int64_t b = db.AddTopic("/b", "sensor_msgs/msg/Imu");
    db.Write(b, 7, {2});
    db.Write(b, 9, {3});
    db.AddTopic("/quiet", "sensor_msgs/msg/CameraInfo");
    db.Close();
  }
  std::ofstream(dir + "/metadata.yaml")
      << "rosbag2_bagfile_information:\n  relative_file_paths:\n    - b_2.db3\n    - b_10.mcap\n"
         "  starting_time:\n    nanoseconds_since_epoch: 5\n";
  std::ofstream(dir + "/notes.txt") << "no bag\n";
  CHECK(IsRos2Bag(dir));
  CHECK(IsRos2Bag(dir + "/b_10.mcap"));
  CHECK(IsRos2Bag(dir + "/b_2.db3"));
  CHECK_FALSE(IsRos2Bag(dir + "/notes.txt"));
  CHECK(Ros2BagFiles(dir) == std::vector<std::string>{dir + "/b_2.db3", dir + "/b_10.mcap"});

  Ros2BagReader reader(dir, {"/a", "/b"});
  std::vector<uint8_t> order;
  while (std::optional<Ros2BagMessage> m = reader.Next()) order.push_back(m->data.at(0));
  CHECK(order == std::vector<uint8_t>{2, 3, 1});

  const std::vector<Ros2Topic> topics = ListRos2Topics(dir);
  REQUIRE(topics.size() == 3);
  CHECK(topics[0].name == "/a");
  CHECK(topics[0].type == "sensor_msgs/msg/Image");
  CHECK(topics[0].serialization == "cdr");
  CHECK(topics[1].messages == 2);
  CHECK(topics[1].RateHz() == Approx(0.5e9));
  CHECK(topics[2].name == "/quiet");
  CHECK(topics[2].messages == 0);
}
