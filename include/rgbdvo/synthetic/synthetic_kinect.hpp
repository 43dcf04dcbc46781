#pragma once
// Synthetic Kinect v1 recordings in the fakenect layout, for tests and demos without a device.
// The colour camera renders the synthetic scene (synthetic.hpp); the IR camera, offset from it
// and with its own intrinsics, renders Z-depth, which is encoded as raw 11-bit disparity
// (kinect_depth.hpp), exactly what a Kinect v1 sends through libfreenect.
//
// The paper's linear colour->IR mapping (eq. 1) cannot be exact for an offset camera: with the
// IR camera at o = (ox, oy, 0) in the colour frame,
//   u_ir = A u + B - fx_ir ox (1/Z - 1/Z_ref),   A = fx_ir / fx_rgb,
//   B = cx_ir - A cx_rgb - fx_ir ox / Z_ref         (and likewise v, C, D with oy),
// so the mapping is exact at the reference depth Z_ref and off by fx_ir |o| |1/Z - 1/Z_ref|
// pixels elsewhere (3.9 px at 1.5 m and 2.9 px at 5 m for fx_ir = 580, |o| = 2.5 cm,
// Z_ref = 2.5 m). In 3D this shifts a point by |o| |1 - Z/Z_ref| sideways: a fixed 1 % shear
// of the scene per metre of depth, which the rigid motion estimate absorbs almost entirely.

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"

namespace rgbdvo {

struct SyntheticKinectOptions {
  PinholeCamera color{525.0, 525.0, 319.5, 239.5, 640, 480};  // colour camera
  PinholeCamera ir{580.0, 580.0, 320.0, 240.0, 640, 480};     // IR (depth) camera
  Eigen::Vector3d ir_in_color{0.025, 0.0, 0.0};  // IR camera centre in the colour frame, m
  double reference_depth_m = 2.5;                // where eq. 1 is exact, m
  int64_t start_us = 1700000000000000;           // wall clock of the first frame, us
  int64_t period_us = 33333;                     // frame period (30 Hz), us
  bool accelerometer = true;                     // write an a- entry per frame
  // The accelerometer reads the apparent gravity g - a in the colour camera's frame, in the
  // Kinect's axes and counts (kinect_accelerometer.hpp): with camera_acceleration, a is the
  // camera's acceleration from second differences of the poses (the centripetal v omega in a
  // robot's turns); otherwise a = 0.
  bool camera_acceleration = false;
  // Gaussian noise on Z with sigma = 1.425e-3 Z^2 m (Khoshelham & Elberink 2012), drawn from
  // noise_seed, before the raw 11-bit disparity quantisation.
  bool depth_noise = false;
  uint32_t noise_seed = 1;
  void Check() const;
};

// Adds the Kinect's depth noise to a CV_32FC1 depth image in metres: Gaussian on Z with sigma
// = kKinectDepthNoiseCoeff Z^2 (Khoshelham & Elberink 2012), drawn from `rng` pixel by pixel in
// row order; pixels without a reading (0) stay 0.
void AddKinectDepthNoise(cv::RNG& rng, cv::Mat* depth_m);

// The calibration matching the simulation, K_ir = the IR intrinsics. Eq. 1 as above (exact at
// the reference depth), or with depth_aware the mapping exact at every depth: A, C as above,
// B = cx_ir - A cx_rgb, D = cy_ir - C cy_rgb, s_u = -fx_ir ox, s_v = -fy_ir oy.
Calibration SyntheticKinectCalibration(const SyntheticKinectOptions& options,
                                       bool depth_aware = false);

// MakeSmoothPath moved 2 m into the room, so the scene lies about 0.4-2.5 m away, the Kinect's
// working range, where one raw depth step is under 2 cm. (From the default start the far wall
// is 4 m away; there a step is 5 cm, which hides the depth change of the small rotations.)
std::vector<Rigid3d> MakeKinectRangePath(int n);

// Writes, into the new folder (refused if not empty, like every recording), one r-, a- and
// d- entry per pose of `world_from_color` (colour at t_k, accelerometer at t_k + 0.3 ms, depth
// at t_k + 1 ms, t_k = start + k * period), plus calib.yaml (the calibration above) and
// calib_depth_aware.yaml (the exact depth-aware one) and groundtruth.txt (TUM format: depth
// timestamp and the colour camera's pose relative to its first pose, as rgbdvo reports poses).
// Returns those poses (color0_from_colork).
std::vector<Rigid3d> WriteSyntheticKinectRecording(const std::string& folder,
                                                   const SyntheticScene& scene,
                                                   const SyntheticKinectOptions& options,
                                                   const std::vector<Rigid3d>& world_from_color);

}  // namespace rgbdvo
