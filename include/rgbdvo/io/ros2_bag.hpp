#pragma once
// ROS 2 bags as rosbag2 records them, read message by message without ROS: an MCAP file (the
// default storage since ROS 2 Iron), an sqlite3 file (.db3, the default of Humble), or a
// rosbag2 folder: metadata.yaml beside one or more split files, read in the order of its
// relative_file_paths list. Streamed: the memory held is the record or chunk being read
// (mcap_reader.hpp) or one sqlite row, never the whole bag.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace rgbdvo {

// One topic of a bag, for choosing the image topics and for `rgbdvo info`.
struct Ros2Topic {
  std::string name, type;     // "/camera/rgb/image_color", "sensor_msgs/msg/Image"
  std::string serialization;  // "cdr" for ROS 2's own
  uint64_t messages = 0;
  uint64_t first_ns = 0, last_ns = 0;  // record (log) times
  double RateHz() const;               // 0 with fewer than two messages
};

struct Ros2BagMessage {
  std::string topic, type, serialization;
  uint64_t log_time_ns = 0;
  std::vector<uint8_t> data;  // the serialised message
};

// True when `path` looks like a ROS 2 bag: an MCAP file by its magic or its .mcap extension, an
// sqlite3 file by its header or its .db3 extension (the reader then says what is wrong with
// it), or a folder holding metadata.yaml.
bool IsRos2Bag(const std::string& path);

// The storage files of the bag in reading order: the file itself, or those metadata.yaml's
// relative_file_paths lists, beside it. Throws std::runtime_error naming metadata.yaml when it
// has no such list or names a file that is neither .mcap nor .db3.
std::vector<std::string> Ros2BagFiles(const std::string& path);

class Ros2BagReader {
 public:
  // Opens the bag; `topics`, when given, are the only ones whose messages Next returns. Throws
  // std::runtime_error naming the file when it is not a readable bag.
  explicit Ros2BagReader(const std::string& path, std::vector<std::string> topics = {});
  ~Ros2BagReader();
  Ros2BagReader(const Ros2BagReader&) = delete;
  Ros2BagReader& operator=(const Ros2BagReader&) = delete;

  // The next message in the order the files hold them; nullopt at the end. Throws
  // std::runtime_error naming the file and the record when the bag turns out corrupt or cut.
  std::optional<Ros2BagMessage> Next();
  // The topics defined so far (with no counts).
  std::vector<Ros2Topic> KnownTopics() const;

 private:
  class Storage;
  class McapStorage;
  class SqliteStorage;
  static std::unique_ptr<Storage> Open(const std::string& file);
  std::vector<std::string> files_;
  size_t next_file_ = 0;
  std::unique_ptr<Storage> storage_;  // of the file being read
  std::vector<std::string> topics_;
  std::vector<Ros2Topic> known_;  // of the files already read
};

// Every topic of the bag with its counts and times, read in one pass over the messages; `each`,
// when given, sees every message on the way. A bag found corrupt or cut part way throws, or,
// with `error` given, ends the pass there with the reason in *error and the topics counted so
// far (opening it still throws).
std::vector<Ros2Topic> ListRos2Topics(const std::string& path,
                                      const std::function<void(const Ros2BagMessage&)>& each = {},
                                      std::string* error = nullptr);

}  // namespace rgbdvo
