#include "rgbdvo/sensor/kinect_accelerometer.hpp"

namespace rgbdvo {

Eigen::Vector3d ApparentGravityFromKinectAccel(const Eigen::Vector3d& reading_mps2) {
  return {reading_mps2.x(), reading_mps2.y(), -reading_mps2.z()};
}

Eigen::Vector3d KinectAccelFromApparentGravity(const Eigen::Vector3d& gravity_in_cam) {
  return {gravity_in_cam.x(), gravity_in_cam.y(), -gravity_in_cam.z()};
}

Eigen::Vector3d KinectAccelFromCounts(int16_t x, int16_t y, int16_t z) {
  return Eigen::Vector3d(x, y, z) * (kStandardGravity / kKinectAccelCountsPerG);
}

}  // namespace rgbdvo
