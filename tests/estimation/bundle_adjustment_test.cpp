#include "rgbdvo/estimation/bundle_adjustment.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace rgbdvo;

namespace {

constexpr double kFocalPx = 520;

// exp(delta) * pose with delta = (translation, rotation): the perturbation BundleResidual's
// d_pose is taken by.
Rigid3d PerturbLeft(const Rigid3d& pose, const Eigen::Matrix<double, 6, 1>& delta) {
  Rigid3d step = Rigid3d::Identity();
  const Eigen::Vector3d phi = delta.tail<3>();
  if (phi.norm() > 0) step.linear() = Eigen::AngleAxisd(phi.norm(), phi.normalized()).matrix();
  step.translation() = delta.head<3>();
  return step * pose;
}

Rigid3d Pose(double yaw_rad, const Eigen::Vector3d& t) {
  Rigid3d pose = Rigid3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(0.1 * yaw_rad, Eigen::Vector3d::UnitX()))
                      .matrix();
  pose.translation() = t;
  return pose;
}

// The point as the camera measures it: direction off by pixel noise, depth by the Kinect's.
Eigen::Vector3d Measure(std::mt19937& rng, const Rigid3d& world_from_cam,
                        const Eigen::Vector3d& world, double pixel_sigma) {
  std::normal_distribution<double> n(0, 1);
  const Eigen::Vector3d q = world_from_cam.inverse() * world;
  const double z = q.z() + n(rng) * kKinectDepthNoiseCoeff * q.z() * q.z();
  return {(q.x() / q.z() + n(rng) * pixel_sigma / kFocalPx) * z,
          (q.y() / q.z() + n(rng) * pixel_sigma / kFocalPx) * z, z};
}

double PositionError(const Rigid3d& a, const Rigid3d& b) {
  return (a.translation() - b.translation()).norm();
}

}  // namespace

TEST_CASE("The bundle residual's derivatives match numerical ones", "[bundle_adjustment]") {
  BundleOptions options;
  options.focal_px = kFocalPx;
  const Rigid3d cam_from_world = Pose(0.3, {0.2, -0.1, 0.4});
  const Eigen::Vector3d point(0.4, -0.3, 2.5);
  const Eigen::Vector3d measured = cam_from_world * point + Eigen::Vector3d(0.01, -0.02, 0.03);
  Eigen::Matrix<double, 3, 6> d_pose;
  Eigen::Matrix3d d_point;
  const Eigen::Vector3d r0 =
      BundleResidual(options, cam_from_world, point, measured, 0, &d_pose, &d_point);
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
    delta[k] = h;
    const Eigen::Vector3d plus =
        BundleResidual(options, PerturbLeft(cam_from_world, delta), point, measured);
    const Eigen::Vector3d minus =
        BundleResidual(options, PerturbLeft(cam_from_world, -delta), point, measured);
    const Eigen::Vector3d numeric = (plus - minus) / (2 * h);
    CHECK((numeric - d_pose.col(k)).norm() <= 1e-5 * (1 + numeric.norm()));
  }
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(k);
    const Eigen::Vector3d numeric =
        (BundleResidual(options, cam_from_world, point + step, measured) -
         BundleResidual(options, cam_from_world, point - step, measured)) /
        (2 * h);
    CHECK((numeric - d_point.col(k)).norm() <= 1e-5 * (1 + numeric.norm()));
  }
  // Whitened: pixels over pixel_sigma, depth over the Kinect's sigma at the measured depth.
  const Eigen::Vector3d q = cam_from_world * point;
  CHECK(r0.x() == Approx(kFocalPx * (q.x() / q.z() - measured.x() / measured.z())));
  CHECK(r0.z() ==
        Approx((q.z() - measured.z()) / (kKinectDepthNoiseCoeff * measured.z() * measured.z())));
}

TEST_CASE("Bundle adjustment brings disturbed poses and points back to the true ones",
          "[bundle_adjustment]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-1.0, 1.0), depth(1.0, 3.0);
  std::normal_distribution<double> n(0, 1);
  std::vector<Rigid3d> truth;
  truth.reserve(5);
  for (int c = 0; c < 5; ++c) truth.push_back(Pose(0.05 * c, {0.1 * c, 0.02 * c, 0.05 * c}));
  std::vector<Eigen::Vector3d> true_points;
  for (int i = 0; i < 200; ++i) {
    const double z = depth(rng);
    const double v = xy(rng);  // one draw per statement, last first: the same on every compiler
    const double u = xy(rng);
    true_points.emplace_back(u * z * 0.5 + 0.2, v * z * 0.4, z);
  }
  BundleOptions options;
  options.focal_px = kFocalPx;
  std::vector<BundleObservation> observations;
  for (int c = 0; c < 5; ++c)
    for (int i = 0; i < 200; ++i)
      observations.push_back({c, i, Measure(rng, truth[c], true_points[i], 1.0)});
  // The first camera fixed (the gauge); the others 2-3 cm and about a degree off, the points
  // where the first camera measured them.
  std::vector<BundleCamera> cameras;
  for (int c = 0; c < 5; ++c) {
    Eigen::Matrix<double, 6, 1> off;
    off << 0.02 * n(rng), 0.02 * n(rng), 0.02 * n(rng), 0.02 * n(rng), 0.02 * n(rng), 0.02 * n(rng);
    cameras.push_back({c == 0 ? truth[c] : PerturbLeft(truth[c], off), c == 0});
  }
  std::vector<Eigen::Vector3d> points;
  points.reserve(200);
  for (int i = 0; i < 200; ++i) points.push_back(truth[0] * observations[i].measured);
  double before = 0;
  for (int c = 1; c < 5; ++c) before += PositionError(cameras[c].world_from_cam, truth[c]);
  const BundleResult result = BundleAdjust(options, &cameras, &points, observations);
  REQUIRE(result.success);
  CHECK(result.final_cost < result.initial_cost);
  CHECK(cameras[0].world_from_cam.isApprox(truth[0]));  // fixed stays
  double after = 0;
  for (int c = 1; c < 5; ++c) {
    after += PositionError(cameras[c].world_from_cam, truth[c]);
    CHECK(PositionError(cameras[c].world_from_cam, truth[c]) < 0.003);
    CHECK(Eigen::AngleAxisd(cameras[c].world_from_cam.linear().transpose() * truth[c].linear())
              .angle() < 0.002);
  }
  CHECK(after < 0.1 * before);
}

TEST_CASE("Bundle adjustment shrugs off a wrong observation (Huber)", "[bundle_adjustment]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(-1.0, 1.0), depth(1.0, 3.0);
  const std::vector<Rigid3d> truth = {Pose(0, {0, 0, 0}), Pose(0.1, {0.1, 0, 0})};
  std::vector<Eigen::Vector3d> points;
  std::vector<BundleObservation> observations;
  for (int i = 0; i < 100; ++i) {
    const double z = depth(rng);
    const double v = xy(rng);  // one draw per statement, last first: the same on every compiler
    const double u = xy(rng);
    const Eigen::Vector3d p(u * z * 0.4, v * z * 0.3, z);
    points.push_back(p);
    for (int c = 0; c < 2; ++c) observations.push_back({c, i, Measure(rng, truth[c], p, 0.5)});
  }
  observations[1].measured += Eigen::Vector3d(0.3, 0.2, 0.1);  // a wrong association
  std::vector<BundleCamera> cameras = {{truth[0], true}, {truth[1], false}};
  BundleOptions options;
  options.focal_px = kFocalPx;
  REQUIRE(BundleAdjust(options, &cameras, &points, observations).success);
  CHECK(PositionError(cameras[1].world_from_cam, truth[1]) < 0.003);
}
