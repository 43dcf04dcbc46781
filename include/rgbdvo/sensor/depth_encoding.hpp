#pragma once
// Depth image encodings -> metres (CV_32FC1, 0 = no reading). The encoding belongs to the source.

#include <opencv2/core.hpp>

namespace rgbdvo {

// 16-bit depth in fixed units per metre (TUM RGB-D: 5000 per metre, 0 = no reading).
// Throws std::invalid_argument if `raw` is not CV_16UC1 or units_per_m <= 0.
cv::Mat DepthFromScaled16(const cv::Mat& raw, double units_per_m);

// Inverse of DepthFromScaled16 (rounded; depths that do not fit in 16 bits become 0).
cv::Mat Scaled16FromDepth(const cv::Mat& depth_m, double units_per_m);

}  // namespace rgbdvo
