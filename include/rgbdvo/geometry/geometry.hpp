#pragma once
// Small rigid-motion helpers shared by every layer. Poses are Eigen::Isometry3d and are named by
// their frames: `b_from_a` maps a point in frame a to frame b, p_b = b_from_a * p_a.

#include <Eigen/Geometry>

namespace rgbdvo {

using Rigid3d = Eigen::Isometry3d;

// Rotation angle of R in radians, in [0, pi]; robust near 0 and pi.
double RotationAngleRad(const Eigen::Matrix3d& R);
double RotationAngleDeg(const Eigen::Matrix3d& R);

// The rotation nearest to M in the Frobenius norm (SVD projection onto SO(3), det = +1).
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M);

// A rigid transform from a quaternion (any norm > 0) and a translation.
Rigid3d MakeRigid(const Eigen::Quaterniond& q, const Eigen::Vector3d& t);

// Rotation about `axis` (need not be unit) by `angle_rad`.
Eigen::Matrix3d AxisAngle(const Eigen::Vector3d& axis, double angle_rad);

}  // namespace rgbdvo
