#include "rgbdvo/geometry/motion_prior.hpp"

#include <catch2/catch.hpp>

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
