#pragma once
// 2D matches -> 3D point pairs through the depth images (paper section 3).

#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "rgbdvo/calibration.hpp"
#include "rgbdvo/features.hpp"

namespace rgbdvo {

struct PointPair {
  Eigen::Vector3d p_prev;  // point in the previous (reference) camera frame, metres
  Eigen::Vector3d p_cur;   // the same point in the current camera frame, metres
};

// Lifts every match whose two keypoints have a depth reading; matches without depth are dropped.
std::vector<PointPair> LiftMatches(const Calibration& calib, const cv::Mat& depth_prev,
                                   const cv::Mat& depth_cur, const Features& prev,
                                   const Features& cur, const std::vector<cv::DMatch>& matches);

}  // namespace rgbdvo
