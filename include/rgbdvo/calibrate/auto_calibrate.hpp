#pragma once
// Fits the colour -> IR mapping of paper eq. 1 (u_ir = A u_vis + B, v_ir = C v_vis + D) from
// recorded frames alone, without clicked pairs. Depth discontinuities are nearly always colour
// edges (an object's outline), while colour edges are often mere texture; so the fit maps each
// depth-edge pixel to the colour image (eq. 1 inverted) and minimises the robust sum of its
// distances to the nearest colour edge (a truncated quadratic on the colour edges' distance
// transform, pooled over frames): a coarse grid search, then Levenberg-Marquardt with a
// shrinking truncation (the chamfer matching of Barrow et al. 1977, applied to calibration).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame.hpp"
#include "rgbdvo/sources/frame_source.hpp"

namespace rgbdvo {

struct AutoCalibrateOptions {
  int max_frames = 30;                  // frames read, spread evenly over the recording
  int min_frames = 3;                   // fewer usable frames: success = false
  int min_edge_points_per_frame = 100;  // a frame with fewer depth-edge points is skipped
  double depth_jump_ratio = 0.08;       // a depth edge: neighbour farther by this fraction, 1
  double canny_low = 50;                // colour edges: Canny hysteresis thresholds, levels
  double canny_high = 150;              //   (per colour channel, 0-255, after a 1 px blur)
  double search_scale = 0.15;           // A, C searched within +-this fraction of the start, 1
  double search_offset_px = 50;         // the image centre's IR pixel searched within +-this, px
  double coarse_truncation_px = 24;     // distance truncation of the grid search, px
  double fine_truncation_px = 3;        // final truncation (halved from the coarse one), px
  double inlier_px = 1.5;               // an edge point this near a colour edge is an inlier, px
  double min_inlier_fraction = 0.3;     // fewer inliers at the fit: success = false, 1
  int max_points = 30000;               // depth-edge points pooled over frames (subsampled)
  int grid_points = 2000;               // of which the grid search scores this many
  int max_iterations = 50;              // Levenberg-Marquardt iterations per truncation level
  int uncertainty_subsets = 4;          // disjoint blocks of frames refitted for the 1-sigma
  // Larger 1-sigma of the mapped corners: success = false (above warn_corner_sigma_px: a
  // warning). Real Kinect recordings (TUM fr1/xyz, fr1/desk, fr3/teddy excerpts, registered
  // depth) gave 1.7-3.6 px, the synthetic room 0.3-1 px.
  double max_corner_sigma_px = 4.0;
  double warn_corner_sigma_px = 2.0;
  // Weakest / strongest constraint below: success = false. One block in view (outlines in two
  // directions, C 6 % off) gave 0.040-0.045; the TUM excerpts 0.053-0.15, the room 0.12-0.19.
  double min_constraint_ratio = 0.05;
  void Check() const;  // throws std::invalid_argument naming the field
};

struct AutoCalibration {
  bool success = false;
  std::string reason;  // why it failed (empty on success)
  double A = 1, B = 0, C = 1, D = 0;
  // 1-sigma uncertainties of A-D: the spread (sample standard deviation / sqrt(k)) of the fits
  // refined on k disjoint blocks of consecutive used frames (options.uncertainty_subsets; with
  // fewer than 2 frames, 0). Blocks see different views, so this is more honest than the
  // normal matrix, whose edge-point residuals are far from independent; with k = 4 the sigma
  // itself is uncertain by about 40 %.
  double sigma_A = 0, sigma_B = 0, sigma_C = 0, sigma_D = 0;
  // The same spread of where the IR image's corners map to colour (the largest of the four), px.
  double corner_sigma_px = 0;
  int frames_given = 0;
  int frames_used = 0;         // frames with enough depth edges
  int edge_points = 0;         // depth-edge points fitted (pooled, subsampled)
  double inlier_fraction = 0;  // of edge_points within inlier_px of a colour edge at the fit
  double rms_px = 0;           // RMS distance of the inliers to their colour edge, px
  // How evenly the edges constrain the mapping: the cost curvature of its least over its most
  // constrained change, per px at the image corners (0.12-0.13 for the synthetic room, 0.04 for
  // one block in view, whose outlines let the mapping slide along them).
  double constraint_ratio = 0;
  int iterations = 0;         // Levenberg-Marquardt iterations, all levels
  int picture_frame = -1;     // index into the given frames of the frame with most inliers
  std::string Brief() const;  // one line: A-D +- sigma, frames, points, inliers, RMS (or why)
  // Empty, or a line saying the fit is uncertain (corner_sigma_px above warn_corner_sigma_px).
  std::string warning;
};

// The fitted parameters: eq. 1's (A, B, C, D). The start calibration's disparity term (s_u,
// s_v: the sensor's baseline, like K_ir) is kept and used, not fitted.
constexpr int kAutoCalibParams = 4;
using AutoCalibParams = Eigen::Matrix<double, kAutoCalibParams, 1>;
AutoCalibParams ParamsFromCalibration(const Calibration& calib);
void ParamsToCalibration(const AutoCalibParams& params, Calibration* calib);
// The colour pixel that sees what IR pixel (u_ir, v_ir), depth z_m metres, sees: the mapping
// inverted, u = (u_ir - B - s_u / z) / A, v = (v_ir - D - s_v / z) / C, with
// disparity = (s_u, s_v) (zero: eq. 1). With `jacobian`, also d(u, v) / d(params).
Eigen::Vector2d IrToColorPixel(const AutoCalibParams& params, const Eigen::Vector2d& disparity,
                               double u_ir, double v_ir, double z_m,
                               Eigen::Matrix<double, 2, kAutoCalibParams>* jacobian = nullptr);

// Fits A-D to `frames` (colour CV_8UC3, depth CV_32FC1 metres in the IR image), starting from
// start's A-D; start's depth range limits the depths used, its s_u, s_v are kept. Expected failures
// (no depth readings, no depth edges, too few usable frames, no convergence, too few inliers) give
// success = false with the reason. Throws std::invalid_argument for an empty frame list or a
// frame of the wrong image types.
AutoCalibration AutoCalibrate(const AutoCalibrateOptions& options, const std::vector<Frame>& frames,
                              const Calibration& start);

// `base` with A-D from the fit (which must have succeeded) and a description saying how they
// were found (from `recording`); K_ir, the depth range and the base description are kept.
Calibration ApplyAutoCalibration(const Calibration& base, const AutoCalibration& fit,
                                 const std::string& recording);

// The residual picture (CV_8UC3, the depth image's size): the depth image in grey (near =
// bright), its depth edges in green and the frame's colour edges mapped by calib (FindIrPixel)
// in magenta; depth edges within 1 px of a mapped colour edge in white. White outlines mean a good
// fit; green ones beside magenta ones, an offset.
cv::Mat AutoCalibrationPicture(const AutoCalibrateOptions& options, const Frame& frame,
                               const Calibration& calib);

// Up to max_frames frames spread evenly over the source (first and last included), skipping the
// others unread when the source knows its size; otherwise every frame is read and spread ones
// kept.
std::vector<Frame> ReadSpreadFrames(FrameSource& source, int max_frames);

}  // namespace rgbdvo
