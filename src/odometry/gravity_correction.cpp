#include "rgbdvo/odometry/gravity_correction.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rgbdvo/sensor/kinect_accelerometer.hpp"

namespace rgbdvo {

void GravityOptions::Check() const {
  if (!(time_constant_s > 0))
    throw std::invalid_argument("GravityOptions.time_constant_s must be > 0");
  if (!(magnitude_sigma_mps2 > 0))
    throw std::invalid_argument("GravityOptions.magnitude_sigma_mps2 must be > 0");
}

GravityCorrection::GravityCorrection(const GravityOptions& options) : options_(options) {
  options_.Check();
}

std::optional<Eigen::Vector3d> GravityCorrection::down_in_world() const {
  if (!(down_sum_.norm() > 0)) return std::nullopt;
  return down_sum_.normalized();
}

Rigid3d GravityCorrection::Update(const Rigid3d& world_from_cam,
                                  const Eigen::Vector3d& gravity_in_cam, double time_s) {
  const double magnitude = gravity_in_cam.norm();
  if (!(magnitude > 0) || !gravity_in_cam.allFinite()) return Rigid3d::Identity();
  const double z = (magnitude - kStandardGravity) / options_.magnitude_sigma_mps2;
  const double weight = std::exp(-0.5 * z * z);
  if (readings_ == 0) first_time_ = last_time_ = time_s;
  const double dt_s = time_s - last_time_;
  last_time_ = time_s;
  ++readings_;
  weight_sum_ += weight;
  const Eigen::Vector3d measured_in_world = world_from_cam.linear() * (gravity_in_cam / magnitude);
  const bool measuring_down = time_s - first_time_ <= options_.time_constant_s;
  if (measuring_down) down_sum_ += weight * measured_in_world;
  const std::optional<Eigen::Vector3d> down = down_in_world();
  if (!down) return Rigid3d::Identity();
  // The turn taking the reading's down (in the world: measured_in_world) to the world's, about
  // their common perpendicular: the camera turns with it.
  const Eigen::Vector3d axis = measured_in_world.cross(*down);
  const double angle = std::atan2(axis.norm(), measured_in_world.dot(*down));
  max_tilt_deg_ = std::max(max_tilt_deg_, angle * 180 / M_PI);
  const double fraction = std::clamp(weight * dt_s / options_.time_constant_s, 0.0, 1.0);
  if (measuring_down || !(axis.norm() > 1e-12) || fraction <= 0) return Rigid3d::Identity();
  Rigid3d correction = Rigid3d::Identity();
  correction.linear() = Eigen::AngleAxisd(fraction * angle, axis.normalized()).toRotationMatrix();
  const Eigen::Vector3d centre = world_from_cam.translation();
  correction.translation() = centre - correction.linear() * centre;
  return correction;
}

}  // namespace rgbdvo
