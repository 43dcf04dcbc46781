#pragma once
// RANSAC over minimal rigid hypotheses from random 3D matches (paper section 3).

#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "rgbdvo/estimation/point_pair.hpp"
#include "rgbdvo/geometry/geometry.hpp"

namespace rgbdvo {

using Rng = std::mt19937;

struct RansacOptions {
  int max_trials = 200;              // hypotheses tried (paper: 200)
  int sample_size = 4;               // matches per hypothesis (paper: 4)
  double inlier_distance_m = 0.015;  // 3D distance for an inlier (paper: 1.5 cm)
  // Stop once an all-inlier sample has been drawn with this probability, given the best inlier
  // ratio so far (Fischler & Bolles 1981; Hartley & Zisserman 4.7.1); max_trials stays the cap.
  // 0 = always run max_trials (the paper).
  double confidence = 0.999;
  void Check() const;
};

struct RansacResult {
  bool success = false;
  Rigid3d prev_from_cur = Rigid3d::Identity();  // refined on the inliers
  std::vector<int> inliers;                     // indices into the pairs
  int trials = 0;
  double rms_m = 0;    // RMS 3D residual of the inliers after refinement
  std::string reason;  // why it failed ("" on success)
  std::string Brief() const;
};

// Best hypothesis by inlier count, then refined by AlignRigid on its inliers (and the inliers
// recomputed once with the refined motion). success=false for too few pairs or no hypothesis.
RansacResult EstimateRigidRansac(const RansacOptions& options, const std::vector<PointPair>& pairs,
                                 Rng& rng);

// A motion model for RANSAC: prev_from_cur fitted (least squares) to the pairs named by the
// indices, nullopt when they are degenerate; sample_size pairs per hypothesis, at least
// min_pairs to refine on.
struct MotionModel {
  int sample_size = 4;
  int min_pairs = 3;
  std::function<std::optional<Rigid3d>(const std::vector<PointPair>&, const std::vector<int>&)> fit;
};

// EstimateRigidRansac with another model (options.sample_size is the rigid model's; the model
// says its own): hypotheses from random samples, inliers by 3D distance, refined as above.
RansacResult EstimateRansac(const RansacOptions& options, const std::vector<PointPair>& pairs,
                            const MotionModel& model, Rng& rng);

}  // namespace rgbdvo
