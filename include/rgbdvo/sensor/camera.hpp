#pragma once
// Colour pixel -> IR pixel -> 3D point (paper section 2.1, eq. 1 and 4), with the optional
// depth-aware term of the calibration (Calibration::s_u, s_v).

#include <Eigen/Core>
#include <limits>
#include <opencv2/core.hpp>
#include <optional>

#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

constexpr double kInfiniteDepth = std::numeric_limits<double>::infinity();

// Paper eq. 1 plus the disparity term: the IR (depth image) pixel that sees the point at depth
// z_m (metres, Z in the IR camera) on the ray of colour pixel uv_vis:
// (A u + B + s_u / z, C v + D + s_v / z). Without a disparity term z_m changes nothing.
Eigen::Vector2d ColorToIr(const Calibration& calib, const Eigen::Vector2d& uv_vis,
                          double z_m = kInfiniteDepth);

// Its inverse: the colour pixel u = (u_ir - B - s_u / z) / A, v = (v_ir - D - s_v / z) / C
// that sees the point at depth z_m seen at IR pixel uv_ir.
Eigen::Vector2d IrToColor(const Calibration& calib, const Eigen::Vector2d& uv_ir,
                          double z_m = kInfiniteDepth);

// The colour camera's centre in the IR camera's frame, as the calibration places it:
// (s_u / fx, s_v / fy, 0), the disparity term's baseline (s_u = -fx o_x for an IR camera at o in
// the colour camera's frame, axes parallel as eq. 1 takes them). Zero without the term: eq. 1
// alone has no baseline and takes the two centres as one.
Eigen::Vector3d ColorCenterInIr(const Calibration& calib);

// The undistorted normalised coordinates (x, y) = K_ir^-1 [u, v, 1] of IR pixel uv_ir, with
// dist_ir removed (OpenCV's model inverted by Newton's method, from the distorted coordinates).
Eigen::Vector2d NormalizeIr(const Calibration& calib, const Eigen::Vector2d& uv_ir);
// The same, Newton's method started from `start` (a nearby pixel's result: fewer steps).
Eigen::Vector2d NormalizeIr(const Calibration& calib, const Eigen::Vector2d& uv_ir,
                            const Eigen::Vector2d& start);
// NormalizeIr of the n pixels (u, v), u = 0 .. n - 1, of one image row, pixel u's Newton's method
// started from start[u]; the same results as one at a time, the pixels' iterations interleaved.
void NormalizeIrRow(const Calibration& calib, int v, int n, const Eigen::Vector2d* start,
                    Eigen::Vector2d* out);

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

// The point at depth z_m on the ray of colour pixel uv_vis, in the IR camera frame:
// BackProject(ColorToIr(uv_vis, z_m), z_m).
Eigen::Vector3d ColorRayPoint(const Calibration& calib, const Eigen::Vector2d& uv_vis, double z_m);

// The IR pixel that sees what colour pixel uv_vis sees. Eq. 1 without a disparity term (the
// depth image is not consulted). With one, the ray's IR pixels ColorToIr(uv_vis, z) form a
// segment over the depth range (z >= 0.1 m); it is walked from near to far in half-pixel steps
// and the first pixel whose depth z puts the ray's point within a pixel of it is the answer
// (a surface nearer on the ray would hide a farther one from the colour camera). nullopt when
// no pixel of the segment agrees: the point is hidden from the IR camera or has no depth.
std::optional<Eigen::Vector2d> FindIrPixel(const Calibration& calib, const cv::Mat& depth_m,
                                           const Eigen::Vector2d& uv_vis);

// The whole chain: the 3D point (IR camera frame) seen at colour pixel uv_vis, or nullopt.
// FindIrPixel, then the depth there: nearest-pixel (the paper) unless max_jump_ratio > 0, then
// SampleDepthBilinear. With a disparity term the point is put on the colour pixel's ray at that
// depth (ColorRayPoint).
std::optional<Eigen::Vector3d> LiftColorPixel(const Calibration& calib, const cv::Mat& depth_m,
                                              const Eigen::Vector2d& uv_vis,
                                              double max_jump_ratio = 0);

}  // namespace rgbdvo
