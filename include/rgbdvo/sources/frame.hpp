#pragma once
// One RGB-D frame as it flows from a source into the odometry.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace rgbdvo {

struct Frame {
  int index = 0;  // 0-based position in the sequence as delivered
  // Seconds (source clock): the time of the depth image. The colour image may have been taken a
  // little earlier or later; the odometry lifts its keypoints across the difference and stamps
  // the pose with the colour image's time (FrameResult::timestamp).
  double timestamp = 0;
  double color_timestamp = 0;  // seconds, the colour image's time
  cv::Mat bgr;                 // CV_8UC3 colour image
  cv::Mat depth_m;             // CV_32FC1 depth in the IR image, metres along Z; 0 = no reading
  std::string name;            // colour file or device frame name, for messages
  // The accelerometer's apparent gravity (g - a) in the colour camera's frame at the colour
  // image's time, m/s^2 (kinect_accelerometer.hpp); empty when none was read.
  std::optional<Eigen::Vector3d> gravity_in_cam;
};

}  // namespace rgbdvo
