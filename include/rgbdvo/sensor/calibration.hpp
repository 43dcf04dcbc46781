#pragma once
// The camera calibration of paper section 2.1: the linear colour->IR mapping (eq. 1), the IR
// (depth) camera intrinsics K_ir (eq. 2) and the usable depth range. Stored as YAML (written by
// cv::FileStorage, read by a reader of its own) with top-level keys A, B, C, D, K_ir (3x3
// opencv-matrix), min_depth_m, max_depth_m and the optional s_u, s_v (the depth-aware term below),
// dist_ir (1x5: k1 k2 p1 p2 k3), depth_units_per_m and description. LoadCalibration also reads a
// ROS camera_info YAML file (camera_matrix, distortion_model, distortion_coefficients: a camera
// calibrated with ROS's camera_calibration), as the camera of registered depth: the identity
// mapping.

#include <array>
#include <string>

namespace rgbdvo {

struct Calibration {
  // u_ir = A * u_vis + B, v_ir = C * v_vis + D (paper eq. 1). Identity for registered depth.
  double A = 1.0;
  double B = 0.0;
  double C = 1.0;
  double D = 0.0;
  // The stereo disparity term eq. 1 leaves out (pixels * metres): the IR pixel that sees what
  // colour pixel (u, v) sees at depth z is (A u + B + s_u / z, C v + D + s_v / z). For an IR
  // camera at o = (o_x, o_y, 0) in the colour camera's frame, s_u = -f_ir,x o_x and
  // s_v = -f_ir,y o_y (Kinect v1: about -585 * 0.025 = -14.6 px m). Both 0 (the default, and
  // the paper): eq. 1, exact only at the depth where B and D were fitted.
  double s_u = 0.0;
  double s_v = 0.0;
  // K_ir: focal lengths and principal point of the depth image, pixels (paper eq. 3 values).
  double fx = 475.0;
  double fy = 475.0;
  double cx = 320.0;
  double cy = 240.0;
  // Lens distortion of the depth image's camera, OpenCV's model k1 k2 p1 p2 k3 (all 0 = none;
  // the paper neglects it). For registered depth it is the colour camera's distortion.
  std::array<double, 5> dist_ir = {0, 0, 0, 0, 0};
  // Depths outside [min_depth_m, max_depth_m] are treated as missing, metres.
  double min_depth_m = 0.4;
  double max_depth_m = 8.0;
  // Units per metre of 16-bit depth images stored with this camera (TUM: 5000; 0 = not given).
  // A recording's depth scale belongs to the camera that made it, not to a command line:
  // `rgbdvo run` takes it from here unless --depth-scale is given.
  double depth_units_per_m = 0;
  // Free text kept with the file (where the numbers came from).
  std::string description;

  bool HasDisparityTerm() const { return s_u != 0.0 || s_v != 0.0; }
  void Check() const;  // throws std::invalid_argument naming the field and the rule it broke
};

// Throws std::runtime_error naming the file if it cannot be read or a field is missing/invalid.
Calibration LoadCalibration(const std::string& path);
// Throws std::runtime_error naming the file if it cannot be written.
void SaveCalibration(const Calibration& calib, const std::string& path);

}  // namespace rgbdvo
