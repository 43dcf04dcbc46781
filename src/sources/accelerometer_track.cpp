#include "rgbdvo/sources/accelerometer_track.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/io/text.hpp"
#include "rgbdvo/sensor/kinect_accelerometer.hpp"
#include "rgbdvo/util/display_text.hpp"

namespace rgbdvo {

namespace {
constexpr double kFramePeriodS = 1.0 / 30;
}  // namespace

AccelerometerTrack::AccelerometerTrack(std::vector<AccelReading> readings)
    : readings_(std::move(readings)) {
  std::stable_sort(
      readings_.begin(), readings_.end(),
      [](const AccelReading& a, const AccelReading& b) { return a.timestamp < b.timestamp; });
}

std::optional<Eigen::Vector3d> AccelerometerTrack::GravityAt(double t) const {
  const auto by_time = [](const AccelReading& r, double s) { return r.timestamp < s; };
  const auto first =
      std::lower_bound(readings_.begin(), readings_.end(), t - kFramePeriodS / 2, by_time);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (auto it = first; it != readings_.end() && it->timestamp <= t + kFramePeriodS / 2; ++it) {
    sum += it->gravity_in_cam;
    ++n;
  }
  if (n > 0) return sum / n;
  // None within the frame: the nearest within a period, on either side.
  const auto after = std::lower_bound(readings_.begin(), readings_.end(), t, by_time);
  const AccelReading* nearest = nullptr;
  if (after != readings_.end()) nearest = &*after;
  if (after != readings_.begin() &&
      (!nearest || t - std::prev(after)->timestamp < nearest->timestamp - t))
    nearest = &*std::prev(after);
  if (nearest && std::abs(nearest->timestamp - t) <= kFramePeriodS) return nearest->gravity_in_cam;
  return std::nullopt;
}

std::vector<AccelReading> ReadTumAccelerometer(const std::string& path) {
  std::vector<AccelReading> readings;
  for (const ListLine& line : ReadListLines(path, "accelerometer file")) {
    std::istringstream fields(line.text);
    double t = 0;
    Eigen::Vector3d a;
    if (!(fields >> t >> a.x() >> a.y() >> a.z()) || !std::isfinite(t) || !a.allFinite())
      throw std::runtime_error(path + ":" + std::to_string(line.number) +
                               ": expected 'timestamp ax ay az', got '" + Excerpt(line.text) + "'");
    readings.push_back({t, ApparentGravityFromKinectAccel(a)});
  }
  return readings;
}

}  // namespace rgbdvo
