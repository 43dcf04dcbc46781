#pragma once
// 2D matches -> 3D point pairs through the depth images (paper section 3).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "rgbdvo/estimation/point_pair.hpp"
#include "rgbdvo/features/features.hpp"
#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

struct LiftOptions {
  // > 0: bilinear depth at the keypoint's sub-pixel position, refused where the 4 neighbours
  // differ by more than this fraction of their mean (a depth edge). 0: the paper's nearest pixel.
  double max_depth_jump_ratio = 0.03;
  void Check() const;
};

// The 3D point (IR camera frame) of every keypoint, or nullopt without depth: LiftColorPixel
// with options.max_depth_jump_ratio. Done once per frame, so a frame matched against several
// references (or kept as one) is not lifted again.
using KeypointPoints = std::vector<std::optional<Eigen::Vector3d>>;
KeypointPoints LiftKeypoints(const Calibration& calib, const LiftOptions& options,
                             const cv::Mat& depth_m, const Features& features);

// As above for a depth image taken at another time than the colour image: depth_from_color
// maps a point from the camera at the colour image's time into the camera at the depth
// image's time (p_depth_cam = depth_from_color * p_color_cam). Each keypoint is moved to where the
// point it sees lies in the depth image (rotation first, then once more with the depth found there,
// for the translation's parallax) and lifted there; the point is returned in the camera at the
// colour image's time, where the keypoints were seen. The identity gives LiftKeypoints above
// exactly.
KeypointPoints LiftKeypointsAcrossTime(const Calibration& calib, const LiftOptions& options,
                                       const cv::Mat& depth_m, const Features& features,
                                       const Rigid3d& depth_from_color);

// The pairs of the matches whose two keypoints have a 3D point (queryIdx indexes prev_points,
// trainIdx cur_points), in match order (the same pairs as lifting both keypoints of each match). If
// match_of_pair is given it receives, for each pair, the index of its match.
std::vector<PointPair> PairMatches(const KeypointPoints& prev_points,
                                   const KeypointPoints& cur_points,
                                   const std::vector<cv::DMatch>& matches,
                                   std::vector<int>* match_of_pair = nullptr);

// Where each reference keypoint should appear in the current colour image: its 3D point moved
// by cur_from_ref, projected with ProjectIr, and eq. 1 inverted (IrToColor). nullopt for
// keypoints without a 3D point or with the moved point not in front of the camera.
std::vector<std::optional<Eigen::Vector2d>> PredictKeypoints(const Calibration& calib,
                                                             const KeypointPoints& ref_points,
                                                             const Rigid3d& cur_from_ref);

// The local affine map of the reference colour image's pixels around each keypoint onto the
// current colour image's (for RefineWarped), as PredictKeypoints moves them: the keypoint's 3D
// point and two beside it, step_px to the right of and below it at the same depth (the surface
// taken as facing the camera), projected before and after the motion. Identity where a point
// has no 3D point or a projection fails.
std::vector<cv::Matx22f> PredictWarps(const Calibration& calib, const KeypointPoints& ref_points,
                                      const Rigid3d& cur_from_ref, double step_px = 4.0);

}  // namespace rgbdvo
