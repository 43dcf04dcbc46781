#include "rgbdvo/odometry/planarity_check.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace rgbdvo {

void PlanarityCheckOptions::Check() const {
  if (!(window_s > 0)) throw std::invalid_argument("PlanarityCheckOptions.window_s must be > 0");
  if (!(max_tilt_deg > 0))
    throw std::invalid_argument("PlanarityCheckOptions.max_tilt_deg must be > 0");
  if (!(max_climb_m > 0))
    throw std::invalid_argument("PlanarityCheckOptions.max_climb_m must be > 0");
}

PlanarityCheck::PlanarityCheck(const PlanarityCheckOptions& options,
                               const Eigen::Vector3d& normal_in_world)
    : options_(options), normal_in_world_(normal_in_world.normalized()) {
  options_.Check();
}

std::optional<std::string> PlanarityCheck::Add(const FrameResult& r) {
  if (!r.world_from_cam_6dof) return std::nullopt;
  // In the planar chain the camera sees the floor's normal as normal_in_world (its rotation
  // keeps it); the 6-DOF chain's camera, turned by R6 R^T, sees it turned likewise.
  const Rigid3d& six = *r.world_from_cam_6dof;
  const Eigen::Vector3d normal =
      six.linear() * r.world_from_cam.linear().transpose() * normal_in_world_;
  window_.push_back({r.timestamp, normal, six.translation()});
  while (window_.size() > 1 && r.timestamp - window_.front().t > options_.window_s)
    window_.pop_front();
  double tilt_deg = 0, climb_m = 0;
  for (const Sample& s : window_) {
    tilt_deg =
        std::max(tilt_deg, std::acos(std::clamp(s.normal.dot(normal), -1.0, 1.0)) * 180 / M_PI);
    // Along the floor as the chain saw it then: its slow tilt drift turns no travel into climb.
    climb_m = std::max(climb_m, std::abs(s.normal.dot(window_.back().position - s.position)));
  }
  const bool beyond = tilt_deg > options_.max_tilt_deg || climb_m > options_.max_climb_m;
  const bool within_half =
      tilt_deg < 0.5 * options_.max_tilt_deg && climb_m < 0.5 * options_.max_climb_m;
  std::ostringstream s;
  s.setf(std::ios::fixed);
  if (off_ && within_half) {
    off_ = false;
    s << std::setprecision(3) << "motion planar again at t=" << r.timestamp << " (frame " << r.frame
      << "); it tilted up to " << std::setprecision(1) << max_tilt_deg_ << " deg and climbed up to "
      << std::setprecision(3) << max_climb_m_ << " m within " << std::setprecision(1)
      << options_.window_s << " s";
    return s.str();
  }
  if (!off_ && !beyond) return std::nullopt;
  ++off_plane_frames_;
  max_tilt_deg_ = off_ ? std::max(max_tilt_deg_, tilt_deg) : tilt_deg;
  max_climb_m_ = off_ ? std::max(max_climb_m_, climb_m) : climb_m;
  if (off_) return std::nullopt;
  off_ = true;
  ++episodes_;
  s << std::setprecision(3) << "motion not planar at t=" << r.timestamp << " (frame " << r.frame
    << "): the 6-DOF estimate tilts " << std::setprecision(1) << tilt_deg << " deg and climbs "
    << std::setprecision(3) << climb_m << " m within " << std::setprecision(1) << options_.window_s
    << " s; --motion planar assumes a flat floor and keeps the poses on it";
  return s.str();
}

}  // namespace rgbdvo
