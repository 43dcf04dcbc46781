#pragma once
// ROS 2 bags (io/ros2_bag.hpp) of sensor_msgs/msg/Image or CompressedImage, serialised as CDR,
// read without ROS as RosbagSource reads ROS 1 bags: colour and depth paired by their header
// stamps (each colour image with the nearest depth image within the window, NearestPairer),
// the depth scale from the encoding, the camera from camera_info. Streamed message by message:
// the images held are those of the pairing window, and the one pair being decoded.
//
// The bag is read twice: once at opening for its topics (types, counts) and the first
// camera_info of each CameraInfo topic, then for the images; a bag corrupt or cut part way is
// run up to where it breaks, as ROS 1 bags are.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rgbdvo/io/ros2_bag.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame_source.hpp"

namespace rgbdvo {

struct Ros2BagSourceOptions {
  // Image or CompressedImage topics; "": the bag's only image topic whose name has no "depth"
  // (colour), the only one whose name has "depth" (depth).
  std::string rgb_topic, depth_topic;
  // CameraInfo topics; "": the camera_info topic nearest the image topic (beside it, or beside
  // one of its parents: /camera/color/camera_info for /camera/color/image_raw/compressed).
  std::string rgb_info_topic, depth_info_topic;
  double max_time_diff_s = 0.02;  // colour-depth pairing window, s (as TumSourceOptions)
  void Check() const;
};

class Ros2BagSource : public FrameSource {
 public:
  // Opens the bag and chooses the topics. Throws std::runtime_error naming the file and the
  // topic (with the bag's image topics) when a topic is missing, ambiguous, of another type or
  // not CDR.
  Ros2BagSource(const std::string& path, const Ros2BagSourceOptions& options);
  ~Ros2BagSource() override;
  // Throws std::runtime_error naming the file, topic and message for a message of another type,
  // CDR shorter than its lengths, an unknown encoding, colour and depth of different sizes, or
  // a bag that turns out corrupt or cut while reading; and, at the end, when no colour image had
  // a depth image within the window.
  std::optional<Frame> Next() override;
  std::string Describe() const override;

  // The camera from the bag's camera_info (the depth topic's, else the colour topic's): K,
  // plumb_bob distortion, the identity colour->depth mapping of registered depth. nullopt when
  // the bag has neither.
  std::optional<Calibration> CameraInfoCalibration() const;
  int unpaired() const;  // colour images without depth within the window, so far
  const std::vector<Ros2Topic>& topics() const;
  const Ros2BagSourceOptions& chosen() const;  // the options with the topics chosen
  // Why the pass at opening stopped early ("" when it read the whole bag): a bag corrupt or cut
  // part way is run up to that point, where Next throws the same error.
  const std::string& scan_error() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rgbdvo
