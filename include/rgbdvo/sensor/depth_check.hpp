#pragma once
// A plausibility check of the depth scale: a wrong scale (TUM's 5000 units per metre read as
// 1000) makes the whole trajectory that many times too large or small, silently. With the right
// scale most readings of a depth image lie within the sensor's range given in the calibration.

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

// A message when the depth scale of a CV_32FC1 depth image in metres (0 = no reading) looks
// wrong, nullopt when plausible or undecided:
// - the steps between neighbouring depth values grow with z^2, as a Kinect v1's (structured
//   light, 1/8 pixel disparity steps: 0.00287 z^2 per metre), but are more than 1.5 times
//   larger or smaller than that: the scale is off by that factor;
// - or more than half of the readings (every 8th pixel of every 8th row, at least 100) lie
//   outside [calib.min_depth_m, calib.max_depth_m].
std::optional<std::string> CheckDepthScale(const cv::Mat& depth_m, const Calibration& calib);

}  // namespace rgbdvo
