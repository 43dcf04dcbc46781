// rgbdvo_mcap_dump FILE: the records McapReader reads from an MCAP file, printed as the format's
// conformance suite lists them (bench/mcap_conformance compares the two): JSON
// {"records": [{"type": T, "fields": [[name, value], ...]}]}, fields by name, numbers as decimal
// strings, byte arrays as lists of them, maps as objects. As there, a chunk's records stand in
// place of the chunk, and message indexes and private records are left out. A file the reader
// refuses: its error on stderr, exit 1. Built with the tests, not installed.
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "rgbdvo/io/mcap_reader.hpp"

namespace {

std::string Quote(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", static_cast<unsigned>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string Number(uint64_t v) { return Quote(std::to_string(v)); }

std::string Bytes(const std::vector<uint8_t>& bytes) {
  std::string out = "[";
  for (size_t i = 0; i < bytes.size(); ++i) out += (i ? ", " : "") + Number(bytes[i]);
  return out + "]";
}

template <typename Map>
std::string Object(const Map& map) {
  std::string out = "{";
  bool first = true;
  for (const auto& [key, value] : map) {
    if (!first) out += ", ";
    first = false;
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::string>)
      out += Quote(key) + ": " + Quote(value);
    else
      out += Number(key) + ": " + Number(value);
  }
  return out + "}";
}

using Fields = std::vector<std::pair<std::string, std::string>>;

// The record's type name and fields as the suite lists them; an empty name: not listed.
std::pair<std::string, Fields> Describe(const rgbdvo::McapRecord& r) {
  using namespace rgbdvo;
  if (const auto* h = std::get_if<McapHeader>(&r.body))
    return {"Header", {{"library", Quote(h->library)}, {"profile", Quote(h->profile)}}};
  if (const auto* f = std::get_if<McapFooter>(&r.body))
    return {"Footer",
            {{"summary_crc", Number(f->summary_crc)},
             {"summary_offset_start", Number(f->summary_offset_start)},
             {"summary_start", Number(f->summary_start)}}};
  if (const auto* s = std::get_if<McapSchema>(&r.body))
    return {"Schema",
            {{"data", Bytes(s->data)},
             {"encoding", Quote(s->encoding)},
             {"id", Number(s->id)},
             {"name", Quote(s->name)}}};
  if (const auto* c = std::get_if<McapChannel>(&r.body))
    return {"Channel",
            {{"id", Number(c->id)},
             {"message_encoding", Quote(c->message_encoding)},
             {"metadata", Object(c->metadata)},
             {"schema_id", Number(c->schema_id)},
             {"topic", Quote(c->topic)}}};
  if (const auto* m = std::get_if<McapMessage>(&r.body))
    return {"Message",
            {{"channel_id", Number(m->channel_id)},
             {"data", Bytes(m->data)},
             {"log_time", Number(m->log_time)},
             {"publish_time", Number(m->publish_time)},
             {"sequence", Number(m->sequence)}}};
  if (const auto* c = std::get_if<McapChunkIndex>(&r.body))
    return {"ChunkIndex",
            {{"chunk_length", Number(c->chunk_length)},
             {"chunk_start_offset", Number(c->chunk_start_offset)},
             {"compressed_size", Number(c->compressed_size)},
             {"compression", Quote(c->compression)},
             {"message_end_time", Number(c->message_end_time)},
             {"message_index_length", Number(c->message_index_length)},
             {"message_index_offsets", Object(c->message_index_offsets)},
             {"message_start_time", Number(c->message_start_time)},
             {"uncompressed_size", Number(c->uncompressed_size)}}};
  if (const auto* a = std::get_if<McapAttachment>(&r.body))
    return {"Attachment",
            {{"create_time", Number(a->create_time)},
             {"data", Bytes(a->data)},
             {"log_time", Number(a->log_time)},
             {"media_type", Quote(a->media_type)},
             {"name", Quote(a->name)}}};
  if (const auto* a = std::get_if<McapAttachmentIndex>(&r.body))
    return {"AttachmentIndex",
            {{"create_time", Number(a->create_time)},
             {"data_size", Number(a->data_size)},
             {"length", Number(a->length)},
             {"log_time", Number(a->log_time)},
             {"media_type", Quote(a->media_type)},
             {"name", Quote(a->name)},
             {"offset", Number(a->offset)}}};
  if (const auto* s = std::get_if<McapStatistics>(&r.body))
    return {"Statistics",
            {{"attachment_count", Number(s->attachment_count)},
             {"channel_count", Number(s->channel_count)},
             {"channel_message_counts", Object(s->channel_message_counts)},
             {"chunk_count", Number(s->chunk_count)},
             {"message_count", Number(s->message_count)},
             {"message_end_time", Number(s->message_end_time)},
             {"message_start_time", Number(s->message_start_time)},
             {"metadata_count", Number(s->metadata_count)},
             {"schema_count", Number(s->schema_count)}}};
  if (const auto* m = std::get_if<McapMetadata>(&r.body))
    return {"Metadata", {{"metadata", Object(m->metadata)}, {"name", Quote(m->name)}}};
  if (const auto* m = std::get_if<McapMetadataIndex>(&r.body))
    return {
        "MetadataIndex",
        {{"length", Number(m->length)}, {"name", Quote(m->name)}, {"offset", Number(m->offset)}}};
  if (const auto* s = std::get_if<McapSummaryOffset>(&r.body))
    return {"SummaryOffset",
            {{"group_length", Number(s->group_length)},
             {"group_opcode", Number(s->group_opcode)},
             {"group_start", Number(s->group_start)}}};
  if (const auto* d = std::get_if<McapDataEnd>(&r.body))
    return {"DataEnd", {{"data_section_crc", Number(d->data_section_crc)}}};
  return {};  // Chunk, MessageIndex, private records
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: rgbdvo_mcap_dump FILE.mcap\n";
    return 2;
  }
  try {
    rgbdvo::McapReader reader(argv[1]);
    std::ostringstream out;
    out << "{\"records\": [";
    bool first = true;
    while (const std::optional<rgbdvo::McapRecord> r = reader.Next()) {
      const auto [type, fields] = Describe(*r);
      if (type.empty()) continue;
      out << (first ? "\n" : ",\n") << "  {\"type\": " << Quote(type) << ", \"fields\": [";
      first = false;
      for (size_t i = 0; i < fields.size(); ++i)
        out << (i ? ", " : "") << "[" << Quote(fields[i].first) << ", " << fields[i].second << "]";
      out << "]}";
    }
    out << "\n]}\n";
    std::cout << out.str();
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
