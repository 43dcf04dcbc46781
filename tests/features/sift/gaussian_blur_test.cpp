#include "rgbdvo/features/sift/gaussian_blur.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

using namespace rgbdvo;

namespace {

cv::Mat RandomImage(int rows, int cols, uint64_t seed) {
  cv::Mat m(rows, cols, CV_32F);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0, 255);
  return m;
}

}  // namespace

TEST_CASE("GaussianBlur32f equals cv::GaussianBlur with reflected borders") {
  // Sizes around the 32-column vector blocks, tiny images, and radii beyond the image size.
  const std::vector<cv::Size> sizes = {{640, 480}, {97, 61}, {33, 32}, {31, 7}, {5, 3}, {1, 9}};
  for (const cv::Size& size : sizes)
    for (const auto& [sigma, radius] : std::vector<std::pair<double, int>>{{1.2, 5}, {3.1, 13}}) {
      const cv::Mat src = RandomImage(size.height, size.width, 7);
      cv::Mat expected, got, diff;
      cv::GaussianBlur(src, expected, cv::Size(2 * radius + 1, 2 * radius + 1), sigma, sigma,
                       cv::BORDER_REFLECT_101);
      GaussianBlur32f(src, got, sigma, radius, &diff);
      INFO(size << " sigma " << sigma << " radius " << radius);
      CHECK(cv::norm(got, expected, cv::NORM_INF) < 1e-3);
      CHECK(cv::norm(diff, got - src, cv::NORM_INF) < 1e-4);
    }
}

TEST_CASE("GaussianBlur32f keeps a constant image and the mean of a random one") {
  const cv::Mat flat(40, 50, CV_32F, cv::Scalar(100));
  cv::Mat out;
  GaussianBlur32f(flat, out, 2.0, 8);
  CHECK(cv::norm(out, flat, cv::NORM_INF) < 1e-3);
  const cv::Mat noise = RandomImage(200, 300, 3);
  GaussianBlur32f(noise, out, 2.0, 8);
  CHECK(cv::mean(out)[0] == Approx(cv::mean(noise)[0]).epsilon(0.01));
  // Blurring removes most of the noise's variance (white noise: by 1 / (4 pi sigma^2) = 50x).
  cv::Scalar mean, sd_in, sd_out;
  cv::meanStdDev(noise, mean, sd_in);
  cv::meanStdDev(out, mean, sd_out);
  CHECK(sd_out[0] < 0.2 * sd_in[0]);
}

TEST_CASE("GaussianBlur32f rejects bad input") {
  cv::Mat out;
  CHECK_THROWS_WITH(GaussianBlur32f(cv::Mat(10, 10, CV_8U), out, 1.0, 3),
                    Catch::Contains("CV_32FC1"));
  const cv::Mat src = RandomImage(10, 10, 1);
  CHECK_THROWS_WITH(GaussianBlur32f(src, out, 0.0, 3), Catch::Contains("sigma"));
  cv::Mat same = src;
  CHECK_THROWS_WITH(GaussianBlur32f(src, same, 1.0, 3), Catch::Contains("must not be src"));
}
