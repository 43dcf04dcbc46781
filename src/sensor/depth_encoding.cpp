#include "rgbdvo/sensor/depth_encoding.hpp"

#include <stdexcept>

namespace rgbdvo {

cv::Mat DepthFromScaled16(const cv::Mat& raw, double units_per_m) {
  if (raw.type() != CV_16UC1) throw std::invalid_argument("depth image must be 16-bit, 1 channel");
  if (!(units_per_m > 0)) throw std::invalid_argument("depth units per metre must be > 0");
  cv::Mat depth;
  raw.convertTo(depth, CV_32F, 1.0 / units_per_m);
  return depth;
}

cv::Mat Scaled16FromDepth(const cv::Mat& depth_m, double units_per_m) {
  cv::Mat scaled = depth_m * units_per_m;
  scaled.setTo(0, scaled > 65535.0);
  cv::Mat raw;
  scaled.convertTo(raw, CV_16U);  // rounds to nearest
  return raw;
}

}  // namespace rgbdvo
