#pragma once
// Guided matching: each reference keypoint is compared only with the current keypoints near
// where a predicted motion puts it (PredictKeypoints,
// odometry/point_pairs.hpp), instead of with all of them (MatchFeatures).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "rgbdvo/features/features.hpp"

namespace rgbdvo {

struct GuidedMatchOptions {
  // Candidates of a reference keypoint: the current keypoints within this distance of its
  // predicted position, colour pixels. 30: about twice the largest distance between the
  // constant-velocity prediction and the matched keypoint of a final inlier measured with
  // brute-force matching on TUM fr1/xyz and fr3/teddy (16 px; 99th percentile 9 px).
  double radius_px = 30;
  double ratio = 0.8;  // Lowe's ratio test among the candidates (as MatchOptions::ratio)
  bool mutual = true;  // mutual nearest neighbours among the candidates (as MatchOptions::mutual)
  void Check() const;
};

// Matches from `ref` to `cur` (DMatch::queryIdx indexes ref, trainIdx cur, distance = L2, as
// MatchFeatures). Reference keypoint i (predicted[i] set) and current keypoint j are candidates
// of each other when |predicted[i] - cur.keypoints[j].pt| <= radius_px. A match is i's nearest
// candidate by descriptor distance, kept if nearer than ratio * the second nearest candidate
// (no second candidate: kept) and, with mutual, if i is also the nearest of j's candidates.
// With a radius covering the image this is MatchFeatures over the keypoints with a prediction.
std::vector<cv::DMatch> MatchGuided(const GuidedMatchOptions& options, const Features& ref,
                                    const std::vector<std::optional<Eigen::Vector2d>>& predicted,
                                    const Features& cur);

}  // namespace rgbdvo
