#pragma once
// Descriptor matching between two frames' features.

#include <opencv2/core.hpp>
#include <vector>

#include "rgbdvo/features/features.hpp"

namespace rgbdvo {

struct MatchOptions {
  // Lowe's ratio test: keep a match if best < ratio * second best distance (Lowe 2004: 0.8).
  double ratio = 0.8;
  // Also require the match to be the best in the other direction (mutual nearest neighbours).
  bool mutual = true;
  void Check() const;
};

// Matches from `prev` to `cur`: DMatch::queryIdx indexes prev, DMatch::trainIdx indexes cur.
std::vector<cv::DMatch> MatchFeatures(const MatchOptions& options, const Features& prev,
                                      const Features& cur);

}  // namespace rgbdvo
