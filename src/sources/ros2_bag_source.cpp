#include "rgbdvo/sources/ros2_bag_source.hpp"

#include <algorithm>
#include <cctype>
#include <deque>
#include <map>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/io/ros2_messages.hpp"
#include "rgbdvo/sources/nearest_pairer.hpp"
#include "rgbdvo/sources/ros2_image.hpp"

namespace rgbdvo {
namespace {

using MessagePtr = std::shared_ptr<const Ros2BagMessage>;

bool IsImageType(const std::string& type) {
  return type == kRos2ImageType || type == kRos2CompressedImageType;
}

bool NamesDepth(const std::string& topic) {
  std::string lower = topic;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("depth") != std::string::npos;
}

std::string TopicList(const std::vector<Ros2Topic>& topics) {
  std::string list;
  for (const Ros2Topic& t : topics)
    list += (list.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
  return list.empty() ? "none" : list;
}

std::string Stamped(const std::string& topic, double stamp_s) {
  std::ostringstream s;
  s.precision(17);
  s << "topic " << topic << ", message stamped " << stamp_s;
  return s.str();
}

}  // namespace

void Ros2BagSourceOptions::Check() const {
  if (!(max_time_diff_s > 0))
    throw std::invalid_argument("Ros2BagSourceOptions.max_time_diff_s must be > 0");
}

struct Ros2BagSource::Impl {
  std::string path;
  Ros2BagSourceOptions options;
  std::vector<Ros2Topic> topics;
  std::map<std::string, std::vector<uint8_t>> first_camera_info;  // by topic
  std::unique_ptr<Ros2BagReader> reader;
  NearestPairer<MessagePtr> pairer{0.02};
  std::deque<TimedPair<MessagePtr>> ready;
  uint64_t color_messages = 0, depth_messages = 0;
  std::optional<Calibration> calib;
  std::string scan_error;  // where the first pass found the bag corrupt or cut
  int next_index = 0;
  bool finished = false;

  const Ros2Topic* Find(const std::string& name) const {
    for (const Ros2Topic& t : topics)
      if (t.name == name) return &t;
    return nullptr;
  }

  // The topic given, or the only image topic whose name has (depth) or lacks (colour) "depth";
  // checked to hold CDR images.
  std::string Choose(const std::string& given, bool depth, const char* role, const char* flag) {
    std::string name = given;
    if (name.empty()) {
      std::vector<std::string> candidates;
      for (const Ros2Topic& t : topics)
        if (IsImageType(t.type) && NamesDepth(t.name) == depth) candidates.push_back(t.name);
      if (candidates.size() != 1)
        throw std::runtime_error(path + ": " + std::to_string(candidates.size()) + " " + role +
                                 " image topics, so none chosen: give one with " + flag +
                                 " (topics in the bag: " + TopicList(topics) + ")");
      name = candidates.front();
    }
    const Ros2Topic* t = Find(name);
    if (t == nullptr || t->messages == 0)
      throw std::runtime_error(path + ": no " + role + " messages on " + name +
                               " (topics in the bag: " + TopicList(topics) + ")");
    if (!IsImageType(t->type))
      throw std::runtime_error(path + ": " + role + " topic " + name + " is " + t->type +
                               ", expected " + kRos2ImageType + " or " + kRos2CompressedImageType);
    if (t->serialization != "cdr")
      throw std::runtime_error(path + ": " + role + " topic " + name + " is serialised as '" +
                               t->serialization + "', expected cdr");
    return name;
  }

  // The camera_info topic given, or the one beside the image topic or one of its parents.
  std::string InfoTopic(const std::string& given, const std::string& image_topic) const {
    if (!given.empty()) return given;
    for (std::string prefix = image_topic; !prefix.empty();) {
      const size_t slash = prefix.rfind('/');
      if (slash == std::string::npos) break;
      prefix.resize(slash);
      std::string candidate = prefix + "/camera_info";
      if (first_camera_info.count(candidate) > 0) return candidate;
    }
    return "";
  }

  void ReadCameraInfo() {
    for (const std::string& topic : {options.depth_info_topic, options.rgb_info_topic}) {
      const auto bytes = first_camera_info.find(topic);
      if (topic.empty() || bytes == first_camera_info.end()) continue;
      Ros2CameraInfo info;
      try {
        info = DecodeRos2CameraInfo(bytes->second.data(), bytes->second.size());
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(path + ": topic " + topic + ", first message: " + e.what());
      }
      if (!(info.k[0] > 0) || !(info.k[4] > 0)) continue;
      Calibration c;
      c.fx = info.k[0], c.fy = info.k[4], c.cx = info.k[2], c.cy = info.k[5];
      if (info.distortion_model == "plumb_bob" || info.distortion_model == "rational_polynomial")
        for (size_t i = 0; i < std::min<size_t>(5, info.d.size()); ++i) c.dist_ir[i] = info.d[i];
      c.description = "from " + topic + " in " + path;
      calib = c;
      return;
    }
  }

  // Reads messages until a pair is decided or the bag ends.
  void Fill() {
    while (ready.empty() && !finished) {
      std::optional<Ros2BagMessage> m = reader->Next();
      if (!m) {
        finished = true;
        for (auto& p : pairer.Take(true)) ready.push_back(std::move(p));
        break;
      }
      const bool color = m->topic == options.rgb_topic;
      const Ros2Topic* topic = Find(m->topic);
      const std::string expected = topic ? topic->type : "";
      if (m->type != expected || m->serialization != "cdr")
        throw std::runtime_error(path + ": topic " + m->topic + ": a message of type " + m->type +
                                 " (" + m->serialization + "), expected " + expected + " (cdr)");
      double stamp = 0;
      try {
        stamp = DecodeRos2Header(m->data.data(), m->data.size(), m->type).Seconds();
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(path + ": topic " + m->topic + ", message logged at " +
                                 std::to_string(m->log_time_ns) + " ns: " + e.what());
      }
      auto message = std::make_shared<const Ros2BagMessage>(std::move(*m));
      if (color)
        pairer.AddColor(stamp, std::move(message));
      else
        pairer.AddDepth(stamp, std::move(message));
      for (auto& p : pairer.Take(false)) ready.push_back(std::move(p));
    }
  }

  // The message's pixels (colour BGR or depth metres); throws naming the file, topic, stamp.
  cv::Mat Decode(const Ros2BagMessage& m, double stamp, bool color) const {
    try {
      if (m.type == kRos2ImageType) {
        const Ros2Image image = DecodeRos2Image(m.data.data(), m.data.size());
        return color ? Ros2ColorImage(image) : Ros2DepthImage(image);
      }
      const Ros2CompressedImage image = DecodeRos2CompressedImage(m.data.data(), m.data.size());
      return color ? Ros2ColorImage(image) : Ros2DepthImage(image);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(path + ": " + Stamped(m.topic, stamp) + ": " + e.what());
    }
  }
};

Ros2BagSource::Ros2BagSource(const std::string& path, const Ros2BagSourceOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.Check();
  Impl& s = *impl_;
  s.path = path;
  s.options = options;
  s.pairer = NearestPairer<MessagePtr>(options.max_time_diff_s);
  s.topics = ListRos2Topics(
      path,
      [&s](const Ros2BagMessage& m) {
        if (m.type == kRos2CameraInfoType && s.first_camera_info.count(m.topic) == 0)
          s.first_camera_info[m.topic] = m.data;
      },
      &s.scan_error);
  s.options.rgb_topic = s.Choose(options.rgb_topic, false, "colour", "--rgb-topic");
  s.options.depth_topic = s.Choose(options.depth_topic, true, "depth", "--depth-topic");
  s.color_messages = s.Find(s.options.rgb_topic)->messages;
  s.depth_messages = s.Find(s.options.depth_topic)->messages;
  s.options.rgb_info_topic = s.InfoTopic(options.rgb_info_topic, s.options.rgb_topic);
  s.options.depth_info_topic = s.InfoTopic(options.depth_info_topic, s.options.depth_topic);
  s.ReadCameraInfo();
  s.reader = std::make_unique<Ros2BagReader>(
      path, std::vector<std::string>{s.options.rgb_topic, s.options.depth_topic});
}

Ros2BagSource::~Ros2BagSource() = default;

std::optional<Frame> Ros2BagSource::Next() {
  Impl& s = *impl_;
  s.Fill();
  if (s.ready.empty()) {
    if (s.next_index == 0)
      throw std::runtime_error(s.path + ": no colour image on " + s.options.rgb_topic +
                               " has a depth image on " + s.options.depth_topic + " within " +
                               std::to_string(s.options.max_time_diff_s) + " s (" +
                               std::to_string(s.color_messages) + " colour, " +
                               std::to_string(s.depth_messages) + " depth messages)");
    return std::nullopt;
  }
  const TimedPair<MessagePtr> p = std::move(s.ready.front());
  s.ready.pop_front();
  Frame f;
  f.index = s.next_index;
  f.timestamp = p.depth_s;
  f.color_timestamp = p.color_s;
  f.bgr = s.Decode(*p.color, p.color_s, true);
  f.depth_m = s.Decode(*p.depth, p.depth_s, false);
  if (f.depth_m.size() != f.bgr.size())
    throw std::runtime_error(s.path + ": " + Stamped(s.options.depth_topic, p.depth_s) +
                             ": depth image is " + std::to_string(f.depth_m.cols) + "x" +
                             std::to_string(f.depth_m.rows) + " but the colour image is " +
                             std::to_string(f.bgr.cols) + "x" + std::to_string(f.bgr.rows));
  std::ostringstream name;
  name.precision(17);
  name << s.options.rgb_topic << "@" << p.color_s;
  f.name = name.str();
  ++s.next_index;
  return f;
}

std::string Ros2BagSource::Describe() const {
  const Impl& s = *impl_;
  std::ostringstream d;
  d << "ROS 2 bag " << s.path << ": colour " << s.options.rgb_topic << " ("
    << s.Find(s.options.rgb_topic)->type << ", " << s.color_messages << " messages), depth "
    << s.options.depth_topic << " (" << s.Find(s.options.depth_topic)->type << ", "
    << s.depth_messages << " messages, scale from the encoding: 16UC1 mm, 32FC1 m), paired within "
    << s.options.max_time_diff_s << " s";
  return d.str();
}

std::optional<Calibration> Ros2BagSource::CameraInfoCalibration() const { return impl_->calib; }

int Ros2BagSource::unpaired() const { return impl_->pairer.unpaired(); }

const std::string& Ros2BagSource::scan_error() const { return impl_->scan_error; }

const std::vector<Ros2Topic>& Ros2BagSource::topics() const { return impl_->topics; }

const Ros2BagSourceOptions& Ros2BagSource::chosen() const { return impl_->options; }

}  // namespace rgbdvo
