#pragma once
// Colour pixel -> IR pixel -> 3D point (paper section 2.1, eq. 1 and 4).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>

#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

// Paper eq. 1: the IR (depth image) pixel that sees what colour pixel uv_vis sees.
Eigen::Vector2d ColorToIr(const Calibration& calib, const Eigen::Vector2d& uv_vis);

// Inverse of eq. 1: the colour pixel u = (u_ir - B) / A, v = (v_ir - D) / C.
Eigen::Vector2d IrToColor(const Calibration& calib, const Eigen::Vector2d& uv_ir);

// The undistorted normalised coordinates (x, y) = K_ir^-1 [u, v, 1] of IR pixel uv_ir, with
// dist_ir removed (fixed-point inversion of OpenCV's model, as cv::undistortPoints does).
Eigen::Vector2d NormalizeIr(const Calibration& calib, const Eigen::Vector2d& uv_ir);

// Paper eq. 4 (plus the lens distortion the paper neglects, when dist_ir is set): X = depth *
// K_ir^-1 [u_ir, v_ir, 1]^T. `depth_m` is the Z coordinate (the Kinect and TUM depth images store
// Z, not the range along the ray), so the result has Z = depth_m.
Eigen::Vector3d BackProject(const Calibration& calib, const Eigen::Vector2d& uv_ir, double depth_m);

// Inverse of BackProject: the IR pixel of a point in the IR camera frame (Z > 0), distorted.
Eigen::Vector2d ProjectIr(const Calibration& calib, const Eigen::Vector3d& p_in_ir);

// The depth (metres) at the IR pixel nearest to uv_ir in a CV_32FC1 depth image, or nullopt when
// the pixel lies outside the image, has no reading (0) or lies outside the calibrated range.
std::optional<double> SampleDepth(const Calibration& calib, const cv::Mat& depth_m,
                                  const Eigen::Vector2d& uv_ir);

// Bilinear depth at the sub-pixel IR position uv_ir from its 4 neighbours, or nullopt when one
// of them has no reading (or is outside the range or image) or they differ by more than
// max_jump_ratio * their mean (a depth discontinuity: interpolating across it invents a point).
std::optional<double> SampleDepthBilinear(const Calibration& calib, const cv::Mat& depth_m,
                                          const Eigen::Vector2d& uv_ir, double max_jump_ratio);

// The whole chain: the 3D point (IR camera frame) seen at colour pixel uv_vis, or nullopt.
// Nearest-pixel depth (the paper) unless max_jump_ratio > 0, then SampleDepthBilinear.
std::optional<Eigen::Vector3d> LiftColorPixel(const Calibration& calib, const cv::Mat& depth_m,
                                              const Eigen::Vector2d& uv_vis,
                                              double max_jump_ratio = 0);

}  // namespace rgbdvo
