// rosbag2's sqlite3 storage: written and read back; files that are not sqlite or lack a table.
#include "rgbdvo/io/rosbag2_sqlite.hpp"

#include <sqlite3.h>

#include <catch2/catch.hpp>
#include <fstream>

#include "test_support.hpp"

using namespace rgbdvo;

TEST_CASE("rosbag2 sqlite3 files read back in stored order with their topics") {
  const std::string path = test::MakeTempDir("sqlite") + "/x.db3";
  Rosbag2SqliteWriter writer(path);
  const int64_t a = writer.AddTopic("/a", "sensor_msgs/msg/Image");
  const int64_t b = writer.AddTopic("/b", "sensor_msgs/msg/CameraInfo");
  for (int i = 0; i < 10; ++i)
    writer.Write(i % 3 ? a : b, 1000 - i, std::vector<uint8_t>(5 + i, uint8_t(i)));
  writer.Close();

  Rosbag2SqliteReader reader(path);
  REQUIRE(reader.topics().size() == 2);
  CHECK(reader.topics()[0].name == "/a");
  CHECK(reader.topics()[1].type == "sensor_msgs/msg/CameraInfo");
  CHECK(reader.topics()[1].serialization_format == "cdr");
  Rosbag2SqliteRow row;
  int n = 0;
  while (reader.Next(&row)) {
    CHECK(row.topic_id == (n % 3 ? a : b));
    CHECK(row.timestamp_ns == 1000 - n);
    CHECK(row.data == std::vector<uint8_t>(5 + n, uint8_t(n)));
    ++n;
  }
  CHECK(n == 10);
}

TEST_CASE("rosbag2 sqlite3 reader refuses a file that is not sqlite or lacks the tables") {
  const std::string dir = test::MakeTempDir("sqlite_bad");
  std::ofstream(dir + "/text.db3") << "this is no database, only text long enough to look\n";
  CHECK_THROWS_WITH(Rosbag2SqliteReader(dir + "/text.db3"),
                    Catch::Contains("text.db3") && Catch::Contains("not a rosbag2 sqlite3 file"));
  // An sqlite3 database with the topics table only.
  sqlite3* db = nullptr;
  REQUIRE(sqlite3_open(std::string(dir + "/topics_only.db3").c_str(), &db) == SQLITE_OK);
  REQUIRE(sqlite3_exec(db,
                       "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT, "
                       "serialization_format TEXT)",
                       nullptr, nullptr, nullptr) == SQLITE_OK);
  sqlite3_close(db);
  CHECK_THROWS_WITH(Rosbag2SqliteReader(dir + "/topics_only.db3"),
                    Catch::Contains("topics_only.db3") && Catch::Contains("messages"));
  CHECK_THROWS_WITH(Rosbag2SqliteReader(dir + "/missing.db3"), Catch::Contains("missing.db3"));
}
