#include "rgbdvo/io/mcap_reader.hpp"

#include <isa-l/crc.h>
#include <lz4frame.h>
#include <zstd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <regex>

#include "test_support.hpp"

using namespace rgbdvo;

namespace {

std::string DataFile(const std::string& name) { return test::SourceDir() + "/data/mcap/" + name; }

std::vector<uint8_t> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

// Little-endian fields appended to a byte vector, as MCAP writes them.
struct Bytes {
  std::vector<uint8_t> b;
  Bytes& Int(uint64_t v, int n) {
    for (int i = 0; i < n; ++i) b.push_back(static_cast<uint8_t>(v >> (8 * i)));
    return *this;
  }
  Bytes& Str(const std::string& s) {
    Int(s.size(), 4);
    b.insert(b.end(), s.begin(), s.end());
    return *this;
  }
  Bytes& Raw(const std::vector<uint8_t>& v) {
    b.insert(b.end(), v.begin(), v.end());
    return *this;
  }
  Bytes& Record(uint8_t opcode, const Bytes& content) {
    Int(opcode, 1).Int(content.b.size(), 8);
    return Raw(content.b);
  }
};

const std::vector<uint8_t> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

std::vector<uint8_t> MessageData(int i) {
  std::vector<uint8_t> data(300 + 40 * i);
  for (size_t k = 0; k < data.size(); ++k) data[k] = static_cast<uint8_t>(k % 7 + i);
  return data;
}

std::vector<uint8_t> Compress(const std::string& compression, const std::vector<uint8_t>& in) {
  if (compression == "zstd") {
    std::vector<uint8_t> out(ZSTD_compressBound(in.size()));
    out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3));
    return out;
  }
  if (compression == "lz4") {
    std::vector<uint8_t> out(LZ4F_compressFrameBound(in.size(), nullptr));
    out.resize(LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr));
    return out;
  }
  return in;
}

// An MCAP file of one chunk (`compression`) holding a schema, a channel and five messages of
// MessageData, its message index, Data End with the data section's CRC, a summary (schema,
// channel, statistics) when asked, the footer with the summary's CRC. `size_error` is added to
// the chunk's declared uncompressed size.
std::vector<uint8_t> WriteMcap(const std::string& compression, bool summary,
                               int64_t size_error = 0) {
  Bytes schema, channel, records;
  schema.Int(1, 2).Str("sensor_msgs/msg/Image").Str("ros2msg").Int(3, 4).Raw({'u', '8', ' '});
  channel.Int(1, 2).Int(1, 2).Str("/camera/rgb").Str("cdr").Int(0, 4);
  records.Record(0x03, schema).Record(0x04, channel);
  Bytes index;
  index.Int(1, 2).Int(5 * 16, 4);
  for (int i = 0; i < 5; ++i) {
    Bytes m;
    m.Int(1, 2).Int(i, 4).Int(100 + i, 8).Int(200 + i, 8).Raw(MessageData(i));
    index.Int(100 + i, 8).Int(records.b.size(), 8);
    records.Record(0x05, m);
  }
  const std::vector<uint8_t> stored = Compress(compression, records.b);
  Bytes chunk;
  chunk.Int(100, 8).Int(104, 8).Int(records.b.size() + size_error, 8);
  chunk.Int(crc32_gzip_refl(0, records.b.data(), records.b.size()), 4).Str(compression);
  chunk.Int(stored.size(), 8).Raw(stored);
  Bytes file;
  file.Raw(kMagic).Record(0x01, Bytes().Str("ros2").Str("rgbdvo test"));
  file.Record(0x06, chunk).Record(0x07, index);
  file.Record(0x0F, Bytes().Int(crc32_gzip_refl(0, file.b.data(), file.b.size()), 4));
  const size_t summary_start = file.b.size();
  if (summary) {
    Bytes stats;
    stats.Int(5, 8).Int(1, 2).Int(1, 4).Int(0, 4).Int(0, 4).Int(1, 4).Int(100, 8).Int(104, 8);
    stats.Int(10, 4).Int(1, 2).Int(5, 8);
    file.Record(0x03, schema).Record(0x04, channel).Record(0x0B, stats);
  }
  const size_t footer = file.b.size();
  file.Int(0x02, 1).Int(20, 8).Int(summary ? summary_start : 0, 8).Int(0, 8);
  const size_t from = summary ? summary_start : footer;
  file.Int(crc32_gzip_refl(0, file.b.data() + from, file.b.size() - from), 4);
  return file.Raw(kMagic).b;
}

std::string WriteTemp(const std::string& name, const std::vector<uint8_t>& bytes) {
  static const std::string dir = test::MakeTempDir("mcap");
  std::string path = dir + "/" + name;
  WriteBytes(path, bytes);
  return path;
}

// Where in the file the first record of `opcode` after the magic starts (records outside
// chunks only).
size_t RecordOffset(const std::vector<uint8_t>& file, uint8_t opcode) {
  size_t pos = 8;
  while (pos + 9 <= file.size() && file[pos] != opcode) {
    uint64_t length = 0;
    for (int i = 7; i >= 0; --i) length = length << 8 | file[pos + 1 + i];
    pos += 9 + length;
  }
  REQUIRE(pos + 9 <= file.size());
  return pos;
}

void SetU64(std::vector<uint8_t>& file, size_t at, uint64_t v) {
  for (int i = 0; i < 8; ++i) file[at + i] = static_cast<uint8_t>(v >> (8 * i));
}

std::string RefusalOf(const std::string& path, const McapReaderOptions& options = {}) {
  try {
    ReadMcapRecords(path, options);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(read without error)";
}

// The types the conformance JSON lists, in order.
std::vector<std::string> JsonTypes(const std::string& path) {
  const std::string json = test::Slurp(path);
  const std::regex type_re("\"type\": \"([A-Za-z]+)\"");
  std::vector<std::string> types;
  for (auto it = std::sregex_iterator(json.begin(), json.end(), type_re);
       it != std::sregex_iterator(); ++it)
    types.push_back((*it)[1]);
  return types;
}

}  // namespace

TEST_CASE("MCAP conformance files read to the record types their JSON lists") {
  for (const char* name :
       {"TenMessages-ch-chx-mx-pad-rch-rsh-st-sum", "TenMessages", "OneAttachment-ax-pad-st-sum",
        "NoData", "OneSchemalessMessage-ch-chx-mx-st-sum", "OneMetadata-mdx-pad-st-sum"}) {
    INFO(name);
    std::vector<std::string> types;
    for (const McapRecord& r : ReadMcapRecords(DataFile(std::string(name) + ".mcap"))) {
      // The suite lists a chunk's records in its place and leaves message indexes out.
      if (r.opcode != 0x06 && r.opcode != 0x07) types.push_back(McapRecordName(r.opcode));
    }
    CHECK(types == JsonTypes(DataFile(std::string(name) + ".json")));
  }
}

TEST_CASE("MCAP messages of the conformance files in file order with their fields") {
  // The log times of TenMessages as its JSON lists them (not sorted: file order).
  const std::vector<uint64_t> log_times = {0, 2, 1, 3, 3, 5, 4, 7, 8, 9};
  for (const char* name : {"TenMessages.mcap", "TenMessages-ch-chx-mx-pad-rch-rsh-st-sum.mcap"}) {
    INFO(name);
    McapReader reader(DataFile(name));
    std::vector<McapMessage> messages;
    while (std::optional<McapMessage> m = reader.NextMessage()) messages.push_back(*m);
    REQUIRE(messages.size() == log_times.size());
    for (size_t i = 0; i < messages.size(); ++i) {
      CHECK(messages[i].sequence == i);
      CHECK(messages[i].log_time == log_times[i]);
      CHECK(messages[i].publish_time == log_times[i]);
      CHECK(messages[i].data == std::vector<uint8_t>{1, 2, 3});
    }
    const McapChannel* channel = reader.Channel(1);
    REQUIRE(channel);
    CHECK(channel->topic == "example");
    CHECK(channel->metadata == std::map<std::string, std::string>{{"foo", "bar"}});
    REQUIRE(reader.Schema(channel->schema_id));
    CHECK(reader.Schema(channel->schema_id)->name == "Example");
  }
  const std::vector<McapRecord> records =
      ReadMcapRecords(DataFile("OneAttachment-ax-pad-st-sum.mcap"));
  const auto* attachment = std::get_if<McapAttachment>(&records.at(1).body);
  REQUIRE(attachment);
  CHECK(attachment->name == "myFile");
  CHECK(attachment->data == std::vector<uint8_t>{1, 2, 3});
  CHECK(attachment->crc != 0);
}

TEST_CASE("MCAP chunks uncompressed, zstd and lz4, with and without a summary") {
  for (const std::string compression : {"", "zstd", "lz4"}) {
    for (const bool summary : {true, false}) {
      INFO("compression '" << compression << "', summary " << summary);
      const std::vector<uint8_t> bytes = WriteMcap(compression, summary);
      McapReader reader(WriteTemp("chunked.mcap", bytes));
      std::optional<McapRecord> r;
      std::vector<McapMessage> messages;
      bool chunk_seen = false, statistics_seen = false;
      while ((r = reader.Next())) {
        if (const auto* c = std::get_if<McapChunk>(&r->body)) {
          CHECK(c->compression == compression);
          chunk_seen = true;
        }
        if (auto* m = std::get_if<McapMessage>(&r->body)) {
          CHECK(r->offset_in_chunk.has_value());
          messages.push_back(*m);
        }
        statistics_seen |= std::holds_alternative<McapStatistics>(r->body);
      }
      CHECK(chunk_seen);
      CHECK(statistics_seen == summary);
      REQUIRE(messages.size() == 5);
      for (int i = 0; i < 5; ++i) {
        CHECK(messages[i].log_time == uint64_t(100 + i));
        CHECK(messages[i].publish_time == uint64_t(200 + i));
        CHECK(messages[i].data == MessageData(i));
      }
      CHECK(reader.Channel(1)->topic == "/camera/rgb");
      CHECK(reader.Schema(1)->name == "sensor_msgs/msg/Image");
    }
  }
}

TEST_CASE("MCAP reader refuses every truncation of a file, naming the file") {
  for (const char* name : {"TenMessages.mcap", "TenMessages-ch-chx-mx-pad-rch-rsh-st-sum.mcap"}) {
    const std::vector<uint8_t> bytes = ReadBytes(DataFile(name));
    for (size_t size = 0; size < bytes.size(); ++size) {
      const std::string path =
          WriteTemp("truncated.mcap", std::vector<uint8_t>(bytes.begin(), bytes.begin() + size));
      INFO(name << " cut to " << size << " bytes");
      CHECK_THROWS_WITH(ReadMcapRecords(path), Catch::StartsWith(path + ": "));
    }
  }
}

TEST_CASE("MCAP reader refuses a bad magic at either end") {
  std::vector<uint8_t> bytes = ReadBytes(DataFile("TenMessages.mcap"));
  bytes[1] = 'N';
  std::string path = WriteTemp("lead.mcap", bytes);
  CHECK(RefusalOf(path) == path + ": not an MCAP file (bad magic at offset 0)");
  bytes = ReadBytes(DataFile("TenMessages.mcap"));
  bytes[bytes.size() - 3] = 'X';
  path = WriteTemp("trail.mcap", bytes);
  CHECK_THAT(RefusalOf(path), Catch::StartsWith(path + ": MCAP Footer record at offset ") &&
                                  Catch::EndsWith("bad magic after the Footer"));
}

TEST_CASE("MCAP reader refuses lengths beyond what is left, before allocating") {
  const std::vector<uint8_t> original = WriteMcap("zstd", true);
  const size_t chunk = RecordOffset(original, 0x06);
  std::vector<uint8_t> bytes = original;
  SetU64(bytes, chunk + 1, ~uint64_t{0});  // the chunk record's content length
  std::string path = WriteTemp("huge_record.mcap", bytes);
  CHECK_THAT(RefusalOf(path),
             Catch::StartsWith(path + ": MCAP Chunk record at offset " + std::to_string(chunk) +
                               ": content length 18446744073709551615 runs past the end"));

  bytes = original;
  SetU64(bytes, chunk + 9 + 8 + 8 + 8 + 4 + 4 + 4, ~uint64_t{0});  // the records' length
  path = WriteTemp("huge_records.mcap", bytes);
  CHECK_THAT(RefusalOf(path), Catch::StartsWith(path + ": MCAP Chunk record at offset ") &&
                                  Catch::Contains("runs past the record's end"));

  bytes = original;
  SetU64(bytes, chunk + 9 + 16, uint64_t{1} << 40);  // uncompressed_size: a terabyte
  path = WriteTemp("huge_uncompressed.mcap", bytes);
  CHECK_THAT(RefusalOf(path), Catch::Contains("uncompressed_size 1099511627776 above the limit"));
  // Within the limit but far beyond what the data gives: refused, the output grown only as far
  // as the data went.
  SetU64(bytes, chunk + 9 + 16, (uint64_t{1} << 30) - 1);
  path = WriteTemp("large_uncompressed.mcap", bytes);
  CHECK_THAT(RefusalOf(path), Catch::StartsWith(path + ": MCAP Chunk record at offset ") &&
                                  Catch::Contains("not the declared uncompressed_size"));

  // A string inside the chunk claiming the largest length a u32 holds (the chunk's CRC zeroed,
  // so not checked).
  const std::vector<uint8_t> plain = WriteMcap("", false);
  bytes = plain;
  const size_t records = RecordOffset(plain, 0x06) + 9 + 8 + 8 + 8 + 4 + 4 + 8;
  for (int i = 0; i < 4; ++i) bytes[RecordOffset(plain, 0x06) + 9 + 24 + i] = 0;
  for (int i = 0; i < 4; ++i) bytes[records + 9 + 2 + i] = 0xFF;  // the schema's name length
  path = WriteTemp("huge_string.mcap", bytes);
  CHECK(RefusalOf(path) == path + ": MCAP Schema record at offset 0 of the records of the " +
                               "Chunk at offset " + std::to_string(RecordOffset(plain, 0x06)) +
                               ": a string of 4294967295 bytes runs past the record's end (" +
                               "39 bytes left)");

  McapReaderOptions small;
  small.max_record_bytes = 1000;
  path = WriteTemp("limit.mcap", original);
  CHECK_THAT(RefusalOf(path, small), Catch::Contains("above the limit of 1000 bytes"));
}

TEST_CASE("MCAP reader refuses bad CRCs, naming the record") {
  // A message's byte in a file of records outside chunks: the data section's CRC.
  std::vector<uint8_t> bytes = ReadBytes(DataFile("TenMessages.mcap"));
  bytes[RecordOffset(bytes, 0x05) + 9 + 22] ^= 1;
  std::string path = WriteTemp("data_crc.mcap", bytes);
  CHECK_THAT(RefusalOf(path), Catch::StartsWith(path + ": MCAP DataEnd record at offset ") &&
                                  Catch::Contains("data section CRC mismatch"));
  // Inside an uncompressed chunk: the chunk's CRC, before the data section's.
  bytes = ReadBytes(DataFile("TenMessages-ch-chx-mx-pad-rch-rsh-st-sum.mcap"));
  const size_t chunk = RecordOffset(bytes, 0x06);
  bytes[chunk + 60] ^= 1;
  path = WriteTemp("chunk_crc.mcap", bytes);
  CHECK(RefusalOf(path) == path + ": MCAP Chunk record at offset " + std::to_string(chunk) +
                               ": uncompressed_crc mismatch (the chunk's records are corrupt)");
  // An attachment's data.
  bytes = ReadBytes(DataFile("OneAttachment-ax-pad-st-sum.mcap"));
  const size_t attachment = RecordOffset(bytes, 0x09);
  bytes[attachment + 9 + 8 + 8 + 4 + 6 + 4 + 24 + 8] ^= 1;
  path = WriteTemp("attachment_crc.mcap", bytes);
  CHECK(RefusalOf(path) == path + ": MCAP Attachment record at offset " +
                               std::to_string(attachment) +
                               ": CRC mismatch (the attachment's bytes are corrupt)");
  // The summary's.
  bytes = WriteMcap("", true);
  bytes[RecordOffset(bytes, 0x0B) + 9] ^= 1;
  path = WriteTemp("summary_crc.mcap", bytes);
  CHECK_THAT(RefusalOf(path), Catch::StartsWith(path + ": MCAP Footer record at offset ") &&
                                  Catch::Contains("summary CRC mismatch"));
}

TEST_CASE("MCAP reader refuses a chunk that decompresses to another size than declared") {
  for (const std::string compression : {"", "zstd", "lz4"}) {
    for (const int64_t error : {-1, 1}) {
      INFO("compression '" << compression << "', declared size off by " << error);
      const std::vector<uint8_t> bytes = WriteMcap(compression, false, error);
      const std::string path = WriteTemp("size.mcap", bytes);
      CHECK_THAT(RefusalOf(path),
                 Catch::StartsWith(path + ": MCAP Chunk record at offset " +
                                   std::to_string(RecordOffset(bytes, 0x06)) + ": ") &&
                     Catch::Contains("uncompressed_size"));
    }
  }
  // Corrupt compressed data.
  for (const std::string compression : {"zstd", "lz4"}) {
    std::vector<uint8_t> bytes = WriteMcap(compression, false);
    const size_t chunk = RecordOffset(bytes, 0x06);
    for (size_t k = chunk + 70; k < chunk + 90; ++k) bytes[k] ^= 0x55;
    const std::string path = WriteTemp("corrupt.mcap", bytes);
    CHECK_THAT(RefusalOf(path),
               Catch::StartsWith(path + ": MCAP Chunk record at offset " + std::to_string(chunk)));
  }
  const std::string path = WriteTemp("unknown.mcap", WriteMcap("brotli", false));
  CHECK_THAT(RefusalOf(path), Catch::EndsWith("unknown compression 'brotli' (known: zstd, lz4)"));
}

TEST_CASE("MCAP reader refuses a message before its channel and a missing file") {
  std::vector<uint8_t> bytes = ReadBytes(DataFile("TenMessages.mcap"));
  const size_t message = RecordOffset(bytes, 0x05);
  bytes[message + 9] = 7;  // channel 7, never defined
  const std::string path = WriteTemp("channel.mcap", bytes);
  CHECK(RefusalOf(path) == path + ": MCAP Message record at offset " + std::to_string(message) +
                               ": message on channel 7, which no Channel record before it " +
                               "defines");
  CHECK_THROWS_WITH(McapReader(path + ".none"), path + ".none: cannot open the MCAP file");
}
