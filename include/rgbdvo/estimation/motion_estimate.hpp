#pragma once
// A frame-to-frame motion with the report of each stage that made it: RANSAC's (its trials,
// its inliers and motion as RANSAC ended) and, when the refinement ran, the refinement's. The
// final motion and inliers are the last stage's, kept apart from the stages' own reports.

#include <optional>
#include <string>
#include <vector>

#include "rgbdvo/estimation/ransac.hpp"
#include "rgbdvo/estimation/refine.hpp"
#include "rgbdvo/geometry/geometry.hpp"

namespace rgbdvo {

struct MotionEstimate {
  RansacResult ransac;                          // the hypothesis stage, unchanged by what follows
  std::optional<RefineResult> refine;           // the final refinement, when it ran
  bool success = false;                         // RANSAC found a motion
  Rigid3d prev_from_cur = Rigid3d::Identity();  // the final motion
  std::vector<int> inliers;                     // the final inliers (indices into the pairs)
  std::string reason;                           // why RANSAC failed ("" on success)
  // With a constrained model (planar): the refinement of the final inliers with all 6 degrees
  // of freedom, started from the final motion, to check the constraint against.
  std::optional<Rigid3d> unconstrained;
  // The pixel noise the refinement measured on RANSAC's inliers (EstimateNoiseScale: in units
  // of RefineOptions::pixel_sigma, at least 1); 0 when the refinement did not run.
  double pixel_noise = 0;

  // The estimate RANSAC alone gives (no refinement).
  static MotionEstimate FromRansac(RansacResult ransac);
};

}  // namespace rgbdvo
