#pragma once
// A constant-velocity motion prior: where the camera should be at the current frame, from the
// last two accepted poses and the frame times (used to guide the matching).

#include "rgbdvo/geometry/geometry.hpp"

namespace rgbdvo {

// b_from_a scaled by s along its own motion: the rotation's angle-axis vector times s, the
// translation times s (first order; s = 1 gives b_from_a, s = 0 the identity).
Rigid3d ScaleMotion(const Rigid3d& b_from_a, double s);

// The weighted mean of two poses of one frame: b * ScaleMotion(b^-1 * a, weight_a), from b
// toward a along the geodesic (the rotation interpolated about its axis, the translations
// averaged). weight_a = 1 gives a, 0 gives b.
Rigid3d WeightedMean(const Rigid3d& a, const Rigid3d& b, double weight_a);

// world_from_cur predicted at time t_cur by constant velocity in the camera frame:
// world_from_last * ScaleMotion(before_from_last, (t_cur - t_last) / (t_last - t_before)), with
// before_from_last = world_from_before^-1 * world_from_last. Without a usable interval
// (t_last <= t_before) the velocity is taken as zero and world_from_last is returned.
Rigid3d PredictConstantVelocity(const Rigid3d& world_from_before, double t_before,
                                const Rigid3d& world_from_last, double t_last, double t_cur);

// A constant velocity in the camera's own frame, per second: the rotation's angle-axis vector
// (rad/s) and the translation (m/s) of cam_t_from_cam_t+1s, in ScaleMotion's first-order sense.
struct Velocity {
  Eigen::Vector3d rotation_per_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d translation_per_s = Eigen::Vector3d::Zero();
};

// The velocity of before_from_last done in `seconds` (zero unless seconds > 0).
Velocity VelocityOf(const Rigid3d& before_from_last, double seconds);

// world_from_cam moved dt seconds along v (dt < 0: back): world_from_cam * M(dt), M(dt) the
// rotation by v.rotation_per_s * dt and the translation v.translation_per_s * dt, so that
// MoveAtVelocity(world_from_last, VelocityOf(before_from_last, span), dt) equals
// world_from_last * ScaleMotion(before_from_last, dt / span).
Rigid3d MoveAtVelocity(const Rigid3d& world_from_cam, const Velocity& v, double dt);

}  // namespace rgbdvo
