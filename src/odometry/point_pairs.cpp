#include "rgbdvo/odometry/point_pairs.hpp"

#include <cmath>
#include <stdexcept>

#include "rgbdvo/sensor/camera.hpp"

namespace rgbdvo {

void LiftOptions::Check() const {
  if (!(max_depth_jump_ratio >= 0))
    throw std::invalid_argument("LiftOptions.max_depth_jump_ratio must be >= 0");
}

KeypointPoints LiftKeypoints(const Calibration& calib, const LiftOptions& options,
                             const cv::Mat& depth_m, const Features& features) {
  KeypointPoints points;
  points.reserve(features.size());
  for (const cv::KeyPoint& k : features.keypoints)
    points.push_back(
        LiftColorPixel(calib, depth_m, {k.pt.x, k.pt.y}, options.max_depth_jump_ratio));
  return points;
}

KeypointPoints LiftKeypointsAcrossTime(const Calibration& calib, const LiftOptions& options,
                                       const cv::Mat& depth_m, const Features& features,
                                       const Rigid3d& depth_from_color) {
  if (depth_from_color.matrix().isIdentity(0))
    return LiftKeypoints(calib, options, depth_m, features);
  const Rigid3d color_from_depth = depth_from_color.inverse();
  const auto lift_at =
      [&](const Eigen::Vector3d& p_in_depth_cam) -> std::optional<Eigen::Vector3d> {
    if (!(p_in_depth_cam.z() > 0)) return std::nullopt;
    const Eigen::Vector2d uv =
        IrToColor(calib, ProjectIr(calib, p_in_depth_cam), p_in_depth_cam.z());
    if (!uv.allFinite()) return std::nullopt;
    return LiftColorPixel(calib, depth_m, uv, options.max_depth_jump_ratio);
  };
  KeypointPoints points;
  points.reserve(features.size());
  for (const cv::KeyPoint& k : features.keypoints) {
    const Eigen::Vector2d uv(k.pt.x, k.pt.y);
    // The keypoint's ray at 1 m in the colour-time camera, turned with the rotation only.
    std::optional<Eigen::Vector3d> p =
        lift_at(depth_from_color.linear() * ColorRayPoint(calib, uv, 1.0));
    if (p) {
      // The depth found puts the point at Z = z_c in the colour-time camera; move it with the
      // whole motion, translation included, and look again.
      const double z_c = (color_from_depth * *p).z();
      if (z_c > 0) p = lift_at(depth_from_color * ColorRayPoint(calib, uv, z_c));
    }
    if (p) p = color_from_depth * *p;
    points.push_back(p);
  }
  return points;
}

std::vector<PointPair> PairMatches(const KeypointPoints& prev_points,
                                   const KeypointPoints& cur_points,
                                   const std::vector<cv::DMatch>& matches,
                                   std::vector<int>* match_of_pair) {
  std::vector<PointPair> pairs;
  pairs.reserve(matches.size());
  if (match_of_pair) match_of_pair->clear();
  for (size_t m = 0; m < matches.size(); ++m) {
    const std::optional<Eigen::Vector3d>& p_prev = prev_points.at(matches[m].queryIdx);
    const std::optional<Eigen::Vector3d>& p_cur = cur_points.at(matches[m].trainIdx);
    if (!p_prev || !p_cur) continue;
    pairs.push_back({*p_prev, *p_cur});
    if (match_of_pair) match_of_pair->push_back(static_cast<int>(m));
  }
  return pairs;
}

std::vector<std::optional<Eigen::Vector2d>> PredictKeypoints(const Calibration& calib,
                                                             const KeypointPoints& ref_points,
                                                             const Rigid3d& cur_from_ref) {
  std::vector<std::optional<Eigen::Vector2d>> out(ref_points.size());
  for (size_t i = 0; i < ref_points.size(); ++i) {
    if (!ref_points[i]) continue;
    const Eigen::Vector3d p_in_cur = cur_from_ref * *ref_points[i];
    if (!(p_in_cur.z() > 0)) continue;
    const Eigen::Vector2d uv = IrToColor(calib, ProjectIr(calib, p_in_cur), p_in_cur.z());
    if (uv.allFinite()) out[i] = uv;
  }
  return out;
}

std::vector<cv::Matx22f> PredictWarps(const Calibration& calib, const KeypointPoints& ref_points,
                                      const Rigid3d& cur_from_ref, double step_px) {
  std::vector<cv::Matx22f> warps(ref_points.size(), cv::Matx22f::eye());
  // A colour pixel's step is A (C) IR pixels: at depth z, A step / fx metres across.
  KeypointPoints three(3 * ref_points.size());
  for (size_t i = 0; i < ref_points.size(); ++i) {
    if (!ref_points[i]) continue;
    const Eigen::Vector3d& p = *ref_points[i];
    three[3 * i] = p;
    three[3 * i + 1] = p + Eigen::Vector3d(step_px * calib.A * p.z() / calib.fx, 0, 0);
    three[3 * i + 2] = p + Eigen::Vector3d(0, step_px * calib.C * p.z() / calib.fy, 0);
  }
  const std::vector<std::optional<Eigen::Vector2d>> before =
      PredictKeypoints(calib, three, Rigid3d::Identity());
  const std::vector<std::optional<Eigen::Vector2d>> after =
      PredictKeypoints(calib, three, cur_from_ref);
  for (size_t i = 0; i < ref_points.size(); ++i) {
    const size_t k = 3 * i;
    if (!before[k] || !before[k + 1] || !before[k + 2] || !after[k] || !after[k + 1] ||
        !after[k + 2])
      continue;
    Eigen::Matrix2d steps_before, steps_after;
    steps_before << *before[k + 1] - *before[k], *before[k + 2] - *before[k];
    steps_after << *after[k + 1] - *after[k], *after[k + 2] - *after[k];
    const double det = steps_before.determinant();
    if (!(std::abs(det) > 1e-6 * step_px * step_px)) continue;
    const Eigen::Matrix2d a = steps_after * steps_before.inverse();
    if (!a.allFinite()) continue;
    warps[i] = cv::Matx22f(static_cast<float>(a(0, 0)), static_cast<float>(a(0, 1)),
                           static_cast<float>(a(1, 0)), static_cast<float>(a(1, 1)));
  }
  return warps;
}

}  // namespace rgbdvo
