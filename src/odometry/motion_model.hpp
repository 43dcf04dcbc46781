#pragma once
// The motion model set up at the first reference (private to src/odometry).

#include <optional>
#include <string>

#include "rgbdvo/geometry/geometry.hpp"
#include "rgbdvo/odometry/odometry.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame.hpp"

namespace rgbdvo {

struct MotionModelSetup {
  // With the planar model: the level frame (planar_motion.hpp); none for 6-DOF.
  std::optional<Eigen::Matrix3d> level_from_cam;
  std::string brief;  // one line: "6-DOF", or "planar" with the floor's normal and its source
};

// The model options.motion names, with the planar model's floor found as motion.floor says:
// in `first`'s depth image, from its accelerometer reading, or from the given mount. Throws
// std::runtime_error, naming the frame and what to do, when the floor is not found.
MotionModelSetup SetUpMotionModel(const OdometryOptions& options, const Calibration& calib,
                                  const Frame& first);

}  // namespace rgbdvo
