#include "rgbdvo/odometry/gravity_correction.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "rgbdvo/sensor/kinect_accelerometer.hpp"
#include "test_support.hpp"

using namespace rgbdvo;

namespace {

constexpr double kDt = 1.0 / 30;
const Eigen::Vector3d kDown(0, kStandardGravity, 0);  // the world's down: +y

Eigen::Matrix3d Turn(double deg, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(deg * M_PI / 180, axis.normalized()).toRotationMatrix();
}

// A pose whose y axis is `tilt_deg` off the world's down (about x), after a yaw.
Rigid3d TiltedPose(double yaw_deg, double tilt_deg, const Eigen::Vector3d& centre) {
  Rigid3d pose = Rigid3d::Identity();
  pose.linear() =
      Turn(yaw_deg, Eigen::Vector3d::UnitY()) * Turn(tilt_deg, Eigen::Vector3d::UnitX());
  pose.translation() = centre;
  return pose;
}

double TiltDeg(const Rigid3d& world_from_cam, const Eigen::Vector3d& true_down_in_cam) {
  const Eigen::Vector3d d = world_from_cam.linear() * true_down_in_cam.normalized();
  return std::acos(std::clamp(d.dot(Eigen::Vector3d::UnitY()), -1.0, 1.0)) * 180 / M_PI;
}

// Readings of the first time constant at a level pose: the world's down is +y.
void Settle(GravityCorrection* g, const GravityOptions& o, double* t) {
  while (*t < o.time_constant_s + kDt / 2) {  // the caller's clock, advanced as readings come
    CHECK(test::RigidNear(g->Update(Rigid3d::Identity(), kDown, *t), Rigid3d::Identity(), 0, 0));
    *t += kDt;
  }
}

}  // namespace

TEST_CASE("Gravity: the first time constant's readings set the world's down, uncorrected") {
  GravityOptions o;
  o.time_constant_s = 1;
  GravityCorrection g(o);
  double t = 0;
  // Readings tilted +-2 degrees in turn (a shaking hand): their mean is the down.
  for (int k = 0; k < 30; ++k, t += kDt) {
    const Eigen::Vector3d reading = Turn(k % 2 ? 2 : -2, Eigen::Vector3d::UnitZ()) * kDown;
    CHECK(test::RigidNear(g.Update(Rigid3d::Identity(), reading, t), Rigid3d::Identity(), 0, 0));
  }
  REQUIRE(g.down_in_world());
  CHECK(std::acos(g.down_in_world()->dot(Eigen::Vector3d::UnitY())) * 180 / M_PI < 0.1);
}

TEST_CASE("Gravity: a tilt error closes by 63 % in a time constant, turning about a level axis") {
  GravityOptions o;
  o.time_constant_s = 2;
  GravityCorrection g(o);
  double t = 0;
  Settle(&g, o, &t);
  // The camera is really level (after a 30 degree yaw) but its pose says 4 degrees of tilt.
  const Eigen::Vector3d centre(1, -0.5, 2);
  const Rigid3d truth = TiltedPose(30, 0, centre);
  Rigid3d pose = TiltedPose(30, 4, centre);
  const Eigen::Vector3d reading = truth.linear().transpose() * kDown;
  const Eigen::Vector3d forward_before = pose.linear().col(2);
  const double start = TiltDeg(pose, reading);
  CHECK(start == Approx(4).margin(1e-9));
  for (int k = 0; k < 60; ++k, t += kDt) pose = g.Update(pose, reading, t) * pose;
  // Discrete steps of dt / tau: (1 - 1/60)^60 = 0.364 of the error is left.
  CHECK(TiltDeg(pose, reading) == Approx(4 * std::pow(1 - kDt / 2, 60)).epsilon(0.01));
  // Turned about a level axis: the heading (forward on the level plane) and the centre stay.
  const Eigen::Vector3d forward = pose.linear().col(2);
  CHECK(std::atan2(forward.x(), forward.z()) ==
        Approx(std::atan2(forward_before.x(), forward_before.z())).margin(1e-9));
  CHECK((pose.translation() - centre).norm() < 1e-12);
}

TEST_CASE("Gravity: readings far from 1 g hardly move the pose") {
  GravityOptions o;
  o.time_constant_s = 1;
  GravityCorrection g(o);
  double t = 0;
  Settle(&g, o, &t);
  const Rigid3d pose = TiltedPose(0, 3, Eigen::Vector3d::Zero());
  const Eigen::Vector3d level = kDown;  // the truth: level
  const double full = TiltDeg(g.Update(pose, level, t) * pose, level);
  GravityCorrection g2(o);
  double t2 = 0;
  Settle(&g2, o, &t2);
  // 1.5 m/s^2 more than g (3 sigma): weight exp(-4.5) = 0.011.
  const double damped =
      TiltDeg(g2.Update(pose, level * (1 + 1.5 / kStandardGravity), t2) * pose, level);
  CHECK(3 - full == Approx(3 * kDt).epsilon(0.01));
  CHECK(3 - damped == Approx(3 * kDt * std::exp(-4.5)).epsilon(0.02));
}

TEST_CASE("Gravity options are checked") {
  GravityOptions o;
  o.time_constant_s = 0;
  CHECK_THROWS_WITH(GravityCorrection(o), Catch::Contains("time_constant_s"));
  o = GravityOptions{};
  o.magnitude_sigma_mps2 = -1;
  CHECK_THROWS_WITH(GravityCorrection(o), Catch::Contains("magnitude_sigma_mps2"));
}
