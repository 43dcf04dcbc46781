#pragma once
// 2D matches -> 3D point pairs through the depth images (paper section 3).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "rgbdvo/calibration.hpp"
#include "rgbdvo/features.hpp"

namespace rgbdvo {

struct PointPair {
  Eigen::Vector3d p_prev;  // point in the previous (reference) camera frame, metres
  Eigen::Vector3d p_cur;   // the same point in the current camera frame, metres
};

struct LiftOptions {
  // > 0: bilinear depth at the keypoint's sub-pixel position, refused where the 4 neighbours
  // differ by more than this fraction of their mean (a depth edge). 0: the paper's nearest pixel.
  double max_depth_jump_ratio = 0.03;
  void Check() const;
};

// Lifts every match whose two keypoints have a depth reading; matches without depth are dropped.
std::vector<PointPair> LiftMatches(const Calibration& calib, const LiftOptions& options,
                                   const cv::Mat& depth_prev, const cv::Mat& depth_cur,
                                   const Features& prev, const Features& cur,
                                   const std::vector<cv::DMatch>& matches);

}  // namespace rgbdvo
