#pragma once
// The pixels of ROS 2 image messages as the odometry takes them: colour as CV_8UC3 BGR, depth
// as CV_32FC1 metres (0 = no reading). The depth scale comes from the encoding (REP 118: 16UC1
// millimetres, 32FC1 metres), never from a flag.

#include <opencv2/core.hpp>

#include "rgbdvo/io/ros2_messages.hpp"

namespace rgbdvo {

// rgb8, bgr8, mono8, rgba8, bgra8; compressed: png or jpeg ("png", "jpeg", or image_transport's
// "rgb8; jpeg compressed bgr8").
cv::Mat Ros2ColorImage(const Ros2Image& m);
cv::Mat Ros2ColorImage(const Ros2CompressedImage& m);

// 16UC1 (or mono16) millimetres, 32FC1 metres, either byte order; compressed: image_transport's
// compressedDepth PNG after its 12-byte header (i32 format, two f32 quantisation parameters):
// 16UC1 millimetres as they are, 32FC1 as quantised inverse depth (depth = a / (value - b)).
cv::Mat Ros2DepthImage(const Ros2Image& m);
cv::Mat Ros2DepthImage(const Ros2CompressedImage& m);

// Each throws std::runtime_error with the reason (unknown encoding or format, data shorter than
// height x step, a row shorter than width, an image that does not decode), for the caller to
// prefix with the file, topic and message.

}  // namespace rgbdvo
