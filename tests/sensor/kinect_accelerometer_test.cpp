#include "rgbdvo/sensor/kinect_accelerometer.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

TEST_CASE("Kinect accelerometer counts are libfreenect's m/s^2") {
  const Eigen::Vector3d a = KinectAccelFromCounts(0, 819, -819);
  CHECK(a.x() == 0);
  CHECK(a.y() == Approx(kStandardGravity));
  CHECK(a.z() == Approx(-kStandardGravity));
}

TEST_CASE("A Kinect reading turns into apparent gravity in the camera frame and back") {
  const Eigen::Vector3d reading(0.5, 7.2, -6.6);
  const Eigen::Vector3d g = ApparentGravityFromKinectAccel(reading);
  CHECK(g.isApprox(Eigen::Vector3d(0.5, 7.2, 6.6)));
  CHECK(KinectAccelFromApparentGravity(g).isApprox(reading));
  // TUM fr1/xyz's first reading, with the camera looking down at the desk (ground truth: about
  // 40 degrees below level): down is below and ahead of the camera, +y and +z.
  const Eigen::Vector3d first = ApparentGravityFromKinectAccel({0.143687, 7.268176, -6.657506});
  CHECK(first.y() > 0);
  CHECK(first.z() > 0);
}
