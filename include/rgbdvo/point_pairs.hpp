#pragma once
// 2D matches -> 3D point pairs through the depth images (paper section 3).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
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

// The 3D point (IR camera frame) of every keypoint, or nullopt without depth: LiftColorPixel
// with options.max_depth_jump_ratio. Done once per frame, so a frame matched against several
// references (or kept as one) is not lifted again.
using KeypointPoints = std::vector<std::optional<Eigen::Vector3d>>;
KeypointPoints LiftKeypoints(const Calibration& calib, const LiftOptions& options,
                             const cv::Mat& depth_m, const Features& features);

// The pairs of the matches whose two keypoints have a 3D point (queryIdx indexes prev_points,
// trainIdx cur_points), in match order (the same pairs as lifting both keypoints of each match). If
// match_of_pair is given it receives, for each pair, the index of its match.
std::vector<PointPair> PairMatches(const KeypointPoints& prev_points,
                                   const KeypointPoints& cur_points,
                                   const std::vector<cv::DMatch>& matches,
                                   std::vector<int>* match_of_pair = nullptr);

}  // namespace rgbdvo
