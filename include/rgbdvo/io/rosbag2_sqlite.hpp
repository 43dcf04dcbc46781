#pragma once
// rosbag2's sqlite3 storage (.db3 files, the default of ROS 2 Humble) through Debian's
// libsqlite3: the table `topics` (id, name, type, serialization_format) and `messages` (id,
// topic_id, timestamp, data). Messages are read in the order they were stored (by id), one
// row at a time, so the memory held is one message.

#include <cstdint>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace rgbdvo {

struct Rosbag2SqliteTopic {
  int64_t id = 0;
  std::string name, type, serialization_format;
};

struct Rosbag2SqliteRow {
  int64_t topic_id = 0;
  int64_t timestamp_ns = 0;
  std::vector<uint8_t> data;
};

class Rosbag2SqliteReader {
 public:
  // Opens the file read-only and reads its topics. Throws std::runtime_error naming the file
  // when it is not an sqlite3 database or lacks the tables.
  explicit Rosbag2SqliteReader(const std::string& path);
  ~Rosbag2SqliteReader();
  Rosbag2SqliteReader(const Rosbag2SqliteReader&) = delete;
  Rosbag2SqliteReader& operator=(const Rosbag2SqliteReader&) = delete;

  const std::vector<Rosbag2SqliteTopic>& topics() const { return topics_; }
  // The next message in stored order into *row; false at the end. Throws std::runtime_error
  // naming the file when the database turns out corrupt.
  bool Next(Rosbag2SqliteRow* row);

 private:
  [[noreturn]] void Fail(const std::string& what) const;
  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* messages_ = nullptr;
  std::vector<Rosbag2SqliteTopic> topics_;
};

class Rosbag2SqliteWriter {
 public:
  // Creates the file (replacing one there) with rosbag2's tables. Throws std::runtime_error
  // naming the file when it cannot.
  explicit Rosbag2SqliteWriter(const std::string& path);
  ~Rosbag2SqliteWriter();  // closes without committing if Close was not called
  Rosbag2SqliteWriter(const Rosbag2SqliteWriter&) = delete;
  Rosbag2SqliteWriter& operator=(const Rosbag2SqliteWriter&) = delete;

  int64_t AddTopic(const std::string& name, const std::string& type,
                   const std::string& serialization_format = "cdr");
  void Write(int64_t topic_id, int64_t timestamp_ns, const std::vector<uint8_t>& data);
  void Close();  // commits; throws std::runtime_error naming the file when it cannot

 private:
  void Exec(const std::string& sql);
  [[noreturn]] void Fail(const std::string& what) const;
  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_ = nullptr;
  int64_t next_topic_ = 1;
};

}  // namespace rgbdvo
