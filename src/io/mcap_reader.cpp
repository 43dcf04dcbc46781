#include "rgbdvo/io/mcap_reader.hpp"

#include <isa-l/crc.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>

#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {

namespace {

constexpr std::array<uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
constexpr uint64_t kRecordPrefix = 9;  // opcode u8, content length u64

enum Op : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

uint64_t LittleEndian(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = v << 8 | p[i];
  return v;
}

// A record's content read field by field; a field longer than what is left throws the reason,
// which the reader turns into an error naming the file and the record.
class Fields {
 public:
  Fields(const uint8_t* data, uint64_t size) : data_(data), size_(size) {}
  uint64_t left() const { return size_ - pos_; }
  uint8_t U8() { return static_cast<uint8_t>(Int(1, "a u8")); }
  uint16_t U16() { return static_cast<uint16_t>(Int(2, "a u16")); }
  uint32_t U32() { return static_cast<uint32_t>(Int(4, "a u32")); }
  uint64_t U64() { return Int(8, "a u64"); }
  const uint8_t* Take(uint64_t n, const char* what) {
    if (n > left())
      throw std::runtime_error(std::string(what) + " of " + std::to_string(n) +
                               " bytes runs past the record's end (" + std::to_string(left()) +
                               " bytes left)");
    const uint8_t* p = data_ + pos_;
    pos_ += n;
    return p;
  }
  std::string String() {
    const uint32_t n = U32();
    const uint8_t* p = Take(n, "a string");
    return std::string(reinterpret_cast<const char*>(p), n);
  }
  std::vector<uint8_t> Bytes(uint64_t n) {
    const uint8_t* p = Take(n, "a byte array");
    return std::vector<uint8_t>(p, p + n);
  }
  std::vector<uint8_t> Rest() { return Bytes(left()); }
  // A map or array: its u32 byte length, then entries read by `entry` until that length is used.
  void Entries(const char* what, const std::function<void(Fields&)>& entry) {
    const uint32_t n = U32();
    Fields inner(Take(n, what), n);
    while (inner.left() > 0) entry(inner);
  }

 private:
  uint64_t Int(int bytes, const char* what) {
    return LittleEndian(Take(static_cast<uint64_t>(bytes), what), bytes);
  }
  const uint8_t* data_;
  uint64_t size_, pos_ = 0;
};

std::map<std::string, std::string> StringMap(Fields& f, const char* what) {
  std::map<std::string, std::string> m;
  f.Entries(what, [&m](Fields& e) {
    std::string key = e.String();
    m[key] = e.String();
  });
  return m;
}

std::map<uint16_t, uint64_t> IdMap(Fields& f, const char* what) {
  std::map<uint16_t, uint64_t> m;
  f.Entries(what, [&m](Fields& e) {
    const uint16_t key = e.U16();
    m[key] = e.U64();
  });
  return m;
}

// One reader per record type: its fields in the specification's order.
McapHeader ReadHeader(Fields& f) {
  McapHeader h;
  h.profile = f.String();
  h.library = f.String();
  return h;
}

McapFooter ReadFooter(Fields& f) {
  McapFooter h;
  h.summary_start = f.U64();
  h.summary_offset_start = f.U64();
  h.summary_crc = f.U32();
  return h;
}

McapSchema ReadSchema(Fields& f) {
  McapSchema s;
  s.id = f.U16();
  s.name = f.String();
  s.encoding = f.String();
  s.data = f.Bytes(f.U32());
  return s;
}

McapChannel ReadChannel(Fields& f) {
  McapChannel c;
  c.id = f.U16();
  c.schema_id = f.U16();
  c.topic = f.String();
  c.message_encoding = f.String();
  c.metadata = StringMap(f, "the metadata map");
  return c;
}

McapMessage ReadMessage(Fields& f) {
  McapMessage m;
  m.channel_id = f.U16();
  m.sequence = f.U32();
  m.log_time = f.U64();
  m.publish_time = f.U64();
  m.data = f.Rest();
  return m;
}

McapChunk ReadChunk(Fields& f, const uint8_t** chunk_records) {
  McapChunk c;
  c.message_start_time = f.U64();
  c.message_end_time = f.U64();
  c.uncompressed_size = f.U64();
  c.uncompressed_crc = f.U32();
  c.compression = f.String();
  c.compressed_size = f.U64();
  *chunk_records = f.Take(c.compressed_size, "the records");
  return c;
}

McapMessageIndex ReadMessageIndex(Fields& f) {
  McapMessageIndex m;
  m.channel_id = f.U16();
  f.Entries("the records array", [&m](Fields& e) {
    const uint64_t time = e.U64();
    m.records.emplace_back(time, e.U64());
  });
  return m;
}

McapChunkIndex ReadChunkIndex(Fields& f) {
  McapChunkIndex c;
  c.message_start_time = f.U64();
  c.message_end_time = f.U64();
  c.chunk_start_offset = f.U64();
  c.chunk_length = f.U64();
  c.message_index_offsets = IdMap(f, "the message index offsets map");
  c.message_index_length = f.U64();
  c.compression = f.String();
  c.compressed_size = f.U64();
  c.uncompressed_size = f.U64();
  return c;
}

McapAttachment ReadAttachment(Fields& f, const uint8_t* content, uint64_t size) {
  McapAttachment a;
  a.log_time = f.U64();
  a.create_time = f.U64();
  a.name = f.String();
  a.media_type = f.String();
  a.data = f.Bytes(f.U64());
  const uint64_t crc_covers = size - f.left();
  a.crc = f.U32();
  if (a.crc != 0 && crc32_gzip_refl(0, content, crc_covers) != a.crc)
    throw std::runtime_error("CRC mismatch (the attachment's bytes are corrupt)");
  return a;
}

McapAttachmentIndex ReadAttachmentIndex(Fields& f) {
  McapAttachmentIndex a;
  a.offset = f.U64();
  a.length = f.U64();
  a.log_time = f.U64();
  a.create_time = f.U64();
  a.data_size = f.U64();
  a.name = f.String();
  a.media_type = f.String();
  return a;
}

McapStatistics ReadStatistics(Fields& f) {
  McapStatistics s;
  s.message_count = f.U64();
  s.schema_count = f.U16();
  s.channel_count = f.U32();
  s.attachment_count = f.U32();
  s.metadata_count = f.U32();
  s.chunk_count = f.U32();
  s.message_start_time = f.U64();
  s.message_end_time = f.U64();
  s.channel_message_counts = IdMap(f, "the channel message counts map");
  return s;
}

McapMetadata ReadMetadata(Fields& f) {
  McapMetadata m;
  m.name = f.String();
  m.metadata = StringMap(f, "the metadata map");
  return m;
}

McapMetadataIndex ReadMetadataIndex(Fields& f) {
  McapMetadataIndex m;
  m.offset = f.U64();
  m.length = f.U64();
  m.name = f.String();
  return m;
}

McapSummaryOffset ReadSummaryOffset(Fields& f) {
  McapSummaryOffset s;
  s.group_opcode = f.U8();
  s.group_start = f.U64();
  s.group_length = f.U64();
  return s;
}

McapDataEnd ReadDataEnd(Fields& f) {
  McapDataEnd d;
  d.data_section_crc = f.U32();
  return d;
}

// The record's body from its content; for a chunk also where its records are in `content`.
// Fields after the known ones (a later minor version's) are ignored, as the specification asks.
McapRecord Parse(uint8_t opcode, const uint8_t* content, uint64_t size,
                 const uint8_t** chunk_records) {
  Fields f(content, size);
  McapRecord r;
  r.opcode = opcode;
  switch (opcode) {
    case kHeader:
      r.body = ReadHeader(f);
      break;
    case kFooter:
      r.body = ReadFooter(f);
      break;
    case kSchema:
      r.body = ReadSchema(f);
      break;
    case kChannel:
      r.body = ReadChannel(f);
      break;
    case kMessage:
      r.body = ReadMessage(f);
      break;
    case kChunk:
      r.body = ReadChunk(f, chunk_records);
      break;
    case kMessageIndex:
      r.body = ReadMessageIndex(f);
      break;
    case kChunkIndex:
      r.body = ReadChunkIndex(f);
      break;
    case kAttachment:
      r.body = ReadAttachment(f, content, size);
      break;
    case kAttachmentIndex:
      r.body = ReadAttachmentIndex(f);
      break;
    case kStatistics:
      r.body = ReadStatistics(f);
      break;
    case kMetadata:
      r.body = ReadMetadata(f);
      break;
    case kMetadataIndex:
      r.body = ReadMetadataIndex(f);
      break;
    case kSummaryOffset:
      r.body = ReadSummaryOffset(f);
      break;
    case kDataEnd:
      r.body = ReadDataEnd(f);
      break;
    case 0:
      throw std::runtime_error("opcode 0 is not a record type");
    default:
      r.body = McapUnknown{};
  }
  return r;
}

std::string Hex(uint8_t v) {
  const char* digits = "0123456789abcdef";
  return std::string("0x") + digits[v >> 4] + digits[v & 15];
}

// Runs a streaming decompressor into an output that grows with what it produces, up to
// `declared` bytes. `step` decompresses from `in` into `out`, advancing both, and returns
// whether its frame is complete; a frame ending exactly at the input's end ends the data.
std::vector<uint8_t> Inflate(const uint8_t* data, size_t size, uint64_t declared,
                             const std::function<bool(uint8_t* out, size_t* out_size,
                                                      const uint8_t* in, size_t* in_size)>& step) {
  std::vector<uint8_t> out(std::min<uint64_t>(declared, std::max<uint64_t>(65536, 4 * size)));
  size_t produced = 0, consumed = 0;
  bool complete = false;
  uint8_t spare = 0;  // asked for a byte beyond the declared size: there must be none
  while (consumed < size || !complete) {
    if (produced == out.size() && out.size() < declared)
      out.resize(std::min<uint64_t>(declared, 2 * out.size()));
    const bool full = produced == out.size();
    size_t out_size = full ? 1 : out.size() - produced;
    size_t in_size = size - consumed;
    complete = step(full ? &spare : out.data() + produced, &out_size, data + consumed, &in_size);
    if (full && out_size > 0)
      throw std::runtime_error("decompresses to more than the declared uncompressed_size " +
                               std::to_string(declared));
    if (out_size == 0 && in_size == 0 && !complete)
      throw std::runtime_error("compressed data ends inside a frame (truncated or corrupt)");
    produced += out_size;
    consumed += in_size;
  }
  if (produced != declared)
    throw std::runtime_error("decompresses to " + std::to_string(produced) +
                             " bytes, not the declared uncompressed_size " +
                             std::to_string(declared));
  return out;
}

}  // namespace

bool McapSchema::operator==(const McapSchema& o) const {
  return id == o.id && name == o.name && encoding == o.encoding && data == o.data;
}

bool McapChannel::operator==(const McapChannel& o) const {
  return id == o.id && schema_id == o.schema_id && topic == o.topic &&
         message_encoding == o.message_encoding && metadata == o.metadata;
}

std::string McapRecordName(uint8_t opcode) {
  static const char* const kNames[] = {
      "",         "Header",        "Footer",        "Schema",     "Channel",         "Message",
      "Chunk",    "MessageIndex",  "ChunkIndex",    "Attachment", "AttachmentIndex", "Statistics",
      "Metadata", "MetadataIndex", "SummaryOffset", "DataEnd"};
  if (opcode >= 1 && opcode <= kDataEnd) return kNames[opcode];
  return "opcode " + Hex(opcode);
}

void McapReaderOptions::Check() const {
  if (max_record_bytes == 0) throw std::invalid_argument("max_record_bytes must be positive");
}

std::vector<uint8_t> DecompressMcapChunk(const std::string& compression, const uint8_t* data,
                                         size_t size, uint64_t uncompressed_size) {
  if (compression.empty()) {
    if (size != uncompressed_size)
      throw std::runtime_error("uncompressed records of " + std::to_string(size) +
                               " bytes, but uncompressed_size says " +
                               std::to_string(uncompressed_size));
    return std::vector<uint8_t>(data, data + size);
  }
  if (size == 0 && uncompressed_size == 0) return {};
  if (compression == "zstd") {
    std::unique_ptr<ZSTD_DCtx, size_t (*)(ZSTD_DCtx*)> ctx(ZSTD_createDCtx(), ZSTD_freeDCtx);
    if (!ctx) throw std::bad_alloc();
    return Inflate(data, size, uncompressed_size,
                   [&ctx](uint8_t* out, size_t* out_size, const uint8_t* in, size_t* in_size) {
                     ZSTD_outBuffer o{out, *out_size, 0};
                     ZSTD_inBuffer i{in, *in_size, 0};
                     const size_t ret = ZSTD_decompressStream(ctx.get(), &o, &i);
                     if (ZSTD_isError(ret))
                       throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(ret));
                     *out_size = o.pos;
                     *in_size = i.pos;
                     return ret == 0;
                   });
  }
  if (compression == "lz4") {
    LZ4F_dctx* raw = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw std::bad_alloc();
    std::unique_ptr<LZ4F_dctx, LZ4F_errorCode_t (*)(LZ4F_dctx*)> ctx(raw,
                                                                     LZ4F_freeDecompressionContext);
    return Inflate(data, size, uncompressed_size,
                   [&ctx](uint8_t* out, size_t* out_size, const uint8_t* in, size_t* in_size) {
                     const size_t ret =
                         LZ4F_decompress(ctx.get(), out, out_size, in, in_size, nullptr);
                     if (LZ4F_isError(ret))
                       throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(ret));
                     return ret == 0;
                   });
  }
  throw std::runtime_error("unknown compression '" + compression + "' (known: zstd, lz4)");
}

// The chunk whose records are being read: its decompressed records and where the next one is.
struct McapReader::Chunk {
  uint64_t offset = 0;  // of the chunk record in the file
  std::vector<uint8_t> records;
  uint64_t pos = 0;
};

McapReader::McapReader(const std::string& path, const McapReaderOptions& options)
    : path_(path), options_(options) {
  options_.Check();
  const std::optional<uint64_t> size = InputFileSize(path, "MCAP file");
  if (!size) throw std::runtime_error(path + ": cannot open the MCAP file");
  file_size_ = *size;
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw std::runtime_error(path + ": cannot open the MCAP file");
  std::array<uint8_t, 8> magic{};
  if (file_size_ < magic.size() + kRecordPrefix + magic.size()) {
    std::fclose(file_);
    throw std::runtime_error(path + ": " + std::to_string(file_size_) +
                             " bytes, too short for an MCAP file (truncated?)");
  }
  Fill(magic.data(), magic.size());
  if (magic != kMagic) {
    std::fclose(file_);
    throw std::runtime_error(path + ": not an MCAP file (bad magic at offset 0)");
  }
}

McapReader::~McapReader() {
  if (file_) std::fclose(file_);
}

void McapReader::Fill(uint8_t* out, uint64_t size) {
  if (std::fread(out, 1, size, file_) != size)
    throw std::runtime_error(path_ + ": read error at offset " + std::to_string(pos_));
  crc_ = crc32_gzip_refl(crc_, out, size);
  pos_ += size;
}

void McapReader::Fail(uint8_t opcode, uint64_t offset, const std::string& what) const {
  std::string where = path_ + ": MCAP " + McapRecordName(opcode) + " record at offset ";
  if (chunk_)
    where += std::to_string(offset) + " of the records of the Chunk at offset " +
             std::to_string(chunk_->offset);
  else
    where += std::to_string(offset);
  throw std::runtime_error(where + ": " + what);
}

const McapSchema* McapReader::Schema(uint16_t id) const {
  const auto it = schemas_.find(id);
  return it == schemas_.end() ? nullptr : &it->second;
}

const McapChannel* McapReader::Channel(uint16_t id) const {
  const auto it = channels_.find(id);
  return it == channels_.end() ? nullptr : &it->second;
}

void McapReader::Register(const McapRecord& record) {
  const uint64_t offset = record.offset_in_chunk ? *record.offset_in_chunk : record.offset;
  if (const auto* s = std::get_if<McapSchema>(&record.body)) {
    if (s->id == 0) return;  // invalid, to be ignored (the specification)
    const auto [it, added] = schemas_.emplace(s->id, *s);
    if (!added && !(it->second == *s))
      Fail(record.opcode, offset,
           "schema " + std::to_string(s->id) + " differs from its first definition");
  } else if (const auto* c = std::get_if<McapChannel>(&record.body)) {
    if (c->schema_id != 0 && !Schema(c->schema_id))
      Fail(record.opcode, offset,
           "channel " + std::to_string(c->id) + " names schema " + std::to_string(c->schema_id) +
               ", which no Schema record before it defines");
    const auto [it, added] = channels_.emplace(c->id, *c);
    if (!added && !(it->second == *c))
      Fail(record.opcode, offset,
           "channel " + std::to_string(c->id) + " differs from its first definition");
  } else if (const auto* m = std::get_if<McapMessage>(&record.body)) {
    if (!Channel(m->channel_id))
      Fail(record.opcode, offset,
           "message on channel " + std::to_string(m->channel_id) +
               ", which no Channel record before it defines");
  }
}

std::optional<McapRecord> McapReader::NextInChunk() {
  Chunk& c = *chunk_;
  const uint64_t left = c.records.size() - c.pos;
  if (left == 0) {
    chunk_.reset();
    return std::nullopt;
  }
  const uint8_t* p = c.records.data() + c.pos;
  const uint8_t opcode = p[0];
  if (left < kRecordPrefix)
    Fail(opcode, c.pos, "the chunk's records end inside this record's opcode and length");
  const uint64_t length = LittleEndian(p + 1, 8);
  if (length > left - kRecordPrefix)
    Fail(opcode, c.pos,
         "content length " + std::to_string(length) +
             " runs past the end of the chunk's records (" + std::to_string(left - kRecordPrefix) +
             " bytes left)");
  // Schemas, channels and messages; a private or later record is skipped.
  if (opcode <= kDataEnd && opcode != kSchema && opcode != kChannel && opcode != kMessage)
    Fail(opcode, c.pos, "not a record a chunk may hold");
  McapRecord r;
  try {
    r = Parse(opcode, p + kRecordPrefix, length, nullptr);
  } catch (const std::runtime_error& e) {
    Fail(opcode, c.pos, e.what());
  }
  r.offset = c.offset;
  r.offset_in_chunk = c.pos;
  Register(r);
  c.pos += kRecordPrefix + length;
  return r;
}

McapRecord McapReader::ReadFileRecord() {
  const uint64_t offset = pos_;
  const uint64_t left = file_size_ - pos_;
  if (left < kRecordPrefix)
    throw std::runtime_error(path_ + ": MCAP file ends at offset " + std::to_string(offset) +
                             " before its Footer record (truncated?)");
  std::array<uint8_t, kRecordPrefix> prefix{};
  const uint32_t crc_before = crc_;
  Fill(prefix.data(), prefix.size());
  const uint8_t opcode = prefix[0];
  const uint64_t length = LittleEndian(prefix.data() + 1, 8);
  if (length > left - kRecordPrefix)
    Fail(opcode, offset,
         "content length " + std::to_string(length) + " runs past the end of the file (" +
             std::to_string(left - kRecordPrefix) + " bytes left; truncated?)");
  if (length > options_.max_record_bytes)
    Fail(opcode, offset,
         "content length " + std::to_string(length) + " above the limit of " +
             std::to_string(options_.max_record_bytes) + " bytes (max_record_bytes)");
  if (!header_read_ && opcode != kHeader) Fail(opcode, offset, "the first record is no Header");
  if (header_read_ && opcode == kHeader) Fail(opcode, offset, "a second Header record");
  header_read_ = true;
  const bool data_end = opcode == kDataEnd;
  if (data_end && data_ended_) Fail(opcode, offset, "a second DataEnd record");
  if (data_ended_ && (opcode == kMessage || opcode == kChunk || opcode == kMessageIndex ||
                      opcode == kAttachment || opcode == kMetadata))
    Fail(opcode, offset, "a data section's record after DataEnd");
  // The data section's CRC covers the file up to the DataEnd record; the summary's from the
  // summary's start up to the Footer's summary_crc field.
  const uint32_t data_crc = crc_before;
  std::vector<uint8_t> content(length);
  Fill(content.data(), length);
  McapRecord r;
  const uint8_t* chunk_records = nullptr;
  try {
    r = Parse(opcode, content.data(), length, &chunk_records);
  } catch (const std::runtime_error& e) {
    Fail(opcode, offset, e.what());
  }
  r.offset = offset;
  if (data_end) {
    const uint32_t stated = std::get<McapDataEnd>(r.body).data_section_crc;
    if (stated != 0 && stated != data_crc)
      Fail(opcode, offset, "data section CRC mismatch (the file's bytes before it are corrupt)");
    data_ended_ = true;
    crc_ = 0;
    crc_start_ = pos_;
  }
  if (const auto* footer = std::get_if<McapFooter>(&r.body)) {
    if (footer->summary_crc != 0) {
      // The CRC runs from the summary's start (the footer itself when there is none); only
      // checked where this pass read from there.
      const uint64_t start = footer->summary_start != 0 ? footer->summary_start : offset;
      uint32_t crc = start == offset ? 0 : crc_before;
      if (start == offset || (data_ended_ && start == crc_start_)) {
        crc = crc32_gzip_refl(crc, prefix.data(), prefix.size());
        crc = crc32_gzip_refl(crc, content.data(), 16);
        if (crc != footer->summary_crc)
          Fail(opcode, offset, "summary CRC mismatch (the summary's bytes are corrupt)");
      }
    }
    std::array<uint8_t, 8> magic{};
    if (file_size_ - pos_ != magic.size())
      Fail(opcode, offset,
           std::to_string(file_size_ - pos_) + " bytes follow the Footer, not the 8 of the magic");
    Fill(magic.data(), magic.size());
    if (magic != kMagic) Fail(opcode, offset, "bad magic after the Footer");
    done_ = true;
  }
  if (const auto* chunk = std::get_if<McapChunk>(&r.body)) {
    if (chunk->uncompressed_size > options_.max_record_bytes)
      Fail(opcode, offset,
           "uncompressed_size " + std::to_string(chunk->uncompressed_size) +
               " above the limit of " + std::to_string(options_.max_record_bytes) +
               " bytes (max_record_bytes)");
    auto next = std::make_unique<Chunk>();
    next->offset = offset;
    try {
      if (chunk->compression.empty()) {
        // The records are the content's tail: moved out rather than copied.
        if (chunk->compressed_size != chunk->uncompressed_size)
          throw std::runtime_error("records of " + std::to_string(chunk->compressed_size) +
                                   " bytes, but uncompressed_size says " +
                                   std::to_string(chunk->uncompressed_size));
        content.erase(content.begin(), content.begin() + (chunk_records - content.data()));
        content.resize(chunk->compressed_size);
        next->records = std::move(content);
      } else {
        next->records = DecompressMcapChunk(chunk->compression, chunk_records,
                                            chunk->compressed_size, chunk->uncompressed_size);
      }
    } catch (const std::runtime_error& e) {
      Fail(opcode, offset, e.what());
    }
    if (chunk->uncompressed_crc != 0 &&
        crc32_gzip_refl(0, next->records.data(), next->records.size()) != chunk->uncompressed_crc)
      Fail(opcode, offset, "uncompressed_crc mismatch (the chunk's records are corrupt)");
    chunk_ = std::move(next);
  }
  Register(r);
  return r;
}

std::optional<McapRecord> McapReader::Next() {
  if (chunk_) {
    std::optional<McapRecord> r = NextInChunk();
    if (r) return r;
  }
  if (done_) return std::nullopt;
  return ReadFileRecord();
}

std::optional<McapMessage> McapReader::NextMessage() {
  while (std::optional<McapRecord> r = Next()) {
    if (auto* m = std::get_if<McapMessage>(&r->body)) return std::move(*m);
  }
  return std::nullopt;
}

std::vector<McapRecord> ReadMcapRecords(const std::string& path, const McapReaderOptions& options) {
  McapReader reader(path, options);
  std::vector<McapRecord> records;
  while (std::optional<McapRecord> r = reader.Next()) records.push_back(std::move(*r));
  return records;
}

}  // namespace rgbdvo
