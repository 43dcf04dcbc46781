#pragma once
// Refinement of a frame-to-frame motion by weighted, robust least squares on the image
// reprojection and depth residuals of the inlier matches (beyond the paper;
// docs/decisions/0002-additions-beyond-the-paper.md).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "rgbdvo/estimation/depth_term.hpp"
#include "rgbdvo/estimation/point_pair.hpp"
#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"

namespace rgbdvo {

struct RefineOptions {
  double pixel_sigma = 1.0;                           // keypoint localisation noise, pixels
  double depth_noise_coeff = kKinectDepthNoiseCoeff;  // Kinect depth noise sigma_z = c * z^2, 1/m
                                                      // (Khoshelham & Elberink 2012)
  double huber_sigmas = 2.0;   // Huber threshold on a whitened residual block
  double inlier_sigmas = 4.0;  // a pair is an inlier below this whitened error
  int max_iterations = 10;     // Levenberg-Marquardt iterations
  // RefineWithInlierSelection: at most this many rounds of selecting the inliers and refining on
  // them (1: select once).
  int selection_rounds = 10;
  // Set: the motion is planar in this level frame (planar_motion.hpp) and only its turn about
  // the level y axis and its x-z translation are refined; the initial motion must be planar.
  std::optional<Eigen::Matrix3d> planar_level_from_cam;
  void Check() const;
};

struct RefineResult {
  bool success = false;
  Rigid3d prev_from_cur = Rigid3d::Identity();
  int iterations = 0;
  double initial_cost = 0, final_cost = 0;  // mean robust cost per pair
  std::string Brief() const;
};

// Minimises, over prev_from_cur = (R, t), the robust (Huber) sum over the pairs named by
// `indices` of the symmetric transfer error: p_cur moved into the previous camera against
// where the previous frame saw it, and p_prev moved into the current camera against where the
// current frame saw it, each as 2 pixel residuals (sigma = pixel_sigma) and a depth residual
// (sigma = depth_noise_coeff * z^2). The observations are recovered from the points
// themselves (x = X/Z, y = Y/Z, z = Z), so `focal_px` is all it needs of the camera.
// With `dense`, its point-to-plane residuals (whitened by its own noise) are added, each with a
// Huber cost truncated at inlier_sigmas.
RefineResult RefineMotion(const RefineOptions& options, double focal_px,
                          const std::vector<PointPair>& pairs, const std::vector<int>& indices,
                          const Rigid3d& initial_prev_from_cur,
                          const DepthPlaneTerm* dense = nullptr);

// Inlier selection and refinement alternated from `start` (e.g. a RANSAC motion refined on its
// inliers): select the pairs whose WhitenedError under the current motion is below
// inlier_sigmas, refine on them from the current motion, and repeat until the selection repeats
// (a fixed point: the motion is the refinement of exactly the pairs it accepts) or after
// selection_rounds rounds. A single round leaves the selection depending on where RANSAC's
// random hypothesis happened to put `start`; the fixed point does not. Ends early, keeping the
// previous round, when fewer than 3 pairs would be selected; `inliers` is empty and `refine`
// unset when even the first selection has fewer than 3.
struct SelectionRefinement {
  std::optional<RefineResult> refine;
  std::vector<int> inliers;  // the pairs `refine` was computed on
  int rounds = 0;            // selections refined on
};
SelectionRefinement RefineWithInlierSelection(const RefineOptions& options, double focal_px,
                                              const std::vector<PointPair>& pairs,
                                              const Rigid3d& start,
                                              const DepthPlaneTerm* dense = nullptr);

// The cost RefineMotion minimises at prev_from_cur (the mean robust cost over the pairs and the
// dense points) and, if gradient is given, its gradient for a left perturbation
// Exp(delta) * prev_from_cur, delta = (omega, v): the hand-written derivatives its
// Gauss-Newton steps use, exposed so that they can be checked against the cost.
double RefineCost(const RefineOptions& options, double focal_px,
                  const std::vector<PointPair>& pairs, const std::vector<int>& indices,
                  const Rigid3d& prev_from_cur, const DepthPlaneTerm* dense,
                  Eigen::Matrix<double, 6, 1>* gradient);

// How well the pairs named by `indices` pin down the translation at prev_from_cur: the standard
// deviation (m) of the refined translation along its least certain direction, with the
// rotation free (the translation block of the inverse Gauss-Newton information of the residuals
// RefineMotion minimises, with each pair's two observations counted once; in
// the planar model's 3 parameters when planar_level_from_cam is set). It grows where the
// matches are few, lie on one plane far away (a turn and a slide look alike) or crowd into one
// part of the image. Infinite when a direction is not constrained at all.
double TranslationStd(const RefineOptions& options, double focal_px,
                      const std::vector<PointPair>& pairs, const std::vector<int>& indices,
                      const Rigid3d& prev_from_cur);

// Whitened symmetric error of one pair under prev_from_cur (the larger of the two directions,
// in sigmas): the inlier test that grows with depth.
double WhitenedError(const RefineOptions& options, double focal_px, const PointPair& pair,
                     const Rigid3d& prev_from_cur);

// How much noisier the pairs named by `indices` are under prev_from_cur than the model says,
// for the image and the depth part of the residual separately: the median whitened pixel error
// over 1.177 (the median of a chi distribution with 2 degrees of freedom) and the median
// absolute whitened depth error over 0.674 (the median of |N(0, 1)|), each at least 1. Motion
// blur and the rolling shutter of a fast turn move keypoints by several pixels; depth taken up
// to 20 ms before or after the colour image errs along the motion. A robust scale estimate (as
// in M-estimation) lets the Huber threshold and the inlier test follow the frame's actual noise
// instead of cutting the true matches away. {1, 1} when indices is empty.
struct NoiseScale {
  double pixel = 1, depth = 1;
};
NoiseScale EstimateNoiseScale(const RefineOptions& options, double focal_px,
                              const std::vector<PointPair>& pairs, const std::vector<int>& indices,
                              const Rigid3d& prev_from_cur);

// The options with pixel_sigma and depth_noise_coeff multiplied by the scales.
RefineOptions ScaleNoise(RefineOptions options, const NoiseScale& scale);

}  // namespace rgbdvo
