#include "rgbdvo/geometry/motion_prior.hpp"

namespace rgbdvo {

Rigid3d ScaleMotion(const Rigid3d& b_from_a, double s) {
  const Eigen::AngleAxisd aa(b_from_a.linear());
  Rigid3d out = Rigid3d::Identity();
  out.linear() = Eigen::AngleAxisd(s * aa.angle(), aa.axis()).toRotationMatrix();
  out.translation() = s * b_from_a.translation();
  return out;
}

Rigid3d WeightedMean(const Rigid3d& a, const Rigid3d& b, double weight_a) {
  return b * ScaleMotion(b.inverse() * a, weight_a);
}

Rigid3d PredictConstantVelocity(const Rigid3d& world_from_before, double t_before,
                                const Rigid3d& world_from_last, double t_last, double t_cur) {
  if (!(t_last > t_before)) return world_from_last;
  const double s = (t_cur - t_last) / (t_last - t_before);
  return world_from_last * ScaleMotion(world_from_before.inverse() * world_from_last, s);
}

Velocity VelocityOf(const Rigid3d& before_from_last, double seconds) {
  Velocity v;
  if (!(seconds > 0)) return v;
  const Eigen::AngleAxisd aa(before_from_last.linear());
  v.rotation_per_s = aa.angle() * aa.axis() / seconds;
  v.translation_per_s = before_from_last.translation() / seconds;
  return v;
}

Rigid3d MoveAtVelocity(const Rigid3d& world_from_cam, const Velocity& v, double dt) {
  const Eigen::Vector3d rotation = v.rotation_per_s * dt;
  Rigid3d motion = Rigid3d::Identity();
  const double angle = rotation.norm();
  if (angle > 0) motion.linear() = Eigen::AngleAxisd(angle, rotation / angle).toRotationMatrix();
  motion.translation() = v.translation_per_s * dt;
  return world_from_cam * motion;
}

}  // namespace rgbdvo
