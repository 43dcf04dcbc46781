#include "rgbdvo/sensor/kinect_depth.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace rgbdvo {
namespace {

// Burrus (2011), OpenKinect wiki "Imaging Information": z = 1 / (raw * kSlope + kOffset).
constexpr double kSlope = -0.0030711016;
constexpr double kOffset = 3.3309495161;
// Largest raw value with a positive denominator.
constexpr int kMaxValidRaw = 1084;

const std::array<float, 2048>& Table() {
  static const std::array<float, 2048> table = [] {
    std::array<float, 2048> t{};
    for (int raw = 0; raw < 2048; ++raw) t[raw] = static_cast<float>(MetresFromKinectRaw(raw));
    return t;
  }();
  return table;
}

}  // namespace

double MetresFromKinectRaw(uint16_t raw) {
  if (raw > kMaxValidRaw) return 0.0;  // includes kKinectNoReading
  return 1.0 / (raw * kSlope + kOffset);
}

uint16_t KinectRawFromMetres(double z_m) {
  if (!(z_m > 0) || !std::isfinite(z_m)) return kKinectNoReading;
  const double raw = std::round((1.0 / z_m - kOffset) / kSlope);
  if (raw < 0 || raw > kMaxValidRaw) return kKinectNoReading;
  return static_cast<uint16_t>(raw);
}

cv::Mat DepthFromKinectRaw(const cv::Mat& raw) {
  if (raw.type() != CV_16UC1) throw std::invalid_argument("Kinect raw depth must be CV_16UC1");
  const std::array<float, 2048>& table = Table();
  cv::Mat depth(raw.size(), CV_32FC1);
  for (int v = 0; v < raw.rows; ++v) {
    const uint16_t* in = raw.ptr<uint16_t>(v);
    float* out = depth.ptr<float>(v);
    for (int u = 0; u < raw.cols; ++u) out[u] = in[u] < 2048 ? table[in[u]] : 0.0f;
  }
  return depth;
}

cv::Mat KinectRawFromDepth(const cv::Mat& depth_m) {
  if (depth_m.type() != CV_32FC1) throw std::invalid_argument("depth must be CV_32FC1 metres");
  cv::Mat raw(depth_m.size(), CV_16UC1);
  for (int v = 0; v < depth_m.rows; ++v) {
    const float* in = depth_m.ptr<float>(v);
    uint16_t* out = raw.ptr<uint16_t>(v);
    for (int u = 0; u < depth_m.cols; ++u) out[u] = KinectRawFromMetres(in[u]);
  }
  return raw;
}

}  // namespace rgbdvo
