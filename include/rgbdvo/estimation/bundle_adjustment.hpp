#pragma once
// Bundle adjustment: the poses of several cameras and the 3D points they see, refined together
// on every observation's residuals: the refinement's model (refine.hpp), two reprojection
// residuals in pixels and one depth residual with the Kinect's noise, Huber-robust. Solved by
// Ceres Solver's Levenberg-Marquardt with the points eliminated (Schur complement;
// docs/decisions/0048-local-map.md says why Ceres).

#include <Eigen/Core>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"

namespace rgbdvo {

struct BundleOptions {
  double focal_px = 525;  // the depth camera's focal length: residuals in pixels
  double pixel_sigma = 1.0;
  double depth_noise_coeff = kKinectDepthNoiseCoeff;  // sigma_z = c * z^2
  double huber_sigmas = 2.0;  // Huber threshold on an observation's whitened residual
  int max_iterations = 10;    // a safeguard: the solver stops when the cost no longer falls
};

struct BundleCamera {
  Rigid3d world_from_cam = Rigid3d::Identity();
  bool fixed = false;  // held where it is (the gauge, or a camera outside the window)
};

// Camera `camera` saw point `point` at `measured`, in its own frame: the keypoint's lifted 3D
// point, whose direction (x/z, y/z) and depth z are what was measured.
struct BundleObservation {
  int camera = 0;
  int point = 0;
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();
  double depth_sigma = 0;  // m; 0 = the Kinect's at the measured depth (depth_noise_coeff)
};

struct BundleResult {
  bool success = false;  // the solver ran and ended with a usable solution
  int iterations = 0;
  double initial_cost = 0, final_cost = 0;  // robust cost, summed over observations
};

// The whitened residual of one observation: the point moved into the camera (cam_from_world *
// point) against `measured`, as (x/z, y/z) in pixels over pixel_sigma and z over the Kinect's
// sigma at the measured depth (or depth_sigma when > 0). With d_pose: its derivative by a
// perturbation (translation, rotation) applied on the left of cam_from_world (exp(delta) *
// cam_from_world); with d_point: by the point.
Eigen::Vector3d BundleResidual(const BundleOptions& options, const Rigid3d& cam_from_world,
                               const Eigen::Vector3d& point, const Eigen::Vector3d& measured,
                               double depth_sigma = 0,
                               Eigen::Matrix<double, 3, 6>* d_pose = nullptr,
                               Eigen::Matrix3d* d_point = nullptr);

// Refines the cameras not fixed and all the points in place. Observations of a point in front
// of no camera are the caller's to leave out. Deterministic: one thread.
BundleResult BundleAdjust(const BundleOptions& options, std::vector<BundleCamera>* cameras,
                          std::vector<Eigen::Vector3d>* points,
                          const std::vector<BundleObservation>& observations);

}  // namespace rgbdvo
