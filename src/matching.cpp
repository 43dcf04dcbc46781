#include "rgbdvo/matching.hpp"

#include <opencv2/features2d.hpp>
#include <stdexcept>

namespace rgbdvo {

void MatchOptions::Check() const {
  if (!(ratio > 0 && ratio <= 1)) throw std::invalid_argument("ratio must be in (0, 1]");
}

std::vector<cv::DMatch> MatchFeatures(const MatchOptions& o, const Features& prev,
                                      const Features& cur) {
  std::vector<cv::DMatch> out;
  if (prev.size() < 2 || cur.size() < 2) return out;
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> forward;  // prev -> cur, two nearest
  matcher.knnMatch(prev.descriptors, cur.descriptors, forward, 2);
  std::vector<int> best_prev_for_cur;
  if (o.mutual) {
    std::vector<cv::DMatch> backward;  // cur -> prev, nearest
    matcher.match(cur.descriptors, prev.descriptors, backward);
    best_prev_for_cur.assign(cur.size(), -1);
    for (const cv::DMatch& m : backward) best_prev_for_cur[m.queryIdx] = m.trainIdx;
  }
  for (const std::vector<cv::DMatch>& knn : forward) {
    if (knn.size() < 2) continue;
    if (!(knn[0].distance < o.ratio * knn[1].distance)) continue;
    if (o.mutual && best_prev_for_cur[knn[0].trainIdx] != knn[0].queryIdx) continue;
    out.push_back(knn[0]);
  }
  return out;
}

}  // namespace rgbdvo
