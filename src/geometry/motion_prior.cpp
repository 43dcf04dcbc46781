#include "rgbdvo/geometry/motion_prior.hpp"

namespace rgbdvo {

Rigid3d ScaleMotion(const Rigid3d& b_from_a, double s) {
  const Eigen::AngleAxisd aa(b_from_a.linear());
  Rigid3d out = Rigid3d::Identity();
  out.linear() = Eigen::AngleAxisd(s * aa.angle(), aa.axis()).toRotationMatrix();
  out.translation() = s * b_from_a.translation();
  return out;
}

Rigid3d PredictConstantVelocity(const Rigid3d& world_from_before, double t_before,
                                const Rigid3d& world_from_last, double t_last, double t_cur) {
  if (!(t_last > t_before)) return world_from_last;
  const double s = (t_cur - t_last) / (t_last - t_before);
  return world_from_last * ScaleMotion(world_from_before.inverse() * world_from_last, s);
}

}  // namespace rgbdvo
