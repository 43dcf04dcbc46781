#include "rgbdvo/features/sift/sift_descriptor.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// SiftDescriptor's definition computed the plain way, in double with std::atan2: 20 x 20 grid
// samples, 4 per bin and side, covering bin coordinates (-1, 4); at each, the central-difference
// gradient interpolated bilinearly (0 where the 4 pixels around the sample are too close to
// the edge), weighted by a Gaussian of half the window width; spread trilinearly over the
// 4 x 4 spatial and 8 orientation bins; normalised, clipped at 0.2, renormalised, x 512.
std::vector<float> ReferenceDescriptor(const cv::Mat& level, float x, float y, float sigma,
                                       float angle_deg) {
  const double kx = std::round(x), ky = std::round(y);
  const double angle = (360.0 - angle_deg) * M_PI / 180;
  const double c = std::cos(angle) * 3 * sigma, s = std::sin(angle) * 3 * sigma;
  const auto at = [&](int yy, int xx) { return static_cast<double>(level.at<float>(yy, xx)); };
  std::vector<double> hist(128, 0.0);
  for (int gr = 0; gr < 20; ++gr)
    for (int gc = 0; gc < 20; ++gc) {
      const double rb = -1 + (gr + 0.5) / 4, cb = -1 + (gc + 0.5) / 4;  // bin coordinates
      const double u = cb - 1.5, v = rb - 1.5;                          // from the centre
      const double px = kx + c * u + s * v, py = ky - s * u + c * v;
      const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
      if (x0 < 1 || y0 < 1 || x0 + 2 >= level.cols || y0 + 2 >= level.rows) continue;
      double dx = 0, dy = 0;
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          const double w = (a ? py - y0 : 1 - (py - y0)) * (b ? px - x0 : 1 - (px - x0));
          dx += w * (at(y0 + a, x0 + b + 1) - at(y0 + a, x0 + b - 1));
          dy += w * (at(y0 + a - 1, x0 + b) - at(y0 + a + 1, x0 + b));
        }
      const double mag = std::exp(-(u * u + v * v) / 8) * std::hypot(dx, dy);
      double o = (std::atan2(dy, dx) - angle) * 8 / (2 * M_PI);
      o -= 8 * std::floor(o / 8);
      const int o0 = static_cast<int>(std::floor(o)), r0 = static_cast<int>(std::floor(rb)),
                c0 = static_cast<int>(std::floor(cb));
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          for (int k = 0; k < 2; ++k) {
            const int r = r0 + i, cc = c0 + j;
            if (r < 0 || r > 3 || cc < 0 || cc > 3) continue;
            const double w = (i ? rb - r0 : 1 - (rb - r0)) * (j ? cb - c0 : 1 - (cb - c0)) *
                             (k ? o - o0 : 1 - (o - o0));
            hist[(r * 4 + cc) * 8 + (o0 + k) % 8] += w * mag;
          }
    }
  double norm = 0;
  for (double h : hist) norm += h * h;
  const double clip = 0.2 * std::sqrt(norm);
  norm = 0;
  for (double& h : hist) {
    h = std::min(h, clip);
    norm += h * h;
  }
  std::vector<float> out(128);
  for (int k = 0; k < 128; ++k)
    out[k] = static_cast<float>(std::min(255.0, std::floor(hist[k] * 512 / std::sqrt(norm) + 0.5)));
  return out;
}

}  // namespace

TEST_CASE("SiftDescriptor equals the descriptor computed the plain way, to rounding") {
  // A real image blurred as a scale-space level; random keypoints (fixed seed), some near the
  // edges, scales 1.6 to 8 pixels, any orientation.
  const std::string path = SourceDir() + "/data/tum_fr1_xyz_first30/rgb/1305031102.175304.png";
  cv::Mat gray = cv::imread(path, cv::IMREAD_GRAYSCALE), level;
  REQUIRE(!gray.empty());
  gray.convertTo(level, CV_32F);
  cv::GaussianBlur(level, level, cv::Size(0, 0), 1.6);
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> ux(0, level.cols - 1.0f), uy(0, level.rows - 1.0f),
      us(1.6f, 8.0f), ua(0, 360);
  double worst_l2 = 0, sum_l2 = 0;
  float worst_entry = 0;
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    const float x = ux(rng), y = uy(rng), sigma = us(rng), angle = ua(rng);
    uint8_t got[kSiftDescriptorSize];
    SiftDescriptor(level, x, y, sigma, angle, got);
    const std::vector<float> expected = ReferenceDescriptor(level, x, y, sigma, angle);
    double l2 = 0;
    for (int k = 0; k < kSiftDescriptorSize; ++k) {
      l2 += (got[k] - expected[k]) * (got[k] - expected[k]);
      worst_entry = std::max(worst_entry, std::abs(got[k] - expected[k]));
    }
    worst_l2 = std::max(worst_l2, std::sqrt(l2));
    sum_l2 += std::sqrt(l2);
  }
  // Entries are whole numbers 0..255 of a vector of norm 512: rounding moves an entry by 1 at
  // most (FastAtan2 is within 2e-5 rad of atan2; float against double sums).
  INFO("worst entry " << worst_entry << ", L2 difference worst " << worst_l2 << " mean "
                      << sum_l2 / n);
  CHECK(worst_entry <= 1);
  CHECK(sum_l2 / n < 0.5);
}
