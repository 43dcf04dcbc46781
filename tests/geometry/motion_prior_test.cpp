#include "rgbdvo/geometry/motion_prior.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

TEST_CASE("ScaleMotion: 1 is the motion, 0 the identity, 2 the rotation twice") {
  std::mt19937 rng(3);
  for (int k = 0; k < 20; ++k) {
    const Rigid3d T = RandomRigid(rng, 0.05 + 0.1 * k, 0.3);
    CHECK(RigidNear(ScaleMotion(T, 1), T, 1e-9, 1e-12));
    CHECK(RigidNear(ScaleMotion(T, 0), Rigid3d::Identity(), 1e-9, 1e-12));
    const Rigid3d twice = ScaleMotion(T, 2);
    CHECK(RotationErrorDeg(twice, T * T) < 1e-9);
    CHECK((twice.translation() - 2 * T.translation()).norm() < 1e-12);
    const Rigid3d half = ScaleMotion(T, 0.5);
    CHECK(RotationErrorDeg(half * half, T) < 1e-9);
    CHECK(RotationErrorDeg(ScaleMotion(T, -1), T.inverse()) < 1e-9);
  }
}

TEST_CASE("PredictConstantVelocity continues a constant motion, scaled by the frame times") {
  std::mt19937 rng(5);
  const Rigid3d step = RandomRigid(rng, 0.03, 0.02);  // per 1/30 s, in the camera frame
  const Rigid3d world_from_0 = RandomRigid(rng, 1.0, 2.0);
  const Rigid3d world_from_1 = world_from_0 * step;
  const double t0 = 10.0, t1 = t0 + 1 / 30.0;
  // One frame later: the same step again.
  CHECK(RigidNear(PredictConstantVelocity(world_from_0, t0, world_from_1, t1, t1 + 1 / 30.0),
                  world_from_1 * step, 1e-9, 1e-12));
  // Two frames later (one dropped): the rotation twice, the translation doubled.
  const Rigid3d two = PredictConstantVelocity(world_from_0, t0, world_from_1, t1, t1 + 2 / 30.0);
  CHECK(RotationErrorDeg(two, world_from_1 * step * step) < 1e-9);
  CHECK(TranslationError(two, world_from_1 * ScaleMotion(step, 2)) < 1e-12);
  // The same time as the last frame: no motion.
  CHECK(RigidNear(PredictConstantVelocity(world_from_0, t0, world_from_1, t1, t1), world_from_1,
                  1e-9, 1e-12));
  // Frames with the same time give no velocity: zero motion.
  CHECK(RigidNear(PredictConstantVelocity(world_from_0, t1, world_from_1, t1, t1 + 0.1),
                  world_from_1, 1e-12, 1e-12));
}

TEST_CASE("MoveAtVelocity moves a pose by the velocity times dt, in the camera's frame") {
  // Camera at (1, 2, 3) turned 90 degrees about z; 0.5 rad/s about z and 1 m/s along its own
  // x. In 20 ms: 90 deg + 0.01 rad about z, and 2 cm along its x, which is the world's y.
  Rigid3d world_from_cam = Rigid3d::Identity();
  world_from_cam.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  world_from_cam.translation() = Eigen::Vector3d(1, 2, 3);
  Velocity v;
  v.rotation_per_s = Eigen::Vector3d(0, 0, 0.5);
  v.translation_per_s = Eigen::Vector3d(1, 0, 0);
  Rigid3d expected = Rigid3d::Identity();
  expected.linear() = Eigen::AngleAxisd(M_PI / 2 + 0.01, Eigen::Vector3d::UnitZ()).matrix();
  expected.translation() = Eigen::Vector3d(1, 2.02, 3);
  CHECK(RigidNear(MoveAtVelocity(world_from_cam, v, 0.02), expected, 1e-9, 1e-12));
  // Back in time: the other way; zero dt or zero velocity: the pose itself.
  expected.linear() = Eigen::AngleAxisd(M_PI / 2 - 0.01, Eigen::Vector3d::UnitZ()).matrix();
  expected.translation() = Eigen::Vector3d(1, 1.98, 3);
  CHECK(RigidNear(MoveAtVelocity(world_from_cam, v, -0.02), expected, 1e-9, 1e-12));
  CHECK(RigidNear(MoveAtVelocity(world_from_cam, v, 0), world_from_cam, 1e-12, 1e-12));
  CHECK(RigidNear(MoveAtVelocity(world_from_cam, Velocity{}, 0.02), world_from_cam, 1e-12, 1e-12));
}

TEST_CASE("VelocityOf a motion, moved by, continues it as PredictConstantVelocity does") {
  std::mt19937 rng(9);
  for (int k = 0; k < 10; ++k) {
    const Rigid3d step = RandomRigid(rng, 0.05, 0.03);
    const Rigid3d world_from_0 = RandomRigid(rng, 1.0, 2.0), world_from_1 = world_from_0 * step;
    const double span = 1 / 30.0, dt = 0.012 * (k - 5) / 5;
    const Velocity v = VelocityOf(step, span);
    CHECK(RigidNear(MoveAtVelocity(world_from_1, v, dt),
                    PredictConstantVelocity(world_from_0, 0, world_from_1, span, span + dt), 1e-9,
                    1e-12));
  }
  const Velocity none = VelocityOf(RandomRigid(rng, 0.1, 0.1), 0);
  CHECK(none.rotation_per_s.norm() == 0);
  CHECK(none.translation_per_s.norm() == 0);
}

TEST_CASE("WeightedMean moves from one pose to the other along the geodesic") {
  const Rigid3d a = MakeRigid(Eigen::Quaterniond(AxisAngle(Eigen::Vector3d(1, 2, 3), 0.4)),
                              Eigen::Vector3d(0.3, -0.1, 0.2));
  const Rigid3d b = MakeRigid(Eigen::Quaterniond(AxisAngle(Eigen::Vector3d(-2, 1, 0.5), 0.9)),
                              Eigen::Vector3d(-0.1, 0.4, 1.0));
  const double apart = RotationAngleRad(a.linear().transpose() * b.linear());
  CHECK(WeightedMean(a, b, 1).isApprox(a, 1e-12));
  CHECK(WeightedMean(a, b, 0).isApprox(b, 1e-12));
  for (double w : {0.25, 0.5, 0.8}) {
    INFO("weight of a " << w);
    const Rigid3d m = WeightedMean(a, b, w);
    CHECK(RotationAngleRad(m.linear().transpose() * a.linear()) == Approx((1 - w) * apart));
    CHECK(RotationAngleRad(m.linear().transpose() * b.linear()) == Approx(w * apart));
    CHECK(m.translation().isApprox(w * a.translation() + (1 - w) * b.translation(), 1e-12));
    CHECK(m.linear().isUnitary(1e-12));
  }
}
