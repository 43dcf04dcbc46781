#pragma once
// ROS 1 bags of sensor_msgs/Image, as robots record them and as the TUM RGB-D benchmark ships
// every sequence (colour rgb8 on /camera/rgb/image_color, depth 32FC1 metres on
// /camera/depth/image, sensor_msgs/CameraInfo beside each). Read with ROS's own bag storage
// library (Debian's librosbag-storage-dev: no ROS install, no roscore), streamed message by
// message, so a bag of any length needs the memory of a few frames. Built with
// RGBDVO_WITH_ROSBAG into the library rgbdvo_rosbag.
//
// The depth scale comes from the data: 16UC1 is millimetres, 32FC1 metres (REP 118), never a
// flag. Colour and depth are paired by their header stamps as TumSource pairs a folder's lists
// (each colour image with the nearest depth image within the window), so a bag and the folder
// made from the same recording give the same frames.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame_source.hpp"

namespace rgbdvo {

struct RosbagSourceOptions {
  std::string rgb_topic = "/camera/rgb/image_color";           // sensor_msgs/Image
  std::string depth_topic = "/camera/depth/image";             // sensor_msgs/Image
  std::string rgb_info_topic = "/camera/rgb/camera_info";      // sensor_msgs/CameraInfo
  std::string depth_info_topic = "/camera/depth/camera_info";  // sensor_msgs/CameraInfo
  double max_time_diff_s = 0.02;  // colour-depth pairing window, s (as TumSourceOptions)
  void Check() const;
};

// One topic of a bag, for `rgbdvo info`.
struct BagTopic {
  std::string topic, type;
  size_t messages = 0;
  double first_s = 0, last_s = 0;  // bag (record) times
  double RateHz() const;           // 0 with fewer than two messages
};

// The topics of the bag at `path`, by name. Throws std::runtime_error naming the file when it
// is not a readable ROS 1 bag (missing, truncated, corrupt).
std::vector<BagTopic> ListBagTopics(const std::string& path);

class RosbagSource : public FrameSource {
 public:
  // Opens the bag and checks that both image topics exist with type sensor_msgs/Image. Throws
  // std::runtime_error naming the file and topic (and the topics the bag has) otherwise.
  RosbagSource(const std::string& path, const RosbagSourceOptions& options);
  ~RosbagSource() override;
  // Throws std::runtime_error naming the topic and message for an unknown encoding, a message
  // whose data does not fill its size, colour and depth of different sizes, or a bag that turns
  // out corrupt or truncated while reading; and, at the end, when no colour image had a depth
  // image within the window.
  std::optional<Frame> Next() override;
  std::string Describe() const override;

  // The camera from the bag's camera_info messages (the depth topic's, else the colour
  // topic's): K, plumb_bob distortion, the identity colour->depth mapping of registered depth,
  // depth scale 0 (the encoding gives it). nullopt when the bag has neither.
  std::optional<Calibration> CameraInfoCalibration() const;
  int unpaired() const;  // colour images without depth within the window, so far

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rgbdvo
