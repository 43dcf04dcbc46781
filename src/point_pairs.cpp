#include "rgbdvo/point_pairs.hpp"

#include "rgbdvo/camera.hpp"

namespace rgbdvo {

std::vector<PointPair> LiftMatches(const Calibration& calib, const cv::Mat& depth_prev,
                                   const cv::Mat& depth_cur, const Features& prev,
                                   const Features& cur, const std::vector<cv::DMatch>& matches) {
  std::vector<PointPair> pairs;
  pairs.reserve(matches.size());
  for (const cv::DMatch& m : matches) {
    const cv::Point2f a = prev.keypoints[m.queryIdx].pt, b = cur.keypoints[m.trainIdx].pt;
    const auto p_prev = LiftColorPixel(calib, depth_prev, {a.x, a.y});
    if (!p_prev) continue;
    const auto p_cur = LiftColorPixel(calib, depth_cur, {b.x, b.y});
    if (!p_cur) continue;
    pairs.push_back({*p_prev, *p_cur});
  }
  return pairs;
}

}  // namespace rgbdvo
