#include "rgbdvo/io/ros2_bag.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "rgbdvo/io/mcap_reader.hpp"

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

double Ros2Topic::RateHz() const {
  return messages > 1 && last_ns > first_ns
             ? static_cast<double>(messages - 1) / (static_cast<double>(last_ns - first_ns) * 1e-9)
             : 0.0;
}

bool IsRos2Bag(const std::string& path) {
  if (fs::is_directory(path)) return false;
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> magic{};
  if (in.read(magic.data(), magic.size()) &&
      std::string(magic.data(), magic.size()) == std::string("\x89MCAP0\r\n", 8))
    return true;
  return fs::path(path).extension() == ".mcap";
}

Ros2BagReader::Ros2BagReader(const std::string& path, std::vector<std::string> topics)
    : storage_(std::make_unique<McapStorage>(path)), topics_(std::move(topics)) {}

Ros2BagReader::~Ros2BagReader() = default;

std::optional<Ros2BagMessage> Ros2BagReader::Next() { return storage_->Next(topics_); }

std::vector<Ros2Topic> Ros2BagReader::KnownTopics() const { return storage_->KnownTopics(); }

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
