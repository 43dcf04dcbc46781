#include "rgbdvo/sensor/depth_check.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <sstream>
#include <vector>

namespace rgbdvo {

namespace {

// Kinect v1 (and every PrimeSense sensor) measures disparity in 1/8 pixel steps with f = 580 px
// and a 7.5 cm baseline, so neighbouring depth values are z^2 / (8 * 580 * 0.075) apart:
// 0.00287 z^2 per metre (measured on TUM fr1/xyz and fr3/teddy: 0.00284-0.00291 from 1 to 5 m).
constexpr double kKinectStepPerZ2 = 1.0 / (8 * 580 * 0.075);

// Sorts positive floats as std::sort would, by their bit patterns (which order as unsigned
// integers do for positive floats) in three passes of 11 bits: a 640 x 480 depth image in about a
// tenth of std::sort's time.
void SortPositive(std::vector<float>* values) {
  if (values->empty()) return;  // memcpy is not given a null pointer, even for no bytes
  constexpr int kBits = 11, kBuckets = 1 << kBits;
  std::vector<uint32_t> keys(values->size()), other(values->size());
  std::memcpy(keys.data(), values->data(), values->size() * sizeof(float));
  for (int shift = 0; shift < 32; shift += kBits) {
    std::vector<size_t> start(kBuckets + 1, 0);
    for (uint32_t k : keys) ++start[((k >> shift) & (kBuckets - 1)) + 1];
    for (int b = 0; b < kBuckets; ++b) start[b + 1] += start[b];
    for (uint32_t k : keys) other[start[(k >> shift) & (kBuckets - 1)]++] = k;
    keys.swap(other);
  }
  std::memcpy(values->data(), keys.data(), keys.size() * sizeof(float));
}

// The depth image's quantisation: the median of (gap to the next smaller distinct value) / z^2
// over the nearer and the farther half of its distinct values. nullopt with fewer than 15
// distinct values in either half.
std::optional<std::pair<double, double>> StepPerZ2(const cv::Mat& depth_m) {
  std::vector<float> values;
  values.reserve(depth_m.total());
  for (int v = 0; v < depth_m.rows; ++v) {
    const float* row = depth_m.ptr<float>(v);
    float last = 0;  // a run of equal readings (a flat surface facing the camera) pushed once
    for (int u = 0; u < depth_m.cols; ++u)
      if (const float z = row[u]; z > 0 && z != last) values.push_back(last = z);
  }
  SortPositive(&values);
  values.erase(std::unique(values.begin(), values.end()), values.end());
  std::vector<double> near, far;
  for (size_t i = 1; i < values.size(); ++i) {
    const double z = values[i];
    (i < values.size() / 2 ? near : far).push_back((values[i] - values[i - 1]) / (z * z));
  }
  if (near.size() < 15 || far.size() < 15) return std::nullopt;
  const auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  return std::make_pair(median(near), median(far));
}

}  // namespace

std::optional<std::string> CheckDepthScale(const cv::Mat& depth_m, const Calibration& calib) {
  if (depth_m.type() != CV_32FC1) return std::nullopt;
  // Steps growing with z^2 (the same step / z^2 near and far) are a structured-light sensor's;
  // the size of that step says the scale. (A time-of-flight sensor's steps are even in z.)
  if (const auto steps = StepPerZ2(depth_m)) {
    const double ratio = steps->first / steps->second;
    const double factor = kKinectStepPerZ2 / (0.5 * (steps->first + steps->second));
    if (ratio > 0.8 && ratio < 1.25 && (factor > 1.5 || factor < 1 / 1.5)) {
      // Depths k times too large have steps k times larger, i.e. 1/k of c z^2 at those depths.
      const double k = factor;
      std::ostringstream s;
      s << std::fixed << std::setprecision(2)
        << "the depth steps grow with the square of depth as a Kinect v1's (structured light) "
           "do, but are "
        << 1 / k << " times its 0.00287 z^2: if this is Kinect v1 or PrimeSense data, depths and "
        << "the trajectory come out " << (k > 1 ? k : 1 / k) << " times too "
        << (k > 1 ? "large" : "small") << "; multiply the depth scale (units per metre) by " << k;
      return s.str();
    }
  }
  std::vector<float> readings;
  for (int v = 4; v < depth_m.rows; v += 8)
    for (int u = 4; u < depth_m.cols; u += 8)
      if (const float z = depth_m.at<float>(v, u); z > 0) readings.push_back(z);
  if (readings.size() < 100) return std::nullopt;
  const auto below = std::count_if(readings.begin(), readings.end(),
                                   [&](float z) { return z < calib.min_depth_m; });
  const auto above = std::count_if(readings.begin(), readings.end(),
                                   [&](float z) { return z > calib.max_depth_m; });
  const double n = static_cast<double>(readings.size());
  if (below + above <= n / 2) return std::nullopt;
  std::nth_element(readings.begin(), readings.begin() + readings.size() / 2, readings.end());
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << "median depth " << readings[readings.size() / 2]
    << " m; " << std::setprecision(0) << 100 * below / n << " % of the readings below and "
    << 100 * above / n << " % above the calibration's range [" << std::setprecision(2)
    << calib.min_depth_m << ", " << calib.max_depth_m
    << "] m: is the depth scale right? A wrong one scales the whole trajectory";
  return s.str();
}

}  // namespace rgbdvo
