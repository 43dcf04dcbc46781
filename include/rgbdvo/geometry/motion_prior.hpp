#pragma once
// A constant-velocity motion prior: where the camera should be at the current frame, from the
// last two accepted poses and the frame times (used to guide the matching).

#include "rgbdvo/geometry/geometry.hpp"

namespace rgbdvo {

// b_from_a scaled by s along its own motion: the rotation's angle-axis vector times s, the
// translation times s (first order; s = 1 gives b_from_a, s = 0 the identity).
Rigid3d ScaleMotion(const Rigid3d& b_from_a, double s);

// world_from_cur predicted at time t_cur by constant velocity in the camera frame:
// world_from_last * ScaleMotion(before_from_last, (t_cur - t_last) / (t_last - t_before)), with
// before_from_last = world_from_before^-1 * world_from_last. Without a usable interval
// (t_last <= t_before) the velocity is taken as zero and world_from_last is returned.
Rigid3d PredictConstantVelocity(const Rigid3d& world_from_before, double t_before,
                                const Rigid3d& world_from_last, double t_last, double t_cur);

}  // namespace rgbdvo
