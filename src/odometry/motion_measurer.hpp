#pragma once
// A frame's motion measured against one reference: by SIFT matches (guided, brute force,
// rematched) or by the reference's keypoints tracked into it; RANSAC, refinement and
// verification either way (private to src/odometry).

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reference.hpp"
#include "rgbdvo/estimation/motion_estimate.hpp"
#include "rgbdvo/estimation/ransac.hpp"
#include "rgbdvo/features/features.hpp"
#include "rgbdvo/odometry/odometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

class MotionMeasurer {
 public:
  // calib as the odometry uses it (without distortion unless options.undistort).
  MotionMeasurer(const OdometryOptions& options, const Calibration& calib);
  // With the planar model: every estimate is about the floor's normal in this level frame.
  void SetLevel(const Eigen::Matrix3d& level_from_cam);
  void SetThreads(int threads) { threads_ = threads; }
  const SiftExtractor& extractor() const { return extractor_; }
  // The depth term's rays for images of `size` (DepthRays), made once.
  const cv::Mat& DepthRaysFor(const cv::Size& size);

  // Motion ref_from_cur (in result.prev_from_cur) from SIFT matches, checked by verification
  // (*reason: "" when it passes); fills r's counts. Guided by world_from_cur_pred, with a
  // brute-force retry if that fails verification, and guided again around the estimate where
  // the prior was off (guided_rematch).
  MotionEstimate Match(const Reference& ref, const Reference& cur,
                       const Rigid3d& world_from_cur_pred, FrameResult* r, std::string* reason);
  // The last Match's kept estimate's inliers as keypoint pairs (ref's keypoint, cur's).
  const std::vector<std::pair<int, int>>& matched_inliers() const { return matched_inliers_; }
  // The motion ref_from_cur from ref's keypoints `tracked` (indices) tracked into cur from where
  // cur_from_ref_pred puts them (fills r's counts); ref's pyramid gets its derivatives and
  // ref keeps its tracking windows for the next frames.
  MotionEstimate Track(Reference* ref, const std::vector<int>& tracked, const Reference& cur,
                       const Rigid3d& cur_from_ref_pred, FrameResult* r);
  // SIFT on ref and its keypoints lifted, once. With `beside` the same for it, its SIFT on a
  // second thread meanwhile when SetThreads gave 2 or more.
  void EnsureFeatures(Reference* ref, FrameResult* r, Reference* beside = nullptr);

 private:
  // RANSAC and refinement on the 3D pairs of `matches`; match_of_pair as in PairMatches.
  // cur_points: the 3D points of the matches' current keypoints (trainIdx).
  MotionEstimate FromMatches(const Reference& ref, const Reference& cur,
                             const KeypointPoints& cur_points,
                             const std::vector<cv::DMatch>& matches, FrameResult* r,
                             std::vector<int>* match_of_pair);
  // The refinement of a verified RANSAC estimate in place (refine_enabled).
  void Refine(const Reference& ref, const Reference& cur, const std::vector<PointPair>& pairs,
              MotionEstimate* estimate);

  OdometryOptions options_;
  Calibration calib_;
  SiftExtractor extractor_;
  Rng rng_;
  std::optional<Eigen::Matrix3d> level_from_cam_;
  cv::Mat depth_rays_;
  int threads_ = 1;
  std::vector<std::pair<int, int>> matched_inliers_;
};

}  // namespace rgbdvo
