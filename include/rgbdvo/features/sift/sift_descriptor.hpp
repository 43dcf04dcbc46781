#pragma once
// SIFT's orientation assignment and 128-d descriptor (Lowe 2004, sections 5 and 6) on one
// Gaussian level of the scale space.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>

namespace rgbdvo {

constexpr int kSiftDescriptorSize = 128;  // 4 x 4 spatial bins x 8 orientation bins

// atan2(y, x) in [0, 2 pi), within 2e-5 rad (the polynomial of Abramowitz & Stegun 4.4.49 on
// [0, 1], then the octant). Branch-free, so that loops over arrays of gradients vectorise.
inline float FastAtan2(float y, float x) {
  constexpr float kPi = 3.14159265358979f;
  const float ax = std::abs(x), ay = std::abs(y);
  const float a = std::min(ax, ay) / (std::max(ax, ay) + 1e-20f);
  const float s = a * a;
  float r =
      ((((0.0208351f * s - 0.0851330f) * s + 0.1801410f) * s - 0.3302995f) * s + 0.9998660f) * a;
  r = ay > ax ? 0.5f * kPi - r : r;
  r = x < 0 ? kPi - r : r;
  r = y < 0 ? 2 * kPi - r : r;
  return r;
}

// The 36-bin histogram of gradient orientations (Lowe section 5) around pixel (x, y) of
// `level` (CV_32F), over the square of half-width `radius`, weighted by a Gaussian of `sigma`
// pixels and smoothed by [1 4 6 4 1] / 16. Gradients: dx = I(x+1) - I(x-1), dy = I(y-1) - I(y+1)
// (y up, as OpenCV's SIFT), bin b covers the angle 10 b degrees. Returns the largest bin.
float OrientationHistogram(const cv::Mat& level, int x, int y, int radius, float sigma,
                           float hist[36]);

// Lowe's descriptor of the keypoint at (x, y) of `level` (centred on the nearest pixel, as
// OpenCV's), scale `sigma` (both in that level's pixels) and orientation `angle_deg`
// (cv::KeyPoint::angle: clockwise in the image, OpenCV's convention), as 128 bytes 0..255,
// laid out as OpenCV's SIFT lays them out. Where OpenCV visits every pixel of the
// rotated window (1200 to 4800 of them), the window is sampled on a regular grid of 4 x 4
// points per spatial bin (400 in all, gradients interpolated bilinearly): the same histogram
// at a fraction of the work.
void SiftDescriptor(const cv::Mat& level, float x, float y, float sigma, float angle_deg,
                    uint8_t* out);

}  // namespace rgbdvo
