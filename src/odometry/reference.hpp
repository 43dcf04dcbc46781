#pragma once
// The frames the odometry keeps to measure the next ones against (private to src/odometry).

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "rgbdvo/features/features.hpp"
#include "rgbdvo/features/keypoint_tracking.hpp"
#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/odometry/point_pairs.hpp"
#include "rgbdvo/odometry/track_staleness.hpp"

namespace rgbdvo {

// A processed frame: its features and 3D points, its depth and its pose. The keyframe, the last
// estimated frame and the current frame are each one.
struct Reference {
  Features features;
  KeypointPoints points;  // the 3D point of each keypoint (or none), lifted once
  // The depth image, for the depth fallback and term and for lifting later (else empty).
  cv::Mat depth_m;
  Rigid3d depth_from_cam = Rigid3d::Identity();  // the depth camera at the depth image's time
  std::vector<Eigen::Vector3d> depth_points;     // SampleDepthPoints, in this camera
  Rigid3d world_from_cam = Rigid3d::Identity();
  Rigid3d world_from_cam_6dof = Rigid3d::Identity();  // planar model: the 6-DOF chain
  int frame = -1;
  double color_timestamp = 0;  // seconds (Frame::color_timestamp)
  int first_inliers = -1;      // as a keyframe: inliers of the first frame measured against it
  // With track_between_keyframes SIFT runs on a frame only when it is needed (from `grey`,
  // lifted with depth_m); until then `features` and `points` are empty.
  bool has_features = true;
  cv::Mat grey;             // the grey colour image (GreyImage)
  TrackingPyramid pyramid;  // the grey image's, to track keypoints into (and from, as a keyframe)
  // As a keyframe: the Lucas-Kanade windows of the keypoints last tracked from it (made at the
  // first frame that tracks them, kept for the next).
  LkWindows windows;
  // As a keyframe: the keypoints tracked into the next frames (SelectSpread; chosen at the
  // first tracked frame), and when they go stale (made at the first tracked frame).
  std::vector<int> tracked;
  std::optional<TrackStaleness> staleness;
  bool pose_from_features = true;  // else from the depth alignment
};

// The depth keyframe of a run of frames aligned by depth (OdometryOptions::depth_keyframe);
// frame -1 before the first alignment.
struct DepthKeyframe {
  cv::Mat depth_m;
  Rigid3d world_from_cam = Rigid3d::Identity();
  int frame = -1;
};

// Where the velocity at the last estimated frame was measured from (its pose and colour time),
// for the constant-velocity prior; unknown before two frames were estimated.
struct VelocityBase {
  bool known = false;
  Rigid3d world_from_cam = Rigid3d::Identity();
  double color_timestamp = 0;
};

}  // namespace rgbdvo
