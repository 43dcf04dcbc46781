#pragma once
// A recording's accelerometer readings and the apparent gravity at a frame's time
// (Frame::gravity_in_cam): TUM's accelerometer.txt (about 870 readings a second) or fakenect's
// a- entries (one per depth frame).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace rgbdvo {

struct AccelReading {
  double timestamp = 0;            // seconds (the recording's clock)
  Eigen::Vector3d gravity_in_cam;  // apparent gravity, colour camera frame, m/s^2
};

class AccelerometerTrack {
 public:
  AccelerometerTrack() = default;
  explicit AccelerometerTrack(std::vector<AccelReading> readings);  // any order
  // The mean of the readings within half a 30 Hz frame period of t (the reading averaged over
  // the frame it belongs to), else the nearest reading within one period; nullopt when none.
  std::optional<Eigen::Vector3d> GravityAt(double t) const;
  size_t size() const { return readings_.size(); }

 private:
  std::vector<AccelReading> readings_;  // by time
};

// TUM's accelerometer.txt: 'timestamp ax ay az' lines, m/s^2 in libfreenect's axes (turned into
// the camera frame by kinect_accelerometer.hpp); '#' comments and blank lines skipped. Throws
// std::runtime_error naming the file and line for an unreadable file or a malformed line.
std::vector<AccelReading> ReadTumAccelerometer(const std::string& path);

}  // namespace rgbdvo
