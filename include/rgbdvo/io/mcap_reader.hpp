#pragma once
// MCAP files, the container of ROS 2 bags (the default storage since ROS 2 Iron): our own reader
// of the format's records (the specification of the format's major version 0: magic, records of
// <opcode u8><content length u64><content>, little-endian), private to the library, not
// installed. Streamed record by record: the memory held is one record, or one chunk compressed
// and decompressed, never the whole file. No summary or index is needed; those present are read
// as records like any other.
//
// Every length is checked against what is left of its record, chunk or file before anything is
// allocated; CRCs that are non-zero are checked (a chunk's uncompressed records, the data
// section at Data End, an attachment, the summary at the footer). A file that breaks the format
// throws std::runtime_error naming the file, the record's type and its offset.

#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace rgbdvo {

// The records of the format, each with the fields the specification gives it.
struct McapHeader {
  std::string profile, library;
};
struct McapFooter {
  uint64_t summary_start = 0, summary_offset_start = 0;
  uint32_t summary_crc = 0;
};
struct McapSchema {
  uint16_t id = 0;
  std::string name, encoding;
  std::vector<uint8_t> data;
  bool operator==(const McapSchema& o) const;
};
struct McapChannel {
  uint16_t id = 0, schema_id = 0;  // schema_id 0: no schema
  std::string topic, message_encoding;
  std::map<std::string, std::string> metadata;
  bool operator==(const McapChannel& o) const;
};
struct McapMessage {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0, publish_time = 0;  // ns
  std::vector<uint8_t> data;
};
// A chunk's own fields; its records follow it in the stream, decompressed and checked.
struct McapChunk {
  uint64_t message_start_time = 0, message_end_time = 0, uncompressed_size = 0;
  uint32_t uncompressed_crc = 0;
  std::string compression;  // "", "zstd" or "lz4"
  uint64_t compressed_size = 0;
};
struct McapMessageIndex {
  uint16_t channel_id = 0;
  std::vector<std::pair<uint64_t, uint64_t>> records;  // log time, offset in the chunk's records
};
struct McapChunkIndex {
  uint64_t message_start_time = 0, message_end_time = 0, chunk_start_offset = 0, chunk_length = 0;
  std::map<uint16_t, uint64_t> message_index_offsets;
  uint64_t message_index_length = 0;
  std::string compression;
  uint64_t compressed_size = 0, uncompressed_size = 0;
};
struct McapAttachment {
  uint64_t log_time = 0, create_time = 0;
  std::string name, media_type;
  std::vector<uint8_t> data;
  uint32_t crc = 0;
};
struct McapAttachmentIndex {
  uint64_t offset = 0, length = 0, log_time = 0, create_time = 0, data_size = 0;
  std::string name, media_type;
};
struct McapStatistics {
  uint64_t message_count = 0;
  uint16_t schema_count = 0;
  uint32_t channel_count = 0, attachment_count = 0, metadata_count = 0, chunk_count = 0;
  uint64_t message_start_time = 0, message_end_time = 0;
  std::map<uint16_t, uint64_t> channel_message_counts;
};
struct McapMetadata {
  std::string name;
  std::map<std::string, std::string> metadata;
};
struct McapMetadataIndex {
  uint64_t offset = 0, length = 0;
  std::string name;
};
struct McapSummaryOffset {
  uint8_t group_opcode = 0;
  uint64_t group_start = 0, group_length = 0;
};
struct McapDataEnd {
  uint32_t data_section_crc = 0;
};
// A private record (opcode 0x80-0xFF) or one of a later minor version: skipped, as the
// specification asks.
struct McapUnknown {};

struct McapRecord {
  uint8_t opcode = 0;
  uint64_t offset = 0;                      // in the file; of the chunk for a record inside one
  std::optional<uint64_t> offset_in_chunk;  // within the chunk's uncompressed records
  std::variant<McapHeader, McapFooter, McapSchema, McapChannel, McapMessage, McapChunk,
               McapMessageIndex, McapChunkIndex, McapAttachment, McapAttachmentIndex,
               McapStatistics, McapMetadata, McapMetadataIndex, McapSummaryOffset, McapDataEnd,
               McapUnknown>
      body;
};

// The name of a record type as the specification writes it ("Chunk", "DataEnd"), or
// "opcode 0xNN" for one it does not define.
std::string McapRecordName(uint8_t opcode);

struct McapReaderOptions {
  // The largest record content, and chunk decompressed, read into memory, bytes: a larger one is
  // refused (a bound on memory whatever a file's lengths claim).
  uint64_t max_record_bytes = uint64_t{1} << 30;
  void Check() const;  // throws, naming the field and the rule it broke
};

class McapReader {
 public:
  // Opens the file and checks its leading magic. Throws std::runtime_error naming the file.
  explicit McapReader(const std::string& path, const McapReaderOptions& options = {});
  ~McapReader();
  McapReader(const McapReader&) = delete;
  McapReader& operator=(const McapReader&) = delete;

  // The next record in file order, a chunk's records right after the chunk itself; nullopt once
  // the footer and the trailing magic ending the file were read. Each Channel is checked
  // against its schema and each Message against its channel (defined before it, as the
  // specification requires), a repeated Schema or Channel against its first definition.
  std::optional<McapRecord> Next();
  // The next Message in file order (the records between are read and checked as by Next).
  std::optional<McapMessage> NextMessage();

  // Schemas and channels defined so far, by id (nullptr when none).
  const McapSchema* Schema(uint16_t id) const;
  const McapChannel* Channel(uint16_t id) const;
  const std::string& path() const { return path_; }

 private:
  struct Chunk;
  std::optional<McapRecord> NextInChunk();
  McapRecord ReadFileRecord();
  void Register(const McapRecord& record);
  void Fill(uint8_t* out, uint64_t size);
  [[noreturn]] void Fail(uint8_t opcode, uint64_t offset, const std::string& what) const;

  std::string path_;
  McapReaderOptions options_;
  std::FILE* file_ = nullptr;
  uint64_t file_size_ = 0, pos_ = 0;
  uint32_t crc_ = 0;  // of every byte read so far since crc_start_
  uint64_t crc_start_ = 0;
  bool data_ended_ = false, done_ = false, header_read_ = false;
  std::unique_ptr<Chunk> chunk_;  // the chunk whose records are being read
  std::map<uint16_t, McapSchema> schemas_;
  std::map<uint16_t, McapChannel> channels_;
};

// All records of the file at `path` as McapReader::Next gives them.
std::vector<McapRecord> ReadMcapRecords(const std::string& path,
                                        const McapReaderOptions& options = {});

// Decompresses a chunk's records: `compression` "" (a copy), "zstd" or "lz4" (frame format), to
// exactly `uncompressed_size` bytes. Throws std::runtime_error with the reason (unknown
// compression, corrupt data, another size than declared); the output grows with what is
// decompressed, never to a size only declared.
std::vector<uint8_t> DecompressMcapChunk(const std::string& compression, const uint8_t* data,
                                         size_t size, uint64_t uncompressed_size);

}  // namespace rgbdvo
