#include "rgbdvo/io/mcap_writer.hpp"

#include <isa-l/crc.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <stdexcept>

namespace rgbdvo {
namespace {

const std::vector<uint8_t> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

void Int(std::vector<uint8_t>* out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out->push_back(static_cast<uint8_t>(v >> (8 * i)));
}

void Str(std::vector<uint8_t>* out, const std::string& s) {
  Int(out, s.size(), 4);
  out->insert(out->end(), s.begin(), s.end());
}

std::vector<uint8_t> Compress(const std::string& compression, const std::vector<uint8_t>& in) {
  if (compression == "zstd") {
    std::vector<uint8_t> out(ZSTD_compressBound(in.size()));
    const size_t n = ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3);
    if (ZSTD_isError(n)) throw std::runtime_error(ZSTD_getErrorName(n));
    out.resize(n);
    return out;
  }
  if (compression == "lz4") {
    std::vector<uint8_t> out(LZ4F_compressFrameBound(in.size(), nullptr));
    const size_t n = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr);
    if (LZ4F_isError(n)) throw std::runtime_error(LZ4F_getErrorName(n));
    out.resize(n);
    return out;
  }
  return in;
}

}  // namespace

void McapWriterOptions::Check() const {
  if (compression != "" && compression != "zstd" && compression != "lz4")
    throw std::invalid_argument("McapWriterOptions.compression must be \"\", zstd or lz4, not '" +
                                compression + "'");
  if (chunk_bytes == 0) throw std::invalid_argument("McapWriterOptions.chunk_bytes must be > 0");
}

McapWriter::McapWriter(const std::string& path, const McapWriterOptions& options)
    : path_(path), options_(options) {
  options_.Check();
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path + ": cannot create the MCAP file");
  std::vector<uint8_t> start = kMagic, header;
  Str(&header, "ros2");
  Str(&header, "rgbdvo");
  Record(&start, 0x01, header);
  Put(start);
}

McapWriter::~McapWriter() {
  if (file_) std::fclose(file_);
}

void McapWriter::Record(std::vector<uint8_t>* out, uint8_t opcode,
                        const std::vector<uint8_t>& content) {
  out->push_back(opcode);
  Int(out, content.size(), 8);
  out->insert(out->end(), content.begin(), content.end());
}

void McapWriter::Put(const std::vector<uint8_t>& bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    throw std::runtime_error(path_ + ": cannot write the MCAP file (disk full?)");
}

uint16_t McapWriter::AddChannel(const std::string& topic, const std::string& schema_name,
                                const std::string& message_encoding) {
  const uint16_t id = next_channel_++;
  std::vector<uint8_t> schema, channel;
  Int(&schema, id, 2);
  Str(&schema, schema_name);
  Str(&schema, "ros2msg");
  Int(&schema, 0, 4);  // no definition text: our reader needs none
  Record(&chunk_, 0x03, schema);
  Int(&channel, id, 2);
  Int(&channel, id, 2);  // the schema of the same id
  Str(&channel, topic);
  Str(&channel, message_encoding);
  Int(&channel, 0, 4);  // no metadata
  Record(&chunk_, 0x04, channel);
  return id;
}

void McapWriter::Write(uint16_t channel_id, uint64_t log_time_ns,
                       const std::vector<uint8_t>& data) {
  std::vector<uint8_t> message;
  message.reserve(22 + data.size());
  Int(&message, channel_id, 2);
  Int(&message, sequence_++, 4);
  Int(&message, log_time_ns, 8);
  Int(&message, log_time_ns, 8);  // publish time
  message.insert(message.end(), data.begin(), data.end());
  Record(&chunk_, 0x05, message);
  chunk_start_ns_ = chunk_has_message_ ? std::min(chunk_start_ns_, log_time_ns) : log_time_ns;
  chunk_end_ns_ = chunk_has_message_ ? std::max(chunk_end_ns_, log_time_ns) : log_time_ns;
  chunk_has_message_ = true;
  if (chunk_.size() >= options_.chunk_bytes) FlushChunk();
}

void McapWriter::FlushChunk() {
  if (chunk_.empty()) return;
  std::vector<uint8_t> stored;
  try {
    stored = Compress(options_.compression, chunk_);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path_ + ": compressing a chunk: " + e.what());
  }
  std::vector<uint8_t> content, record;
  content.reserve(stored.size() + 64);
  Int(&content, chunk_start_ns_, 8);
  Int(&content, chunk_end_ns_, 8);
  Int(&content, chunk_.size(), 8);
  Int(&content, crc32_gzip_refl(0, chunk_.data(), chunk_.size()), 4);
  Str(&content, options_.compression);
  Int(&content, stored.size(), 8);
  content.insert(content.end(), stored.begin(), stored.end());
  Record(&record, 0x06, content);
  Put(record);
  chunk_.clear();
  chunk_has_message_ = false;
}

void McapWriter::Close() {
  if (!file_) return;
  FlushChunk();
  std::vector<uint8_t> end, data_end, footer;
  Int(&data_end, 0, 4);  // no data section CRC: 0 says not computed
  Record(&end, 0x0F, data_end);
  Int(&footer, 0, 8);  // no summary: its start,
  Int(&footer, 0, 8);  // the summary offsets' start
  Int(&footer, 0, 4);  // and its CRC
  Record(&end, 0x02, footer);
  end.insert(end.end(), kMagic.begin(), kMagic.end());
  Put(end);
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!closed) throw std::runtime_error(path_ + ": cannot write the MCAP file (disk full?)");
}

}  // namespace rgbdvo
