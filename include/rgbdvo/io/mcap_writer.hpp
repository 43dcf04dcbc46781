#pragma once
// Writes MCAP files as our reader reads them (mcap_reader.hpp): the magic, a Header, then
// chunks (uncompressed, zstd or lz4) holding the Schema, Channel and Message records in the
// order they were given, Data End and a Footer without a summary. For converting recordings
// into ROS 2 bags and for the tests; private to the library, not installed.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace rgbdvo {

struct McapWriterOptions {
  std::string compression = "zstd";          // of the chunks: "", "zstd" or "lz4"
  uint64_t chunk_bytes = uint64_t{1} << 20;  // records gathered before a chunk is written, bytes
  void Check() const;                        // throws, naming the field and the rule it broke
};

class McapWriter {
 public:
  // Creates the file (profile "ros2"). Throws std::runtime_error naming it when it cannot be.
  explicit McapWriter(const std::string& path, const McapWriterOptions& options = {});
  ~McapWriter();  // closes the file if Close was not called (errors then are lost)
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // A channel on `topic` whose messages are `schema_name` (encoding ros2msg, no definition
  // text) serialised as `message_encoding`; returns its id.
  uint16_t AddChannel(const std::string& topic, const std::string& schema_name,
                      const std::string& message_encoding = "cdr");
  void Write(uint16_t channel_id, uint64_t log_time_ns, const std::vector<uint8_t>& data);
  // Writes the last chunk, Data End, the footer and the magic. Throws std::runtime_error naming
  // the file when a write fails.
  void Close();

 private:
  void Record(std::vector<uint8_t>* out, uint8_t opcode, const std::vector<uint8_t>& content);
  void FlushChunk();
  void Put(const std::vector<uint8_t>& bytes);

  std::string path_;
  McapWriterOptions options_;
  std::FILE* file_ = nullptr;
  std::vector<uint8_t> chunk_;  // the records of the chunk being gathered
  uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  bool chunk_has_message_ = false;
  uint16_t next_channel_ = 1;
  uint32_t sequence_ = 0;
};

}  // namespace rgbdvo
