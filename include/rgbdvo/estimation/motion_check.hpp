#pragma once
// The paper's verification step: reject implausible frame-to-frame motions.

#include <string>

#include "rgbdvo/estimation/motion_estimate.hpp"

namespace rgbdvo {

struct MotionCheckOptions {
  int min_inliers = 15;            // fewer RANSAC inliers -> reject (paper: 15)
  double max_translation_m = 0.5;  // larger motion per frame -> reject (paper: 50 cm)
  double max_rotation_deg = 60.0;  // larger rotation per frame -> reject (paper: 60 degrees)
  void Check() const;
};

// "" when the motion is plausible, else a short reason without commas or spaces, such as
// "inliers<15" or "translation>0.5m".
std::string CheckMotion(const MotionCheckOptions& options, const MotionEstimate& estimate);

}  // namespace rgbdvo
