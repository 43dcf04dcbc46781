#pragma once
// The fallback for frames that features cannot carry (motion blur, textureless walls): the
// motion between two depth images by point-to-plane ICP. Depth is not blurred by fast turns the
// way colour is, and it needs no texture. It uses OpenCV contrib's ICP odometries (Newcombe et
// al., KinectFusion, ISMAR 2011: projective association, coarse to fine) on the depth camera's
// pinhole model (K_ir; lens distortion ignored).
//
// ICP converges to the nearest minimum, and in a fast turn neither "no motion" nor the
// constant-velocity prediction is reliably near the right one. So it starts from several
// places and keeps the result that explains the depth images best (DepthAgreement), and only
// when the majority of the overlapping points agree.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <opencv2/rgbd.hpp>
#include <string>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"

namespace rgbdvo {

struct DepthAlignOptions {
  // Largest motion accepted between the two depth images (as the paper's verification).
  double max_translation_m = 0.5;
  double max_rotation_deg = 60.0;
  // ICP on every n-th pixel of each row and column: on fr1/desk's fast turn (7 frames) half
  // resolution is 4x faster (52 against 210 ms a frame) and as accurate on 6 frames (within
  // 0.13 degrees and 3 mm), 1.9 degrees worse on one.
  int downsample = 2;
  // Accept a result only if at least this fraction of the current image's points that land on a
  // reading of the previous image agree with it (DepthAgreement): a majority.
  double min_agreement = 0.5;
  // A point agrees when its depth is within this many sigmas of the reading it lands on, sigma
  // = depth_noise_coeff * z^2 (Khoshelham & Elberink 2012; as the refinement), plus
  // agreement_floor_m for the ICP's own residual misalignment at edges.
  double agreement_sigmas = 3.0;
  double depth_noise_coeff = kKinectDepthNoiseCoeff;  // 1/m
  double agreement_floor_m = 0.005;
  // A translation direction is free when the mean squared component of the surface normals
  // along it is below this (TranslationConstraint): there ICP's result is replaced by the
  // prediction's. Measured: 0.13-0.23 on TUM fr1/desk's ICP frames, 0.008-0.010 where a robot
  // faces a floor and one plain wall (its normals' noise), and a surface facing the direction
  // over 3 % of the image is enough to hold it.
  double min_constraint = 0.03;
  void Check() const;
};

// How well the surfaces of a depth image pin down a translation: over their unit normals n,
// the eigenvalues of mean(n n^T), each the mean squared normal component along its direction
// (0 when no surface faces it: a floor and one wall leave the direction along both free).
struct TranslationConstraint {
  double weakest = 0;                            // the smallest eigenvalue
  std::vector<Eigen::Vector3d> free_directions;  // those with eigenvalues below the minimum
};
// Of a CV_32FC3 normal image (OpenCV's, NaN where none), every 2nd pixel in both directions;
// directions below min_constraint are free (all three without normals).
TranslationConstraint MeasureTranslationConstraint(const cv::Mat& normals, double min_constraint);

struct DepthAlignResult {
  bool success = false;
  Rigid3d prev_from_cur = Rigid3d::Identity();  // p_prev = R * p_cur + t
  double agreement = 0;                         // DepthAgreement of the result
  TranslationConstraint constraint;             // of the previous image's surfaces
  std::string reason;                           // why it failed ("" on success)
};

// Of the current image's points on a grid (every 8th pixel) that, moved by prev_from_cur and
// projected into the previous image, land on a reading: the fraction whose depth agrees with
// that reading (see DepthAlignOptions). 0 when none lands. CV_32FC1 metres, 0 = no reading.
double DepthAgreement(const DepthAlignOptions& options, const Calibration& calib,
                      const cv::Mat& prev_depth_m, const cv::Mat& cur_depth_m,
                      const Rigid3d& prev_from_cur);

// Aligns depth images with OpenCV's odometries, which it keeps (their normal computers are
// built once, on the first image size seen).
class DepthAligner {
 public:
  DepthAligner(const DepthAlignOptions& options, const Calibration& calib);

  // Aligns cur to prev from five starts: FastICPOdometry from no motion; ICPOdometry from its
  // result, from its rotation with no translation, from its rotation with the translation of
  // `prev_from_cur_guess` (the prediction), and from the prediction. The result is the one of
  // highest DepthAgreement, success when that is at least min_agreement and the motion within
  // the limits. prev_depth_m and cur_depth_m: CV_32FC1 metres in the depth camera, 0 = no
  // reading, same size. Throws std::invalid_argument for other types or sizes.
  DepthAlignResult Align(const cv::Mat& prev_depth_m, const cv::Mat& cur_depth_m,
                         const Rigid3d& prev_from_cur_guess) const;

 private:
  DepthAlignOptions options_;
  Calibration calib_;
  cv::Ptr<cv::rgbd::ICPOdometry> icp_;
  cv::Ptr<cv::rgbd::FastICPOdometry> fast_;
};

}  // namespace rgbdvo
