#pragma once
// The depth images' own evidence in the refinement (beyond the paper;
// docs/decisions/0014-depth-term-gated.md): point-to-plane residuals between the current frame's
// depth points and the reference's depth surface, by projective association (as KinectFusion's
// ICP), added to the feature residuals. The features fix the motion where the scene has texture;
// the depth surface pins it where the features are few or their depth is read off an edge.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

// The undistorted normalised coordinates (x, y) of every pixel of a depth image of the given
// size (NormalizeIr, once per camera): CV_64FC2.
cv::Mat DepthRays(const Calibration& calib, cv::Size size);

// The points of a depth image (CV_32FC1 metres, 0 = no reading) on a grid of every `step`-th
// pixel, in the camera cam (cam_from_depth maps the depth camera's points into it; e.g. the
// camera at the colour image's time). rays: DepthRays of the image's size.
std::vector<Eigen::Vector3d> SampleDepthPoints(const cv::Mat& rays, const cv::Mat& depth_m,
                                               const Rigid3d& cam_from_depth, int step);

// Point-to-plane residuals of points (in the current camera) against a reference depth image.
class DepthPlaneTerm {
 public:
  // ref_depth_m: the reference's depth image (kept by reference, must outlive the term);
  // ref_depth_from_cam: maps points of the reference camera (the pose's frame) into its depth
  // camera; points: SampleDepthPoints of the current frame; noise_coeff: sigma_z = c * z^2.
  // rays: DepthRays of the image's size (kept by reference); max_jump_ratio: a reading whose
  // neighbours (2 pixels away) differ from it by more than this fraction lies on a depth jump,
  // where the surface is undefined.
  DepthPlaneTerm(const Calibration& calib, const cv::Mat& rays, const cv::Mat& ref_depth_m,
                 const Rigid3d& ref_depth_from_cam, const std::vector<Eigen::Vector3d>& points,
                 double noise_coeff, double max_jump_ratio);

  size_t size() const { return points_.size(); }
  // Whitened point-to-plane residual of point i moved by ref_from_cur, against the reference
  // surface at the pixel it projects to, and (if J) its derivative for a left perturbation
  // ref_from_cur <- Exp(delta) * ref_from_cur, delta = (omega, v). False when the point lands on
  // no reading or on a depth jump.
  bool Residual(size_t i, const Rigid3d& ref_from_cur, double* r,
                Eigen::Matrix<double, 1, 6>* J) const;
  // Scales the noise (a robust estimate of the frame's actual residual spread).
  void ScaleNoise(double scale) { noise_coeff_ *= scale; }
  double noise_coeff() const { return noise_coeff_; }

 private:
  Calibration calib_;
  const cv::Mat& rays_;
  const cv::Mat& depth_;
  Rigid3d depth_from_cam_;
  const std::vector<Eigen::Vector3d>& points_;
  double noise_coeff_;
  double max_jump_ratio_;
};

// The median absolute whitened residual over 0.674 (the median of |N(0, 1)|), at least 1, of
// the points that land on a reading under ref_from_cur: how much noisier the depth surfaces
// agree than the sensor model says. 1 when none lands.
double EstimateDepthTermScale(const DepthPlaneTerm& term, const Rigid3d& ref_from_cur);

}  // namespace rgbdvo
