#include "rgbdvo/estimation/depth_term.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "rgbdvo/sensor/camera.hpp"

namespace rgbdvo {

cv::Mat DepthRays(const Calibration& calib, cv::Size size) {
  cv::Mat rays(size, CV_64FC2);
  // Each pixel's Newton iteration starts where the rays of the two pixels above it extrapolate
  // to, off only by the distortion's curvature over a pixel, where NormalizeIr's own start (the
  // distorted coordinates) is off by the whole distortion (3 px in TUM fr1's corners); the first
  // two rows start from NormalizeIr's rays. Started from the rows above, the pixels of a row are
  // independent and NormalizeIrRow interleaves their iterations.
  std::vector<Eigen::Vector2d> start(size.width), xy(size.width);
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      if (v < 2) {
        start[u] = NormalizeIr(calib, {u, v});
      } else {
        const cv::Vec2d &above = rays.at<cv::Vec2d>(v - 1, u),
                        &above2 = rays.at<cv::Vec2d>(v - 2, u);
        start[u] = {2 * above[0] - above2[0], 2 * above[1] - above2[1]};
      }
    }
    NormalizeIrRow(calib, v, size.width, start.data(), xy.data());
    cv::Vec2d* row = rays.ptr<cv::Vec2d>(v);
    for (int u = 0; u < size.width; ++u) row[u] = {xy[u].x(), xy[u].y()};
  }
  return rays;
}

std::vector<Eigen::Vector3d> SampleDepthPoints(const cv::Mat& rays, const cv::Mat& depth_m,
                                               const Rigid3d& cam_from_depth, int step) {
  std::vector<Eigen::Vector3d> points;
  for (int v = step / 2; v < depth_m.rows; v += step)
    for (int u = step / 2; u < depth_m.cols; u += step) {
      const float z = depth_m.at<float>(v, u);
      if (!(z > 0)) continue;
      const cv::Vec2d& r = rays.at<cv::Vec2d>(v, u);
      points.push_back(cam_from_depth * Eigen::Vector3d(r[0] * z, r[1] * z, z));
    }
  return points;
}

DepthPlaneTerm::DepthPlaneTerm(const Calibration& calib, const cv::Mat& rays,
                               const cv::Mat& ref_depth_m, const Rigid3d& ref_depth_from_cam,
                               const std::vector<Eigen::Vector3d>& points, double noise_coeff,
                               double max_jump_ratio)
    : calib_(calib),
      rays_(rays),
      depth_(ref_depth_m),
      depth_from_cam_(ref_depth_from_cam),
      points_(points),
      noise_coeff_(noise_coeff),
      max_jump_ratio_(max_jump_ratio) {}

bool DepthPlaneTerm::Residual(size_t i, const Rigid3d& T, double* r,
                              Eigen::Matrix<double, 1, 6>* J) const {
  constexpr int kH = 2;  // the surface's tangents from the readings this many pixels away
  const Eigen::Vector3d x = T * points_[i];  // in the reference camera
  const Eigen::Vector3d y = depth_from_cam_ * x;
  if (!(y.z() > 0)) return false;
  const Eigen::Vector2d uv = ProjectIr(calib_, y);
  const int u = static_cast<int>(std::lround(uv.x())), v = static_cast<int>(std::lround(uv.y()));
  if (!(u >= kH && v >= kH && u < depth_.cols - kH && v < depth_.rows - kH)) return false;
  const auto point = [&](int pu, int pv, Eigen::Vector3d* p) {
    const float z = depth_.at<float>(pv, pu);
    if (!(z > 0)) return false;
    const cv::Vec2d& ray = rays_.at<cv::Vec2d>(pv, pu);
    *p = Eigen::Vector3d(ray[0] * z, ray[1] * z, z);
    return true;
  };
  Eigen::Vector3d q, left, right, up, down;
  if (!point(u, v, &q) || !point(u - kH, v, &left) || !point(u + kH, v, &right) ||
      !point(u, v - kH, &up) || !point(u, v + kH, &down))
    return false;
  const double jump = max_jump_ratio_ * q.z();
  for (const Eigen::Vector3d* n : {&left, &right, &up, &down})
    if (std::abs(n->z() - q.z()) > jump) return false;
  Eigen::Vector3d normal = (right - left).cross(down - up);
  const double length = normal.norm();
  if (!(length > 0)) return false;
  normal /= length;
  // Both readings carry the sensor's depth noise (sigma_z = c z^2) along their rays.
  const double sigma = std::sqrt(2.0) * noise_coeff_ * q.z() * q.z();
  *r = normal.dot(y - q) / sigma;
  if (J) {
    // y = D Exp(delta) T p ~ D (x + omega x x + v): dy/d(omega, v) = R_D [-[x]x, I].
    const Eigen::RowVector3d nR = normal.transpose() * depth_from_cam_.linear() / sigma;
    J->head<3>() = x.cross(nR.transpose()).transpose();  // nR (-[x]x) = (x cross nR^T)^T
    J->tail<3>() = nR;
  }
  return true;
}

double EstimateDepthTermScale(const DepthPlaneTerm& term, const Rigid3d& ref_from_cur) {
  std::vector<double> residuals;
  residuals.reserve(term.size());
  for (size_t i = 0; i < term.size(); ++i) {
    double r;
    if (term.Residual(i, ref_from_cur, &r, nullptr)) residuals.push_back(std::abs(r));
  }
  if (residuals.empty()) return 1.0;
  auto mid = residuals.begin() + static_cast<std::ptrdiff_t>(residuals.size() / 2);
  std::nth_element(residuals.begin(), mid, residuals.end());
  constexpr double kMedianAbsNormal = 0.674;
  return std::max(1.0, *mid / kMedianAbsNormal);
}

}  // namespace rgbdvo
