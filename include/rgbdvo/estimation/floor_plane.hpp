#pragma once
// The floor under a camera rigidly mounted on a ground robot, from one depth image: the
// camera-to-floor extrinsic (height, roll, pitch) that the planar motion model needs
// (planar_motion.hpp; docs/decisions/0010-planar-motion.md). RANSAC over planes through 3
// back-projected pixels, then weighted least-squares planes through the inliers.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>

#include "rgbdvo/estimation/ransac.hpp"
#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

struct FloorFitOptions {
  int pixel_step = 8;          // every n-th pixel in both directions is back-projected
  int max_trials = 300;        // plane hypotheses
  double max_tilt_deg = 45.0;  // the floor's normal within this of the camera's down (+y), deg
  // A point is on the plane within 3 sigma of the Kinect's depth noise at its depth,
  // sigma = 1.425e-3 z^2 m (Khoshelham & Elberink 2012), and at least min_inlier_m.
  double min_inlier_m = 0.01;
  double min_fraction = 0.05;  // fewer of the back-projected points on the floor: no floor
  // Weighted least-squares fits after RANSAC, each re-selecting the inliers of the last.
  int refinements = 5;
  void Check() const;  // throws std::invalid_argument naming the field
};

struct FloorFit {
  bool success = false;
  std::string reason;  // why not (empty on success)
  // Unit normal of the floor in the camera frame, pointing down (away from the camera), and
  // the camera's height above the floor: the floor is {p : normal . p = height_m}.
  Eigen::Vector3d normal_in_cam = Eigen::Vector3d::UnitY();
  double height_m = 0;
  // The smallest rotation taking normal_in_cam to the camera's +y: the level frame of
  // planar_motion.hpp. Its angles, degrees: pitch = atan2(n_z, n_y) (positive: the camera
  // looks down) and roll = asin(n_x) (positive: the floor's normal leans to the camera's +x).
  Eigen::Matrix3d level_from_cam = Eigen::Matrix3d::Identity();
  double pitch_deg = 0, roll_deg = 0;
  int points = 0;             // back-projected points
  int inliers = 0;            // of them on the floor
  std::string Brief() const;  // one line: height, pitch, roll, support (or the reason)
};

// The floor in `depth_m` (CV_32FC1 metres, the IR camera of `calib`): among planes whose
// normal is within max_tilt_deg of the camera's down and which lie below the camera, the one
// with most points on it. success = false (with the reason) without depth or such a plane.
FloorFit FitFloor(const FloorFitOptions& options, const Calibration& calib, const cv::Mat& depth_m,
                  Rng& rng);

}  // namespace rgbdvo
