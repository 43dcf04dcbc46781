#pragma once
// One RGB-D frame as it flows from a source into the odometry.

#include <opencv2/core.hpp>
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
};

}  // namespace rgbdvo
