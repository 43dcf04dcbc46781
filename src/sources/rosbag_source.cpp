#include "rgbdvo/sources/rosbag_source.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <algorithm>
#include <deque>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/sources/nearest_pairer.hpp"

namespace rgbdvo {
namespace {

using ImagePtr = sensor_msgs::Image::ConstPtr;

void OpenBag(rosbag::Bag* bag, const std::string& path) {
  try {
    bag->open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(
        path + ": not a readable ROS 1 bag (" + e.what() +
        "; a truncated bag can be repaired with `rosbag reindex`, Debian package python3-rosbag)");
  }
}

std::string TopicList(rosbag::View&& view) {
  std::string list;
  for (const rosbag::ConnectionInfo* c : view.getConnections())
    list += (list.empty() ? "" : ", ") + c->topic + " (" + c->datatype + ")";
  return list.empty() ? "none" : list;
}

// What is wrong with an image message's layout, or "" when its data fills height x step with
// rows of width x bytes_per_pixel.
std::string LayoutError(const sensor_msgs::Image& m, size_t bytes_per_pixel) {
  if (m.width == 0 || m.height == 0) return "empty image";
  if (m.is_bigendian && bytes_per_pixel > 1) return "big-endian data is not supported";
  if (m.step < static_cast<size_t>(m.width) * bytes_per_pixel)
    return "step " + std::to_string(m.step) + " is shorter than a row";
  if (m.data.size() < static_cast<size_t>(m.step) * m.height)
    return "data has " + std::to_string(m.data.size()) + " bytes, " +
           std::to_string(static_cast<size_t>(m.step) * m.height) + " expected";
  return "";
}

// A view of the message's pixels (no copy; valid while the message lives).
cv::Mat Pixels(const sensor_msgs::Image& m, int type) {
  return cv::Mat(static_cast<int>(m.height), static_cast<int>(m.width), type,
                 const_cast<uint8_t*>(m.data.data()), m.step);
}

std::string Where(const std::string& topic, const sensor_msgs::Image& m) {
  std::ostringstream s;
  s.precision(17);
  s << "topic " << topic << ", message stamped " << m.header.stamp.toSec();
  return s.str();
}

// CV_8UC3 BGR from rgb8, bgr8, mono8, rgba8 or bgra8.
cv::Mat DecodeColor(const sensor_msgs::Image& m, const std::string& topic) {
  static const std::map<std::string, std::pair<int, int>> kLayouts = {
      {"rgb8", {CV_8UC3, cv::COLOR_RGB2BGR}},   {"bgr8", {CV_8UC3, -1}},
      {"mono8", {CV_8UC1, cv::COLOR_GRAY2BGR}}, {"rgba8", {CV_8UC4, cv::COLOR_RGBA2BGR}},
      {"bgra8", {CV_8UC4, cv::COLOR_BGRA2BGR}},
  };
  const auto layout = kLayouts.find(m.encoding);
  if (layout == kLayouts.end())
    throw std::runtime_error(Where(topic, m) + ": colour encoding '" + m.encoding +
                             "' not supported (rgb8, bgr8, mono8, rgba8, bgra8)");
  const auto [type, conversion] = layout->second;
  if (const std::string e = LayoutError(m, CV_ELEM_SIZE(type)); !e.empty())
    throw std::runtime_error(Where(topic, m) + ": " + e);
  cv::Mat bgr;
  if (conversion < 0)
    Pixels(m, type).copyTo(bgr);
  else
    cv::cvtColor(Pixels(m, type), bgr, conversion);
  return bgr;
}

// CV_32FC1 metres (0 = no reading) from 16UC1 millimetres or 32FC1 metres (REP 118: NaN and
// 0 mean no reading).
cv::Mat DecodeDepth(const sensor_msgs::Image& m, const std::string& topic) {
  const bool mm = m.encoding == "16UC1" || m.encoding == "mono16";
  if (!mm && m.encoding != "32FC1")
    throw std::runtime_error(Where(topic, m) + ": depth encoding '" + m.encoding +
                             "' not supported (16UC1 millimetres, 32FC1 metres)");
  const int type = mm ? CV_16UC1 : CV_32FC1;
  if (const std::string e = LayoutError(m, CV_ELEM_SIZE(type)); !e.empty())
    throw std::runtime_error(Where(topic, m) + ": " + e);
  cv::Mat depth;
  Pixels(m, type).convertTo(depth, CV_32F, mm ? 1e-3 : 1.0);
  cv::patchNaNs(depth, 0);
  depth.setTo(0, depth < 0);
  return depth;
}

}  // namespace

void RosbagSourceOptions::Check() const {
  if (!(max_time_diff_s > 0))
    throw std::invalid_argument("RosbagSourceOptions.max_time_diff_s must be > 0");
  if (rgb_topic.empty() || depth_topic.empty())
    throw std::invalid_argument("RosbagSourceOptions.rgb_topic and depth_topic must be given");
}

double BagTopic::RateHz() const {
  return messages > 1 && last_s > first_s ? static_cast<double>(messages - 1) / (last_s - first_s)
                                          : 0.0;
}

std::vector<BagTopic> ListBagTopics(const std::string& path) {
  rosbag::Bag bag;
  OpenBag(&bag, path);
  std::map<std::string, BagTopic> topics;
  for (const rosbag::ConnectionInfo* c : rosbag::View(bag).getConnections()) {
    BagTopic& t = topics[c->topic];
    t.topic = c->topic;
    t.type = c->datatype;
  }
  for (auto& [name, t] : topics) {
    rosbag::View view(bag, rosbag::TopicQuery(name));
    t.messages = view.size();
    if (t.messages > 0)
      t.first_s = view.getBeginTime().toSec(), t.last_s = view.getEndTime().toSec();
  }
  std::vector<BagTopic> list;
  list.reserve(topics.size());
  for (auto& [name, t] : topics) list.push_back(t);
  return list;
}

struct RosbagSource::Impl {
  std::string path;
  RosbagSourceOptions options;
  rosbag::Bag bag;
  std::unique_ptr<rosbag::View> view;
  rosbag::View::iterator it;
  NearestPairer<ImagePtr> pairer;
  std::deque<TimedPair<ImagePtr>> ready;
  size_t color_messages = 0, depth_messages = 0;
  std::optional<Calibration> calib;
  int next_index = 0;
  bool finished = false;

  Impl(const std::string& p, const RosbagSourceOptions& o) : path(p), options(o), pairer(0) {}

  // The number of messages on `topic`; throws when it is missing or not of `type`.
  size_t CheckTopic(const std::string& topic, const std::string& type, const char* role) {
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    for (const rosbag::ConnectionInfo* c : view.getConnections())
      if (c->datatype != type)
        throw std::runtime_error(path + ": " + role + " topic " + topic + " is " + c->datatype +
                                 ", expected " + type);
    if (view.size() == 0)
      throw std::runtime_error(path + ": no " + role + " messages on " + topic +
                               " (topics in the bag: " + TopicList(rosbag::View(bag)) + ")");
    return view.size();
  }

  void ReadCameraInfo() {
    for (const std::string& topic : {options.depth_info_topic, options.rgb_info_topic}) {
      if (topic.empty()) continue;
      rosbag::View view(bag, rosbag::TopicQuery(topic));
      for (const rosbag::MessageInstance& m : view) {
        const sensor_msgs::CameraInfo::ConstPtr info = m.instantiate<sensor_msgs::CameraInfo>();
        if (!info || !(info->K[0] > 0) || !(info->K[4] > 0)) break;
        Calibration c;
        c.fx = info->K[0], c.fy = info->K[4], c.cx = info->K[2], c.cy = info->K[5];
        if (info->distortion_model == "plumb_bob" ||
            info->distortion_model == "rational_polynomial")
          for (size_t i = 0; i < std::min<size_t>(5, info->D.size()); ++i)
            c.dist_ir[i] = info->D[i];
        c.description = "from " + topic + " in " + path;
        calib = c;
        return;
      }
    }
  }

  // Reads messages until a pair is decided or the bag ends.
  void Fill() {
    while (ready.empty() && !finished) {
      try {
        if (it == view->end()) {
          finished = true;
          for (auto& p : pairer.Take(true)) ready.push_back(std::move(p));
          break;
        }
        const ImagePtr image = it->instantiate<sensor_msgs::Image>();
        const std::string& topic = it->getTopic();
        ++it;
        if (!image) continue;
        if (topic == options.rgb_topic)
          pairer.AddColor(image->header.stamp.toSec(), image);
        else
          pairer.AddDepth(image->header.stamp.toSec(), image);
      } catch (const rosbag::BagException& e) {
        throw std::runtime_error(path + ": corrupt or truncated bag after " +
                                 std::to_string(next_index) + " frames (" + e.what() + ")");
      }
      for (auto& p : pairer.Take(false)) ready.push_back(std::move(p));
    }
  }
};

RosbagSource::RosbagSource(const std::string& path, const RosbagSourceOptions& options)
    : impl_(std::make_unique<Impl>(path, options)) {
  options.Check();
  impl_->pairer = NearestPairer<ImagePtr>(options.max_time_diff_s);
  OpenBag(&impl_->bag, path);
  impl_->color_messages = impl_->CheckTopic(options.rgb_topic, "sensor_msgs/Image", "colour");
  impl_->depth_messages = impl_->CheckTopic(options.depth_topic, "sensor_msgs/Image", "depth");
  impl_->ReadCameraInfo();
  impl_->view = std::make_unique<rosbag::View>(
      impl_->bag,
      rosbag::TopicQuery(std::vector<std::string>{options.rgb_topic, options.depth_topic}));
  impl_->it = impl_->view->begin();
}

RosbagSource::~RosbagSource() = default;

std::optional<Frame> RosbagSource::Next() {
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
  const TimedPair<ImagePtr> p = std::move(s.ready.front());
  s.ready.pop_front();
  Frame f;
  f.index = s.next_index;
  f.timestamp = p.depth_s;
  f.color_timestamp = p.color_s;
  f.bgr = DecodeColor(*p.color, s.options.rgb_topic);
  f.depth_m = DecodeDepth(*p.depth, s.options.depth_topic);
  if (f.depth_m.size() != f.bgr.size())
    throw std::runtime_error(Where(s.options.depth_topic, *p.depth) + ": depth image is " +
                             std::to_string(f.depth_m.cols) + "x" + std::to_string(f.depth_m.rows) +
                             " but the colour image is " + std::to_string(f.bgr.cols) + "x" +
                             std::to_string(f.bgr.rows));
  std::ostringstream name;
  name.precision(17);
  name << s.options.rgb_topic << "@" << p.color_s;
  f.name = name.str();
  ++s.next_index;
  return f;
}

std::string RosbagSource::Describe() const {
  const Impl& s = *impl_;
  std::ostringstream d;
  d << "ROS bag " << s.path << ": colour " << s.options.rgb_topic << " (" << s.color_messages
    << " messages), depth " << s.options.depth_topic << " (" << s.depth_messages
    << " messages, scale from the encoding: 16UC1 mm, 32FC1 m), paired within "
    << s.options.max_time_diff_s << " s";
  return d.str();
}

std::optional<Calibration> RosbagSource::CameraInfoCalibration() const { return impl_->calib; }

int RosbagSource::unpaired() const { return impl_->pairer.unpaired(); }

}  // namespace rgbdvo
