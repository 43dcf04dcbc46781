#include "rgbdvo/sensor/camera.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace rgbdvo {

Eigen::Vector2d ColorToIr(const Calibration& c, const Eigen::Vector2d& uv, double z_m) {
  return {c.A * uv.x() + c.B + c.s_u / z_m, c.C * uv.y() + c.D + c.s_v / z_m};
}

Eigen::Vector2d IrToColor(const Calibration& c, const Eigen::Vector2d& uv_ir, double z_m) {
  return {(uv_ir.x() - c.B - c.s_u / z_m) / c.A, (uv_ir.y() - c.D - c.s_v / z_m) / c.C};
}

namespace {

bool HasDistortion(const Calibration& c) {
  for (double k : c.dist_ir)
    if (k != 0) return true;
  return false;
}

// OpenCV's (Brown-Conrady) model on normalised coordinates.
Eigen::Vector2d Distort(const Calibration& c, const Eigen::Vector2d& x) {
  const auto& [k1, k2, p1, p2, k3] = c.dist_ir;
  const double r2 = x.squaredNorm(), radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x.x() * radial + 2 * p1 * x.x() * x.y() + p2 * (r2 + 2 * x.x() * x.x()),
          x.y() * radial + p1 * (r2 + 2 * x.y() * x.y()) + 2 * p2 * x.x() * x.y()};
}

}  // namespace

Eigen::Vector3d ColorCenterInIr(const Calibration& c) {
  return Eigen::Vector3d(c.s_u / c.fx, c.s_v / c.fy, 0);
}

namespace {

// The root of Distort(x) = distorted by Newton's method from x = start: from x = distorted 3-4
// steps to a step below 1e-13 (a billionth of a pixel), where the fixed-point iteration
// x += distorted - Distort(x) contracts only by the distortion's slope (about 0.3 in a Kinect
// image's corners).
Eigen::Vector2d Undistort(const Calibration& c, const Eigen::Vector2d& distorted,
                          const Eigen::Vector2d& start) {
  const auto& [k1, k2, p1, p2, k3] = c.dist_ir;
  Eigen::Vector2d x = start;
  for (int i = 0; i < 20; ++i) {
    const double r2 = x.squaredNorm(), radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
    const double slope = 2 * (k1 + r2 * (2 * k2 + 3 * r2 * k3));  // d radial / d x, over x
    Eigen::Matrix2d J;
    J << radial + slope * x.x() * x.x() + 2 * p1 * x.y() + 6 * p2 * x.x(),
        slope * x.x() * x.y() + 2 * p1 * x.x() + 2 * p2 * x.y(),
        slope * x.x() * x.y() + 2 * p1 * x.x() + 2 * p2 * x.y(),
        radial + slope * x.y() * x.y() + 6 * p1 * x.y() + 2 * p2 * x.x();
    const Eigen::Vector2d step = J.inverse() * (distorted - Distort(c, x));
    if (!step.allFinite()) break;
    x += step;
    if (step.squaredNorm() < 1e-26) break;
  }
  return x;
}

}  // namespace

Eigen::Vector2d NormalizeIr(const Calibration& c, const Eigen::Vector2d& uv_ir) {
  Eigen::Vector2d distorted((uv_ir.x() - c.cx) / c.fx, (uv_ir.y() - c.cy) / c.fy);
  return HasDistortion(c) ? Undistort(c, distorted, distorted) : distorted;
}

Eigen::Vector2d NormalizeIr(const Calibration& c, const Eigen::Vector2d& uv_ir,
                            const Eigen::Vector2d& start) {
  Eigen::Vector2d distorted((uv_ir.x() - c.cx) / c.fx, (uv_ir.y() - c.cy) / c.fy);
  return HasDistortion(c) ? Undistort(c, distorted, start) : distorted;
}

Eigen::Vector3d BackProject(const Calibration& c, const Eigen::Vector2d& uv_ir, double depth_m) {
  const Eigen::Vector2d x = NormalizeIr(c, uv_ir);
  return {x.x() * depth_m, x.y() * depth_m, depth_m};
}

Eigen::Vector2d ProjectIr(const Calibration& c, const Eigen::Vector3d& p) {
  Eigen::Vector2d x(p.x() / p.z(), p.y() / p.z());
  if (HasDistortion(c)) x = Distort(c, x);
  return {c.fx * x.x() + c.cx, c.fy * x.y() + c.cy};
}

std::optional<double> SampleDepth(const Calibration& c, const cv::Mat& depth_m,
                                  const Eigen::Vector2d& uv_ir) {
  const double u = std::round(uv_ir.x()), v = std::round(uv_ir.y());
  if (!(u >= 0 && v >= 0 && u < depth_m.cols && v < depth_m.rows)) return std::nullopt;
  const double d = depth_m.at<float>(static_cast<int>(v), static_cast<int>(u));
  if (!(d > 0) || d < c.min_depth_m || d > c.max_depth_m) return std::nullopt;
  return d;
}

std::optional<double> SampleDepthBilinear(const Calibration& c, const cv::Mat& depth_m,
                                          const Eigen::Vector2d& uv_ir, double max_jump_ratio) {
  const double u = uv_ir.x(), v = uv_ir.y();
  if (!(u >= 0 && v >= 0 && u <= depth_m.cols - 1 && v <= depth_m.rows - 1)) return std::nullopt;
  const int u0 = std::min(static_cast<int>(u), depth_m.cols - 2);
  const int v0 = std::min(static_cast<int>(v), depth_m.rows - 2);
  const double au = u - u0, av = v - v0;
  const float* row0 = depth_m.ptr<float>(v0);
  const float* row1 = depth_m.ptr<float>(v0 + 1);
  const double d[4] = {row0[u0], row0[u0 + 1], row1[u0], row1[u0 + 1]};
  double lo = d[0], hi = d[0];
  for (double x : d) {
    if (!(x > 0) || x < c.min_depth_m || x > c.max_depth_m) return std::nullopt;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  if (hi - lo > max_jump_ratio * 0.25 * (d[0] + d[1] + d[2] + d[3])) return std::nullopt;
  return (1 - av) * ((1 - au) * d[0] + au * d[1]) + av * ((1 - au) * d[2] + au * d[3]);
}

Eigen::Vector3d ColorRayPoint(const Calibration& c, const Eigen::Vector2d& uv_vis, double z_m) {
  return BackProject(c, ColorToIr(c, uv_vis, z_m), z_m);
}

std::optional<Eigen::Vector2d> FindIrPixel(const Calibration& c, const cv::Mat& depth_m,
                                           const Eigen::Vector2d& uv_vis) {
  const Eigen::Vector2d at_infinity = ColorToIr(c, uv_vis);
  if (!c.HasDisparityTerm()) return at_infinity;
  // The ray's IR pixel at inverse depth w = 1/z is at_infinity + s w.
  const Eigen::Vector2d s(c.s_u, c.s_v);
  const double s_norm = s.norm();
  const double w_near = 1.0 / std::max(c.min_depth_m, 0.1), w_far = 1.0 / c.max_depth_m;
  const int steps = std::max(1, static_cast<int>(std::ceil(s_norm * (w_near - w_far) / 0.5)));
  Eigen::Vector2i last(-1, -1);
  for (int i = 0; i <= steps; ++i) {
    const double w = w_near - (w_near - w_far) * i / steps;
    const Eigen::Vector2d uv_ir = at_infinity + s * w;
    const Eigen::Vector2i pixel(static_cast<int>(std::lround(uv_ir.x())),
                                static_cast<int>(std::lround(uv_ir.y())));
    if (pixel == last) continue;
    last = pixel;
    const std::optional<double> d = SampleDepth(c, depth_m, uv_ir);
    if (d && s_norm * std::abs(1.0 / *d - w) <= 1.0) return ColorToIr(c, uv_vis, *d);
  }
  return std::nullopt;
}

std::optional<Eigen::Vector3d> LiftColorPixel(const Calibration& c, const cv::Mat& depth_m,
                                              const Eigen::Vector2d& uv_vis,
                                              double max_jump_ratio) {
  const std::optional<Eigen::Vector2d> uv_ir = FindIrPixel(c, depth_m, uv_vis);
  if (!uv_ir) return std::nullopt;
  const std::optional<double> d = max_jump_ratio > 0
                                      ? SampleDepthBilinear(c, depth_m, *uv_ir, max_jump_ratio)
                                      : SampleDepth(c, depth_m, *uv_ir);
  if (!d) return std::nullopt;
  if (c.HasDisparityTerm()) return ColorRayPoint(c, uv_vis, *d);
  return BackProject(c, *uv_ir, *d);
}

}  // namespace rgbdvo
