#include "rgbdvo/estimation/floor_plane.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "rgbdvo/estimation/planar_motion.hpp"
#include "rgbdvo/sensor/camera.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"

namespace rgbdvo {
namespace {

double InlierDistance(const FloorFitOptions& o, double z) {
  return std::max(o.min_inlier_m, 3 * kKinectDepthNoiseCoeff * z * z);
}

bool OnPlane(const FloorFitOptions& o, const Eigen::Vector3d& p, const Eigen::Vector3d& n,
             double h) {
  return std::abs(n.dot(p) - h) < InlierDistance(o, p.z());
}

int CountInliers(const FloorFitOptions& o, const std::vector<Eigen::Vector3d>& points,
                 const Eigen::Vector3d& n, double h) {
  return static_cast<int>(std::count_if(
      points.begin(), points.end(), [&](const Eigen::Vector3d& p) { return OnPlane(o, p, n, h); }));
}

}  // namespace

void FloorFitOptions::Check() const {
  if (pixel_step < 1) throw std::invalid_argument("FloorFitOptions.pixel_step must be >= 1");
  if (refinements < 1) throw std::invalid_argument("FloorFitOptions.refinements must be >= 1");
  if (max_trials < 1) throw std::invalid_argument("FloorFitOptions.max_trials must be >= 1");
  if (!(max_tilt_deg > 0 && max_tilt_deg < 90))
    throw std::invalid_argument("FloorFitOptions.max_tilt_deg must be in (0, 90)");
  if (!(min_inlier_m > 0)) throw std::invalid_argument("FloorFitOptions.min_inlier_m must be > 0");
  if (!(min_fraction > 0 && min_fraction <= 1))
    throw std::invalid_argument("FloorFitOptions.min_fraction must be in (0, 1]");
}

std::string FloorFit::Brief() const {
  if (!success) return "no floor: " + reason;
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << "floor " << height_m << " m below the camera, pitch "
    << std::setprecision(1) << pitch_deg << " deg, roll " << roll_deg << " deg (" << inliers
    << " of " << points << " points)";
  return s.str();
}

FloorFit FitFloor(const FloorFitOptions& o, const Calibration& calib, const cv::Mat& depth_m,
                  Rng& rng) {
  o.Check();
  if (depth_m.type() != CV_32FC1) throw std::invalid_argument("FitFloor: depth must be CV_32FC1");
  FloorFit fit;
  std::vector<Eigen::Vector3d> points;
  for (int v = o.pixel_step / 2; v < depth_m.rows; v += o.pixel_step)
    for (int u = o.pixel_step / 2; u < depth_m.cols; u += o.pixel_step)
      if (const std::optional<double> d = SampleDepth(calib, depth_m, {u, v}))
        points.push_back(BackProject(calib, {u, v}, *d));
  fit.points = static_cast<int>(points.size());
  if (points.size() < 3) {
    fit.reason = "no depth readings";
    return fit;
  }
  const double min_cos = std::cos(o.max_tilt_deg * M_PI / 180);
  std::uniform_int_distribution<size_t> pick(0, points.size() - 1);
  Eigen::Vector3d best_n = Eigen::Vector3d::UnitY();
  double best_h = 0;
  int best = 0;
  for (int trial = 0; trial < o.max_trials; ++trial) {
    const Eigen::Vector3d &a = points[pick(rng)], &b = points[pick(rng)], &c = points[pick(rng)];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (!(n.norm() > 1e-9)) continue;
    n.normalize();
    if (n.y() < 0) n = -n;  // pointing down
    const double h = n.dot(a);
    if (n.y() < min_cos || !(h > 0)) continue;  // too steep, or not below the camera
    const int count = CountInliers(o, points, n, h);
    if (count > best) best = count, best_n = n, best_h = h;
  }
  if (best < o.min_fraction * static_cast<double>(points.size())) {
    std::ostringstream why;
    why << "no plane within " << o.max_tilt_deg << " degrees of level below the camera holds "
        << 100 * o.min_fraction << " % of the depth readings (best: " << best << " of "
        << points.size() << ")";
    fit.reason = why.str();
    return fit;
  }
  // Weighted least squares through the inliers, re-selected with each new plane. A reading's
  // noise lies along its ray: sigma_z = c z^2 along p / z, of which the plane's normal sees
  // sigma_z (n . p) / z = c h z; so weights 1 / z^2.
  // The refits keep points within 3 of those sigmas (at least min_inlier_m): RANSAC's wider
  // test would let the foot of a far wall in (10 cm at 5 m).
  Eigen::Vector3d n = best_n;
  double h = best_h;
  const auto near_plane = [&](const Eigen::Vector3d& p) {
    return std::abs(n.dot(p) - h) <
           std::max(o.min_inlier_m, 3 * kKinectDepthNoiseCoeff * h * p.z());
  };
  for (int iteration = 0; iteration < o.refinements; ++iteration) {
    double weight_sum = 0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : points)
      if (near_plane(p)) {
        const double w = 1 / (p.z() * p.z());
        weight_sum += w;
        mean += w * p;
      }
    if (!(weight_sum > 0)) break;
    mean /= weight_sum;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3d& p : points)
      if (near_plane(p)) cov += (p - mean) * (p - mean).transpose() / (p.z() * p.z());
    n = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0);
    if (n.y() < 0) n = -n;
    h = n.dot(mean);
  }
  fit.normal_in_cam = n;
  fit.height_m = h;
  fit.inliers = CountInliers(o, points, n, h);
  fit.level_from_cam = LevelFromFloorNormal(n);
  const Eigen::Vector2d mount = MountFromFloorNormal(n);
  fit.pitch_deg = mount.x();
  fit.roll_deg = mount.y();
  fit.success = true;
  return fit;
}

}  // namespace rgbdvo
