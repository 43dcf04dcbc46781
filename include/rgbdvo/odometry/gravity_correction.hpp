#pragma once
// Roll and pitch against gravity (docs/decisions/0011-gravity.md): a complementary filter between
// the odometry's orientation, good over short times and drifting slowly, and the accelerometer's
// gravity, noisy (every acceleration of the camera tilts it) but without drift.
//
// The world's down is the weighted mean of the readings of the first time constant, turned into
// the world by the poses they were taken at (the odometry has drifted least then; a mean over
// the whole run would follow the drift it is meant to correct). From then on each frame's pose
// is turned about a horizontal axis through the camera's centre, so that its down moves toward
// the reading's by the fraction w * dt / time_constant of the angle between them (yaw and
// position unchanged). A hand-held
// camera's accelerations average out over such a time: their mean over T seconds is the change
// of velocity over T, so with 0.5 m/s of it the mean reading tilts by at most 0.5 / (g T) rad,
// 0.6 degrees at T = 5 s, while the odometry's tilt drifts by about 0.2 deg/s (TUM fr1 excerpts).
// The weight w = exp(-((|reading| - g) / sigma)^2 / 2) lowers readings that are clearly not
// gravity alone (a sideways acceleration changes the magnitude only to second order, which
// the time constant has to absorb).

#include <Eigen/Core>
#include <optional>

#include "rgbdvo/geometry/geometry.hpp"

namespace rgbdvo {

struct GravityOptions {
  double time_constant_s = 5;         // seconds for the pull to close 63 % of a tilt error
  double magnitude_sigma_mps2 = 0.5;  // the weight's width in |reading| - g, m/s^2
  void Check() const;
};

class GravityCorrection {
 public:
  explicit GravityCorrection(const GravityOptions& options);
  // The correction for a frame at world_from_cam, taken at time_s (seconds, increasing), whose
  // accelerometer read gravity_in_cam (apparent gravity, camera frame, m/s^2): a rotation about
  // the camera's centre in the world frame (left-multiply the frame's pose, and every pose the
  // odometry chains from, by it). Identity within the first time constant, whose readings set
  // the world's down.
  Rigid3d Update(const Rigid3d& world_from_cam, const Eigen::Vector3d& gravity_in_cam,
                 double time_s);
  // Unit down in the world frame, once a reading with weight came in.
  std::optional<Eigen::Vector3d> down_in_world() const;
  int readings() const { return readings_; }
  double mean_weight() const { return readings_ > 0 ? weight_sum_ / readings_ : 0; }
  // The largest angle between a frame's down and its reading, degrees.
  double max_tilt_deg() const { return max_tilt_deg_; }

 private:
  GravityOptions options_;
  Eigen::Vector3d down_sum_ = Eigen::Vector3d::Zero();
  double first_time_ = 0, last_time_ = 0;
  int readings_ = 0;
  double weight_sum_ = 0, max_tilt_deg_ = 0;
};

}  // namespace rgbdvo
