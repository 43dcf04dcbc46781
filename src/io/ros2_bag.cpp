#include "rgbdvo/io/ros2_bag.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "rgbdvo/io/mcap_reader.hpp"
#include "rgbdvo/io/rosbag2_sqlite.hpp"
#include "rgbdvo/util/input_file.hpp"

namespace rgbdvo {

namespace fs = std::filesystem;

// One storage file of a bag.
class Ros2BagReader::Storage {
 public:
  virtual ~Storage() = default;
  virtual std::optional<Ros2BagMessage> Next(const std::vector<std::string>& topics) = 0;
  virtual std::vector<Ros2Topic> KnownTopics() const = 0;
};

class Ros2BagReader::McapStorage : public Storage {
 public:
  explicit McapStorage(const std::string& path) : reader_(path) {}
  std::optional<Ros2BagMessage> Next(const std::vector<std::string>& topics) override {
    while (std::optional<McapMessage> m = reader_.NextMessage()) {
      const McapChannel* channel = reader_.Channel(m->channel_id);
      if (!topics.empty() &&
          std::find(topics.begin(), topics.end(), channel->topic) == topics.end())
        continue;
      Ros2BagMessage out;
      out.topic = channel->topic;
      const McapSchema* schema = reader_.Schema(channel->schema_id);
      out.type = schema ? schema->name : "";
      out.serialization = channel->message_encoding;
      out.log_time_ns = m->log_time;
      out.data = std::move(m->data);
      return out;
    }
    return std::nullopt;
  }
  std::vector<Ros2Topic> KnownTopics() const override {
    std::vector<Ros2Topic> topics;
    for (uint32_t id = 0; id <= 0xffff; ++id)
      if (const McapChannel* c = reader_.Channel(static_cast<uint16_t>(id))) {
        const McapSchema* schema = reader_.Schema(c->schema_id);
        topics.push_back({c->topic, schema ? schema->name : "", c->message_encoding});
      }
    return topics;
  }

 private:
  McapReader reader_;
};

class Ros2BagReader::SqliteStorage : public Storage {
 public:
  explicit SqliteStorage(const std::string& path) : reader_(path) {
    for (const Rosbag2SqliteTopic& t : reader_.topics()) by_id_[t.id] = &t;
  }
  std::optional<Ros2BagMessage> Next(const std::vector<std::string>& topics) override {
    Rosbag2SqliteRow row;
    while (reader_.Next(&row)) {
      const auto t = by_id_.find(row.topic_id);
      const std::string name = t == by_id_.end() ? "" : t->second->name;
      if (!topics.empty() && std::find(topics.begin(), topics.end(), name) == topics.end())
        continue;
      Ros2BagMessage out;
      out.topic = name;
      if (t != by_id_.end()) {
        out.type = t->second->type;
        out.serialization = t->second->serialization_format;
      }
      out.log_time_ns = static_cast<uint64_t>(row.timestamp_ns);
      out.data = std::move(row.data);
      return out;
    }
    return std::nullopt;
  }
  std::vector<Ros2Topic> KnownTopics() const override {
    std::vector<Ros2Topic> topics;
    for (const Rosbag2SqliteTopic& t : reader_.topics())
      topics.push_back({t.name, t.type, t.serialization_format});
    return topics;
  }

 private:
  Rosbag2SqliteReader reader_;
  std::map<int64_t, const Rosbag2SqliteTopic*> by_id_;
};

namespace {

bool StartsWith(const std::string& path, const std::string& magic) {
  if (!InputFileSize(path, "bag file")) return false;
  std::ifstream in(path, std::ios::binary);
  std::string head(magic.size(), '\0');
  return in.read(head.data(), static_cast<std::streamsize>(head.size())) && head == magic;
}

const std::string kMcapMagic("\x89MCAP0\r\n", 8);
const std::string kSqliteMagic("SQLite format 3\0", 16);

bool IsMcap(const std::string& file) {
  return StartsWith(file, kMcapMagic) || fs::path(file).extension() == ".mcap";
}

std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(" \t\r");
  std::string t = s.substr(a, b - a + 1);
  if (t.size() >= 2 && (t.front() == '"' || t.front() == '\'') && t.back() == t.front())
    t = t.substr(1, t.size() - 2);
  return t;
}

}  // namespace

double Ros2Topic::RateHz() const {
  return messages > 1 && last_ns > first_ns
             ? static_cast<double>(messages - 1) / (static_cast<double>(last_ns - first_ns) * 1e-9)
             : 0.0;
}

bool IsRos2Bag(const std::string& path) {
  if (fs::is_directory(path)) return fs::is_regular_file(fs::path(path) / "metadata.yaml");
  return IsMcap(path) || StartsWith(path, kSqliteMagic) || fs::path(path).extension() == ".db3";
}

std::vector<std::string> Ros2BagFiles(const std::string& path) {
  if (!fs::is_directory(path)) return {path};
  const fs::path metadata = fs::path(path) / "metadata.yaml";
  std::ifstream in(metadata);
  if (!in) throw std::runtime_error(metadata.string() + ": cannot be read");
  // Only the block list under relative_file_paths: is read; rosbag2 writes it in recording
  // order, which file names need not sort to (_10 before _2).
  std::vector<std::string> files;
  bool in_list = false;
  for (std::string line; std::getline(in, line);) {
    const std::string t = Trim(line);
    if (t == "relative_file_paths:") {
      in_list = true;
      continue;
    }
    if (!in_list) continue;
    if (t.rfind("- ", 0) != 0) break;
    const std::string name = Trim(t.substr(2));
    const std::string extension = fs::path(name).extension().string();
    if (extension != ".mcap" && extension != ".db3")
      throw std::runtime_error(metadata.string() + ": split file " + name +
                               " is neither .mcap nor .db3 (a compressed bag? decompress it "
                               "with `ros2 bag convert` first)");
    files.push_back((fs::path(path) / name).string());
  }
  if (files.empty())
    throw std::runtime_error(metadata.string() +
                             ": no relative_file_paths list naming the bag's files");
  return files;
}

std::unique_ptr<Ros2BagReader::Storage> Ros2BagReader::Open(const std::string& file) {
  if (IsMcap(file)) return std::make_unique<McapStorage>(file);
  return std::make_unique<SqliteStorage>(file);
}

Ros2BagReader::Ros2BagReader(const std::string& path, std::vector<std::string> topics)
    : files_(Ros2BagFiles(path)), topics_(std::move(topics)) {
  storage_ = Open(files_[next_file_++]);
}

Ros2BagReader::~Ros2BagReader() = default;

std::optional<Ros2BagMessage> Ros2BagReader::Next() {
  while (storage_) {
    if (std::optional<Ros2BagMessage> m = storage_->Next(topics_)) return m;
    for (Ros2Topic& t : storage_->KnownTopics()) known_.push_back(std::move(t));
    storage_.reset();
    if (next_file_ < files_.size()) storage_ = Open(files_[next_file_++]);
  }
  return std::nullopt;
}

std::vector<Ros2Topic> Ros2BagReader::KnownTopics() const {
  std::vector<Ros2Topic> topics = known_;
  if (storage_)
    for (Ros2Topic& t : storage_->KnownTopics()) topics.push_back(std::move(t));
  return topics;
}

std::vector<Ros2Topic> ListRos2Topics(const std::string& path,
                                      const std::function<void(const Ros2BagMessage&)>& each,
                                      std::string* error) {
  Ros2BagReader reader(path);
  std::map<std::string, Ros2Topic> topics;
  const auto next = [&reader, error]() -> std::optional<Ros2BagMessage> {
    if (!error) return reader.Next();
    try {
      return reader.Next();
    } catch (const std::runtime_error& e) {
      *error = e.what();
      return std::nullopt;
    }
  };
  while (std::optional<Ros2BagMessage> m = next()) {
    Ros2Topic& t = topics[m->topic];
    if (t.messages == 0) {
      t.name = m->topic, t.type = m->type, t.serialization = m->serialization;
      t.first_ns = t.last_ns = m->log_time_ns;
    }
    ++t.messages;
    t.first_ns = std::min(t.first_ns, m->log_time_ns);
    t.last_ns = std::max(t.last_ns, m->log_time_ns);
    if (each) each(*m);
  }
  for (const Ros2Topic& t : reader.KnownTopics())
    if (topics.count(t.name) == 0) topics[t.name] = t;
  std::vector<Ros2Topic> list;
  list.reserve(topics.size());
  for (auto& [name, t] : topics) list.push_back(t);
  return list;
}

}  // namespace rgbdvo
