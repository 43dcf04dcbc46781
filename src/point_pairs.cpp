#include "rgbdvo/point_pairs.hpp"

#include <stdexcept>

#include "rgbdvo/camera.hpp"

namespace rgbdvo {

void LiftOptions::Check() const {
  if (!(max_depth_jump_ratio >= 0))
    throw std::invalid_argument("max_depth_jump_ratio must be >= 0");
}

std::vector<PointPair> LiftMatches(const Calibration& calib, const LiftOptions& options,
                                   const cv::Mat& depth_prev, const cv::Mat& depth_cur,
                                   const Features& prev, const Features& cur,
                                   const std::vector<cv::DMatch>& matches) {
  std::vector<PointPair> pairs;
  pairs.reserve(matches.size());
  for (const cv::DMatch& m : matches) {
    const cv::Point2f a = prev.keypoints[m.queryIdx].pt, b = cur.keypoints[m.trainIdx].pt;
    const auto p_prev = LiftColorPixel(calib, depth_prev, {a.x, a.y}, options.max_depth_jump_ratio);
    if (!p_prev) continue;
    const auto p_cur = LiftColorPixel(calib, depth_cur, {b.x, b.y}, options.max_depth_jump_ratio);
    if (!p_cur) continue;
    pairs.push_back({*p_prev, *p_cur});
  }
  return pairs;
}

}  // namespace rgbdvo
