#pragma once
// The Kinect v1's accelerometer (a KXSD9 in the sensor head, read by libfreenect as the tilt
// state's accelerometer_x/y/z, 819 counts per g) and the colour camera's frame (x right, y down,
// z forward).
//
// An accelerometer at rest reads the apparent gravity g - a (a = its acceleration): here
// "apparent gravity" is the vector a plumb line would point along, down when the camera is
// still. libfreenect's readings in m/s^2 (freenect_get_mks_accel: counts / 819 * 9.80665; the
// values in TUM's accelerometer.txt, which ROS's kinect_aux passes on unchanged) are that vector
// with z reversed: apparent gravity in the camera = (ax, ay, -az). Measured on TUM fr1/xyz and
// the fast part of fr1/desk: with this sign the readings within 0.5 m/s^2 of g are 2.1 and 5.3
// degrees (median) from the down the ground truth's rotations predict; with x reversed too 3.5
// and 14.4 degrees.

#include <Eigen/Core>
#include <cstdint>

namespace rgbdvo {

constexpr double kStandardGravity = 9.80665;    // m/s^2 (libfreenect's GRAVITY)
constexpr double kKinectAccelCountsPerG = 819;  // libfreenect.h FREENECT_COUNTS_PER_G

// libfreenect's reading (m/s^2) -> apparent gravity in the colour camera's frame, m/s^2.
Eigen::Vector3d ApparentGravityFromKinectAccel(const Eigen::Vector3d& reading_mps2);
// The inverse: what the Kinect reports for this apparent gravity (the synthetic Kinect).
Eigen::Vector3d KinectAccelFromApparentGravity(const Eigen::Vector3d& gravity_in_cam);
// Raw counts (freenect_raw_tilt_state) -> m/s^2, as freenect_get_mks_accel.
Eigen::Vector3d KinectAccelFromCounts(int16_t x, int16_t y, int16_t z);

}  // namespace rgbdvo
