#include "rgbdvo/estimation/planar_motion.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace rgbdvo {

Rigid3d PlanarMotion(const Eigen::Matrix3d& level_from_cam, double yaw_rad, double x_m,
                     double z_m) {
  Rigid3d in_level = Rigid3d::Identity();
  in_level.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
  in_level.translation() = Eigen::Vector3d(x_m, 0, z_m);
  Rigid3d level = Rigid3d::Identity();
  level.linear() = level_from_cam;
  return level.inverse() * in_level * level;
}

Eigen::Matrix3d LevelFromFloorNormal(const Eigen::Vector3d& normal_in_cam) {
  return Eigen::Quaterniond::FromTwoVectors(normal_in_cam.normalized(), Eigen::Vector3d::UnitY())
      .toRotationMatrix();
}

Eigen::Vector3d FloorNormalFromMount(double pitch_deg, double roll_deg) {
  const double p = pitch_deg * M_PI / 180, r = roll_deg * M_PI / 180;
  return {std::sin(r), std::cos(r) * std::cos(p), std::cos(r) * std::sin(p)};
}

Eigen::Vector2d MountFromFloorNormal(const Eigen::Vector3d& n) {
  return {std::atan2(n.z(), n.y()) * 180 / M_PI,
          std::asin(std::clamp(n.x(), -1.0, 1.0)) * 180 / M_PI};
}

Rigid3d ProjectPlanar(const Eigen::Matrix3d& level_from_cam, const Rigid3d& prev_from_cur) {
  const Eigen::Matrix3d R = level_from_cam * prev_from_cur.linear() * level_from_cam.transpose();
  const Eigen::Vector3d t = level_from_cam * prev_from_cur.translation();
  // R_y(yaw) = [c 0 s; 0 1 0; -s 0 c]: the yaw maximising trace(R_y^T R).
  const double yaw = std::atan2(R(0, 2) - R(2, 0), R(0, 0) + R(2, 2));
  return PlanarMotion(level_from_cam, yaw, t.x(), t.z());
}

std::optional<Rigid3d> AlignPlanar(const Eigen::Matrix3d& level_from_cam,
                                   const std::vector<PointPair>& pairs,
                                   const std::vector<int>& indices) {
  const size_t n = indices.empty() ? pairs.size() : indices.size();
  if (n < 2) return std::nullopt;
  const auto pair_at = [&](size_t i) -> const PointPair& {
    return pairs[indices.empty() ? i : static_cast<size_t>(indices[i])];
  };
  // x-z coordinates in the level frame, and their centroids.
  std::vector<Eigen::Vector2d> a(n), b(n);
  Eigen::Vector2d a_mean = Eigen::Vector2d::Zero(), b_mean = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d pa = level_from_cam * pair_at(i).p_prev;
    const Eigen::Vector3d pb = level_from_cam * pair_at(i).p_cur;
    a[i] = {pa.x(), pa.z()};
    b[i] = {pb.x(), pb.z()};
    a_mean += a[i];
    b_mean += b[i];
  }
  a_mean /= static_cast<double>(n);
  b_mean /= static_cast<double>(n);
  double c = 0, s = 0, spread = 0;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d da = a[i] - a_mean, db = b[i] - b_mean;
    c += da.dot(db);
    s += da.x() * db.y() - da.y() * db.x();
    spread += db.squaredNorm();
  }
  if (!(spread > 1e-12)) return std::nullopt;  // the points coincide in x-z
  const double yaw = std::atan2(s, c);
  // R_y(yaw) maps (x, z) to (cos x + sin z, -sin x + cos z).
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const Eigen::Vector2d rotated(cy * b_mean.x() + sy * b_mean.y(),
                                -sy * b_mean.x() + cy * b_mean.y());
  const Eigen::Vector2d t = a_mean - rotated;
  return PlanarMotion(level_from_cam, yaw, t.x(), t.y());
}

RansacResult EstimatePlanarRansac(const RansacOptions& options,
                                  const Eigen::Matrix3d& level_from_cam,
                                  const std::vector<PointPair>& pairs, Rng& rng) {
  const MotionModel planar{
      2, 2, [&level_from_cam](const std::vector<PointPair>& p, const std::vector<int>& idx) {
        return AlignPlanar(level_from_cam, p, idx);
      }};
  return EstimateRansac(options, pairs, planar, rng);
}

}  // namespace rgbdvo
