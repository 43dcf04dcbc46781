// Laws of the rotation helpers, at the angles where naive formulas break (near 0 and near pi).
#include "rgbdvo/geometry/geometry.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "test_support.hpp"

using namespace rgbdvo;

TEST_CASE("RotationAngleRad returns the angle from 0 to pi, accurately at both ends") {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  for (double angle : {0.0, 1e-9, 1e-6, 1e-3, 0.5, 1.0, 2.0, M_PI - 1e-3, M_PI - 1e-6, M_PI}) {
    INFO("angle " << angle);
    const Eigen::Matrix3d R = AxisAngle(axis, angle);
    // Relative accuracy near 0 (acos of the trace loses it: 1e-9 rad would come out 0 or 2e-8),
    // absolute near pi.
    CHECK(std::abs(RotationAngleRad(R) - angle) <= 1e-12 + 1e-9 * angle);
    CHECK(RotationAngleRad(R.transpose()) == Approx(RotationAngleRad(R)).margin(1e-12));
    CHECK(RotationAngleDeg(R) == Approx(RotationAngleRad(R) * 180 / M_PI).margin(1e-12));
  }
  // Beyond pi the angle folds back: a turn by pi + x is a turn by pi - x about the other way.
  CHECK(RotationAngleRad(AxisAngle(axis, M_PI + 0.25)) == Approx(M_PI - 0.25).margin(1e-12));
}

TEST_CASE("NearestRotation keeps a rotation and repairs a perturbed or reflected one") {
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0, 1);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Matrix3d R = AxisAngle(test::RandomVector(rng, n), 3.0 * i / 50);
    CHECK((NearestRotation(R) - R).norm() < 1e-12);
    Eigen::Matrix3d noisy = R;
    for (int k = 0; k < 9; ++k) noisy(k / 3, k % 3) += 1e-3 * n(rng);
    const Eigen::Matrix3d Q = NearestRotation(noisy);
    CHECK((Q.transpose() * Q - Eigen::Matrix3d::Identity()).norm() < 1e-12);
    CHECK(Q.determinant() == Approx(1.0).margin(1e-12));
    CHECK((Q - R).norm() < 1e-2);  // near the rotation it was perturbed from
  }
  // A reflection has no rotation at its own distance: the nearest proper one flips one axis.
  const Eigen::Matrix3d reflection = Eigen::Vector3d(1, 1, -1).asDiagonal();
  CHECK(NearestRotation(reflection).determinant() == Approx(1.0).margin(1e-12));
}

TEST_CASE("MakeRigid normalises the quaternion and composes as p_b = b_from_a * p_a") {
  const Rigid3d T = MakeRigid(Eigen::Quaterniond(2, 0, 0, 0), Eigen::Vector3d(1, 2, 3));
  CHECK((T.linear() - Eigen::Matrix3d::Identity()).norm() < 1e-15);
  const Rigid3d turn = MakeRigid(Eigen::Quaterniond(AxisAngle({0, 0, 1}, M_PI / 2)), {0, 0, 0});
  const Eigen::Vector3d p = (T * turn) * Eigen::Vector3d(1, 0, 0);  // turned first, then moved
  CHECK((p - Eigen::Vector3d(1, 3, 3)).norm() < 1e-12);
}
