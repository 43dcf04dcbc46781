// The MCAP writer read back by our reader: every compression, channels and messages in order.
#include "rgbdvo/io/mcap_writer.hpp"

#include <catch2/catch.hpp>

#include "rgbdvo/io/mcap_reader.hpp"
#include "test_support.hpp"

using namespace rgbdvo;

TEST_CASE("MCAP writer's files read back record for record, every compression") {
  const std::string dir = test::MakeTempDir("mcap_writer");
  for (const std::string compression : {"", "zstd", "lz4"}) {
    const std::string path = dir + "/w" + compression + ".mcap";
    McapWriterOptions options;
    options.compression = compression;
    options.chunk_bytes = 1000;  // several chunks
    McapWriter writer(path, options);
    const uint16_t a = writer.AddChannel("/a", "sensor_msgs/msg/Image");
    const uint16_t b = writer.AddChannel("/b", "sensor_msgs/msg/CameraInfo");
    for (int i = 0; i < 20; ++i)
      writer.Write(i % 2 ? b : a, 1000 + i, std::vector<uint8_t>(100 + i, uint8_t(i)));
    writer.Close();

    McapReader reader(path);
    int n = 0;
    while (std::optional<McapMessage> m = reader.NextMessage()) {
      CHECK(m->channel_id == (n % 2 ? b : a));
      CHECK(m->log_time == uint64_t(1000 + n));
      CHECK(m->data == std::vector<uint8_t>(100 + n, uint8_t(n)));
      ++n;
    }
    CHECK(n == 20);
    CHECK(reader.Channel(b)->topic == "/b");
    CHECK(reader.Schema(reader.Channel(b)->schema_id)->name == "sensor_msgs/msg/CameraInfo");
    CHECK(reader.Channel(a)->message_encoding == "cdr");
  }
}

TEST_CASE("MCAP writer refuses an unknown compression and an unwritable path") {
  McapWriterOptions options;
  options.compression = "bz2";
  CHECK_THROWS_WITH(McapWriter("/nonexistent/x.mcap", options), Catch::Contains("bz2"));
  CHECK_THROWS_WITH(McapWriter("/nonexistent/x.mcap"), Catch::Contains("/nonexistent/x.mcap"));
}
