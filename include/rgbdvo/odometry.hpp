#pragma once
// The visual odometry loop: features -> matches -> 3D pairs -> RANSAC -> verification -> pose.

#include <cstdint>
#include <string>

#include "rgbdvo/calibration.hpp"
#include "rgbdvo/features.hpp"
#include "rgbdvo/frame.hpp"
#include "rgbdvo/geometry.hpp"
#include "rgbdvo/matching.hpp"
#include "rgbdvo/motion_check.hpp"
#include "rgbdvo/ransac.hpp"

namespace rgbdvo {

struct OdometryOptions {
  FeatureOptions features;
  MatchOptions matching;
  RansacOptions ransac;
  MotionCheckOptions verify;
  // After this many rejected frames in a row the reference is given up: the current frame
  // becomes the new reference at the last known pose (status "lost"), so a stuck reference
  // cannot freeze the trajectory forever. 0 = never.
  int max_rejected_run = 30;
  uint32_t seed = 42;  // RANSAC random generator seed (fixed: runs are reproducible)
  void Check() const;
  std::string ToString() const;  // the effective configuration, one "key = value" per line
};

enum class FrameStatus { kFirst, kAccepted, kRejected, kLost };

// Seconds spent per stage for one frame (for bench/speed).
struct StageTimes {
  double features = 0, matching = 0, lifting = 0, ransac = 0;
};

struct FrameResult {
  int frame = 0;
  double timestamp = 0;
  Rigid3d world_from_cam = Rigid3d::Identity();
  int features = 0;
  int matches = 0;
  int pairs = 0;  // matches with depth at both ends
  int inliers = 0;
  FrameStatus status = FrameStatus::kFirst;
  std::string reason;  // why rejected or lost, "" otherwise
  StageTimes times;
  // "first", "accepted", "rejected:<reason>" or "lost:<reason>" (no commas).
  std::string StatusString() const;
};

// Policy after a rejected frame: its pose is reported as the last accepted pose (status
// rejected) and the next frame is matched against the last accepted frame (the reference), so
// the motion across the rejected frame is still measured, not lost.
class Odometry {
 public:
  Odometry(const OdometryOptions& options, const Calibration& calib);
  FrameResult Process(const Frame& frame);

 private:
  OdometryOptions options_;
  Calibration calib_;
  SiftExtractor extractor_;
  Rng rng_;
  bool has_reference_ = false;
  Features ref_features_;
  cv::Mat ref_depth_;
  Rigid3d world_from_ref_ = Rigid3d::Identity();
  int rejected_run_ = 0;
};

}  // namespace rgbdvo
