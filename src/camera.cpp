#include "rgbdvo/camera.hpp"

#include <cmath>

namespace rgbdvo {

Eigen::Vector2d ColorToIr(const Calibration& c, const Eigen::Vector2d& uv) {
  return {c.A * uv.x() + c.B, c.C * uv.y() + c.D};
}

Eigen::Vector3d BackProject(const Calibration& c, const Eigen::Vector2d& uv_ir, double depth_m) {
  return {(uv_ir.x() - c.cx) / c.fx * depth_m, (uv_ir.y() - c.cy) / c.fy * depth_m, depth_m};
}

Eigen::Vector2d ProjectIr(const Calibration& c, const Eigen::Vector3d& p) {
  return {c.fx * p.x() / p.z() + c.cx, c.fy * p.y() / p.z() + c.cy};
}

std::optional<double> SampleDepth(const Calibration& c, const cv::Mat& depth_m,
                                  const Eigen::Vector2d& uv_ir) {
  const double u = std::round(uv_ir.x()), v = std::round(uv_ir.y());
  if (!(u >= 0 && v >= 0 && u < depth_m.cols && v < depth_m.rows)) return std::nullopt;
  const double d = depth_m.at<float>(static_cast<int>(v), static_cast<int>(u));
  if (!(d > 0) || d < c.min_depth_m || d > c.max_depth_m) return std::nullopt;
  return d;
}

std::optional<Eigen::Vector3d> LiftColorPixel(const Calibration& c, const cv::Mat& depth_m,
                                              const Eigen::Vector2d& uv_vis) {
  const Eigen::Vector2d uv_ir = ColorToIr(c, uv_vis);
  const std::optional<double> d = SampleDepth(c, depth_m, uv_ir);
  if (!d) return std::nullopt;
  return BackProject(c, uv_ir, *d);
}

}  // namespace rgbdvo
