#include "rgbdvo/geometry/geometry.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace rgbdvo {

double RotationAngleRad(const Eigen::Matrix3d& R) {
  // atan2 of |sin| and cos: well conditioned near 0 and near pi, unlike acos of the trace.
  const Eigen::Vector3d axis_sin(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const double s = 0.5 * axis_sin.norm();
  const double c = 0.5 * (R.trace() - 1.0);
  return std::atan2(s, c);
}

double RotationAngleDeg(const Eigen::Matrix3d& R) { return RotationAngleRad(R) * 180.0 / M_PI; }

Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) S(2, 2) = -1;
  return svd.matrixU() * S * svd.matrixV().transpose();
}

Rigid3d MakeRigid(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
  Rigid3d T = Rigid3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

Eigen::Matrix3d AxisAngle(const Eigen::Vector3d& axis, double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
}

}  // namespace rgbdvo
