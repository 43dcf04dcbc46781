#include "rgbdvo/point_pairs.hpp"

#include <stdexcept>

#include "rgbdvo/camera.hpp"

namespace rgbdvo {

void LiftOptions::Check() const {
  if (!(max_depth_jump_ratio >= 0))
    throw std::invalid_argument("max_depth_jump_ratio must be >= 0");
}

KeypointPoints LiftKeypoints(const Calibration& calib, const LiftOptions& options,
                             const cv::Mat& depth_m, const Features& features) {
  KeypointPoints points;
  points.reserve(features.size());
  for (const cv::KeyPoint& k : features.keypoints)
    points.push_back(
        LiftColorPixel(calib, depth_m, {k.pt.x, k.pt.y}, options.max_depth_jump_ratio));
  return points;
}

std::vector<PointPair> PairMatches(const KeypointPoints& prev_points,
                                   const KeypointPoints& cur_points,
                                   const std::vector<cv::DMatch>& matches,
                                   std::vector<int>* match_of_pair) {
  std::vector<PointPair> pairs;
  pairs.reserve(matches.size());
  if (match_of_pair) match_of_pair->clear();
  for (size_t m = 0; m < matches.size(); ++m) {
    const std::optional<Eigen::Vector3d>& p_prev = prev_points.at(matches[m].queryIdx);
    const std::optional<Eigen::Vector3d>& p_cur = cur_points.at(matches[m].trainIdx);
    if (!p_prev || !p_cur) continue;
    pairs.push_back({*p_prev, *p_cur});
    if (match_of_pair) match_of_pair->push_back(static_cast<int>(m));
  }
  return pairs;
}

}  // namespace rgbdvo
