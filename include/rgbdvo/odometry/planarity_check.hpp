#pragma once
// Whether the planar motion model still holds: with --motion planar every frame's
// motion is also refined with all 6 degrees of freedom on the same inliers, and those 6-DOF
// motions are chained alongside (FrameResult::world_from_cam_6dof). On a flat floor that chain
// only wanders by the estimates' noise; on a ramp, a kerb or in a hand-held camera it tilts or
// climbs. This check compares it over a sliding window (the chain's own long-term drift, which
// the planar model exists to avoid, does not count) and says when the motion stops and starts
// again being planar.

#include <Eigen/Core>
#include <deque>
#include <optional>
#include <string>

#include "rgbdvo/odometry/odometry.hpp"

namespace rgbdvo {

struct PlanarityCheckOptions {
  // A robot on a flat floor tilts by its suspension's rocking (a degree or two) and does not
  // climb; the 6-DOF chain's noise over a second is below a degree and a centimetre (measured
  // on the synthetic robot recording, docs/decisions/0010-planar-motion.md). Beyond these
  // within window_s, the motion is not planar.
  double window_s = 1.0;      // seconds of colour time compared
  double max_tilt_deg = 5.0;  // change of the floor's normal in the 6-DOF chain, deg
  double max_climb_m = 0.05;  // change of height along the floor's normal, m
  void Check() const;         // throws std::invalid_argument naming the field
};

class PlanarityCheck {
 public:
  // normal_in_world: the floor's unit normal in the world (= first camera) frame.
  PlanarityCheck(const PlanarityCheckOptions& options, const Eigen::Vector3d& normal_in_world);
  // Feeds the next frame's result (frames without world_from_cam_6dof are skipped). Returns a
  // one-line warning when the motion leaves the plane ("motion not planar at t=... (frame N):
  // the 6-DOF estimate tilts 7.3 deg and climbs 0.012 m within 1.0 s; --motion planar assumes
  // a flat floor") and when it is back within half the bounds.
  std::optional<std::string> Add(const FrameResult& result);
  int off_plane_frames() const { return off_plane_frames_; }  // frames beyond the bounds
  int episodes() const { return episodes_; }

 private:
  struct Sample {
    double t;
    Eigen::Vector3d normal;    // the floor's normal as the 6-DOF chain's camera sees it, world
    Eigen::Vector3d position;  // the camera centre in the 6-DOF chain, world
  };
  PlanarityCheckOptions options_;
  Eigen::Vector3d normal_in_world_;
  std::deque<Sample> window_;
  bool off_ = false;
  double max_tilt_deg_ = 0, max_climb_m_ = 0;  // over the current episode
  int off_plane_frames_ = 0, episodes_ = 0;
};

}  // namespace rgbdvo
