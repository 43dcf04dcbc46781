#include "rgbdvo/sources/tum_to_ros2.hpp"

#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

#include "rgbdvo/io/mcap_writer.hpp"
#include "rgbdvo/io/ros2_messages.hpp"
#include "rgbdvo/io/rosbag2_sqlite.hpp"
#include "rgbdvo/sources/tum_source.hpp"

namespace rgbdvo {
namespace {

constexpr const char* kColorTopic = "/camera/rgb/image_color";
constexpr const char* kDepthTopic = "/camera/depth/image";
constexpr const char* kColorInfoTopic = "/camera/rgb/camera_info";
constexpr const char* kDepthInfoTopic = "/camera/depth/camera_info";

// The bag being written, whatever its storage.
class BagOut {
 public:
  virtual ~BagOut() = default;
  virtual int AddTopic(const std::string& topic, const std::string& type) = 0;
  virtual void Write(int topic, uint64_t time_ns, const std::vector<uint8_t>& data) = 0;
  virtual void Close() = 0;
};

class McapOut : public BagOut {
 public:
  McapOut(const std::string& path, const std::string& compression)
      : writer_(path, McapWriterOptions{compression, uint64_t{1} << 20}) {}
  int AddTopic(const std::string& topic, const std::string& type) override {
    return writer_.AddChannel(topic, type);
  }
  void Write(int topic, uint64_t time_ns, const std::vector<uint8_t>& data) override {
    writer_.Write(static_cast<uint16_t>(topic), time_ns, data);
  }
  void Close() override { writer_.Close(); }

 private:
  McapWriter writer_;
};

class SqliteOut : public BagOut {
 public:
  explicit SqliteOut(const std::string& path) : writer_(path) {}
  int AddTopic(const std::string& topic, const std::string& type) override {
    return static_cast<int>(writer_.AddTopic(topic, type));
  }
  void Write(int topic, uint64_t time_ns, const std::vector<uint8_t>& data) override {
    writer_.Write(topic, static_cast<int64_t>(time_ns), data);
  }
  void Close() override { writer_.Close(); }

 private:
  Rosbag2SqliteWriter writer_;
};

Ros2Header HeaderAt(double t, const std::string& frame) {
  Ros2Header h;
  h.sec = static_cast<int32_t>(std::floor(t));
  h.nanosec = static_cast<uint32_t>(std::llround((t - std::floor(t)) * 1e9));
  if (h.nanosec >= 1000000000u) ++h.sec, h.nanosec -= 1000000000u;
  h.frame_id = frame;
  return h;
}

uint64_t Nanoseconds(const Ros2Header& h) {
  return static_cast<uint64_t>(h.sec) * 1000000000u + h.nanosec;
}

Ros2Image ImageMessage(const cv::Mat& pixels, const std::string& encoding, const Ros2Header& h) {
  Ros2Image m;
  m.header = h;
  m.height = static_cast<uint32_t>(pixels.rows);
  m.width = static_cast<uint32_t>(pixels.cols);
  m.encoding = encoding;
  m.step = static_cast<uint32_t>(pixels.cols * pixels.elemSize());
  const cv::Mat packed = pixels.isContinuous() ? pixels : pixels.clone();
  m.data.assign(packed.datastart, packed.dataend);
  return m;
}

}  // namespace

void TumToRos2Options::Check() const {
  if (storage != "mcap" && storage != "sqlite3")
    throw std::invalid_argument("TumToRos2Options.storage must be mcap or sqlite3, not '" +
                                storage + "'");
  if (depth_encoding != "32FC1" && depth_encoding != "16UC1")
    throw std::invalid_argument("TumToRos2Options.depth_encoding must be 32FC1 or 16UC1, not '" +
                                depth_encoding + "'");
  McapWriterOptions{compression, 1}.Check();
  if (!(fx > 0) || !(fy > 0)) throw std::invalid_argument("TumToRos2Options.fx and fy must be > 0");
}

size_t WriteTumAsRos2Bag(const std::string& folder, const std::string& out,
                         const TumToRos2Options& options) {
  options.Check();
  TumSource source(folder, TumSourceOptions());
  std::unique_ptr<BagOut> bag;
  if (options.storage == "sqlite3")
    bag = std::make_unique<SqliteOut>(out);
  else
    bag = std::make_unique<McapOut>(out, options.compression);
  const int color_topic = bag->AddTopic(kColorTopic, kRos2ImageType);
  const int depth_topic = bag->AddTopic(kDepthTopic, kRos2ImageType);
  int color_info_topic = -1, depth_info_topic = -1;
  Ros2CameraInfo info;
  if (options.camera_info) {
    color_info_topic = bag->AddTopic(kColorInfoTopic, kRos2CameraInfoType);
    depth_info_topic = bag->AddTopic(kDepthInfoTopic, kRos2CameraInfoType);
    info.width = 640, info.height = 480, info.distortion_model = "plumb_bob";
    info.d = {0, 0, 0, 0, 0};
    info.k = {options.fx, 0, options.cx, 0, options.fy, options.cy, 0, 0, 1};
    info.r = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    info.p = {options.fx, 0, options.cx, 0, 0, options.fy, options.cy, 0, 0, 0, 1, 0};
  }
  for (size_t i = 0; i < options.first; ++i)
    if (!source.Skip()) break;
  size_t written = 0;
  while (written < options.count) {
    const std::optional<Frame> f = source.Next();
    if (!f) break;
    const Ros2Header color_header = HeaderAt(f->color_timestamp, "rgb");
    const Ros2Header depth_header = HeaderAt(f->timestamp, "depth");
    cv::Mat rgb, depth = f->depth_m;
    cv::cvtColor(f->bgr, rgb, cv::COLOR_BGR2RGB);
    if (options.depth_encoding == "16UC1") f->depth_m.convertTo(depth, CV_16U, 1000.0);
    const std::vector<uint8_t> color = EncodeRos2Image(ImageMessage(rgb, "rgb8", color_header));
    const std::vector<uint8_t> depth_message =
        EncodeRos2Image(ImageMessage(depth, options.depth_encoding, depth_header));
    if (options.camera_info) {
      info.header = color_header;
      const std::vector<uint8_t> bytes = EncodeRos2CameraInfo(info);
      bag->Write(color_info_topic, Nanoseconds(color_header), bytes);
      bag->Write(depth_info_topic, Nanoseconds(color_header), bytes);
    }
    // In stamp order, as a recorder receives them.
    const bool color_first = Nanoseconds(color_header) <= Nanoseconds(depth_header);
    const auto write_color = [&] { bag->Write(color_topic, Nanoseconds(color_header), color); };
    const auto write_depth = [&] {
      bag->Write(depth_topic, Nanoseconds(depth_header), depth_message);
    };
    if (color_first)
      write_color(), write_depth();
    else
      write_depth(), write_color();
    ++written;
  }
  bag->Close();
  return written;
}

}  // namespace rgbdvo
