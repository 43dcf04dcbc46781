#include "rgbdvo/features/keypoint_tracking.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

using namespace rgbdvo;

namespace {

// A smooth random texture (noise blurred at 2 px), 8-bit grey, fixed seed.
cv::Mat Texture(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 255);
  cv::Mat noise(rows, cols, CV_32F);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) noise.at<float>(y, x) = u(rng);
  cv::Mat smooth, grey;
  cv::GaussianBlur(noise, smooth, cv::Size(), 2.0);
  cv::normalize(smooth, smooth, 0, 255, cv::NORM_MINMAX);
  smooth.convertTo(grey, CV_8U);
  return grey;
}

// img moved by (dx, dy) pixels: a point at p in img is at p + (dx, dy) in the result.
cv::Mat Shifted(const cv::Mat& img, double dx, double dy) {
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::Mat out;
  cv::warpAffine(img, out, m, img.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT_101);
  return out;
}

}  // namespace

TEST_CASE("Tracked points land where the image moved them, from a guess several pixels off") {
  const TrackOptions options;
  const cv::Mat a = Texture(240, 320, 7);
  const double dx = 12.4, dy = -7.7;
  const cv::Mat b = Shifted(a, dx, dy);
  std::vector<cv::Point2f> points, guess;
  for (int y = 60; y <= 180; y += 30)
    for (int x = 60; x <= 260; x += 40) {
      points.emplace_back(static_cast<float>(x), static_cast<float>(y));
      guess.emplace_back(static_cast<float>(x + dx + 5), static_cast<float>(y + dy - 4));
    }
  // As the odometry does: derivatives for the image tracked from only. Tracked into a pyramid
  // with derivatives the points land at the same places.
  const TrackingPyramid from = MakeTrackingPyramid(options, a, true);
  const TrackingPyramid into = MakeTrackingPyramid(options, b, false);
  CHECK(HasDerivatives(from));
  CHECK(!HasDerivatives(into));
  const std::vector<std::optional<cv::Point2f>> tracked =
      TrackPoints(options, from, into, points, guess);
  const std::vector<std::optional<cv::Point2f>> into_full =
      TrackPoints(options, from, MakeTrackingPyramid(options, b, true), points, guess);
  REQUIRE(tracked.size() == points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    INFO("point " << points[i]);
    REQUIRE(tracked[i]);
    CHECK(std::abs(tracked[i]->x - (points[i].x + dx)) < 0.1);
    CHECK(std::abs(tracked[i]->y - (points[i].y + dy)) < 0.1);
    REQUIRE(into_full[i]);
    CHECK(*into_full[i] == *tracked[i]);
  }
}

TEST_CASE("A point whose patch is not in the other image is dropped by the back-tracking check") {
  TrackOptions options;
  options.max_back_error_px = 1;
  const cv::Mat a = Texture(240, 320, 7);
  cv::Mat b = Shifted(a, 3, 2);
  // Another texture pasted over the middle: what was there is gone.
  Texture(80, 80, 99).copyTo(b(cv::Rect(120, 80, 80, 80)));
  const std::vector<cv::Point2f> points = {{160, 120}, {60, 60}};
  const std::vector<cv::Point2f> guess = {{163, 122}, {63, 62}};
  const std::vector<std::optional<cv::Point2f>> tracked =
      TrackPoints(options, MakeTrackingPyramid(options, a, true),
                  MakeTrackingPyramid(options, b, false), points, guess);
  CHECK(!tracked[0]);
  REQUIRE(tracked[1]);
  CHECK(std::abs(tracked[1]->x - 63) < 0.1);
  CHECK(std::abs(tracked[1]->y - 62) < 0.1);
}

TEST_CASE("Nothing to track gives nothing; an empty image is refused") {
  const TrackOptions options;
  const TrackingPyramid p = MakeTrackingPyramid(options, Texture(64, 64, 1), true);
  CHECK(TrackPoints(options, p, p, {}, {}).empty());
  CHECK_THROWS_WITH(GreyImage(cv::Mat()), Catch::Contains("empty image"));
  CHECK_THROWS_AS(MakeTrackingPyramid(options, cv::Mat(8, 8, CV_8UC3), false),
                  std::invalid_argument);
  TrackOptions bad;
  bad.max_back_error_px = -1;
  CHECK_THROWS_AS(bad.Check(), std::invalid_argument);
}

TEST_CASE("The tracked keypoints are the strongest of each cell of the image in turn") {
  // 8 x 8 cells of 10 x 10 pixels; cell (0, 0) holds three keypoints, cell (7, 7) one, cell
  // (3, 4) one that is not usable.
  std::vector<cv::KeyPoint> kps = {cv::KeyPoint(2, 2, 2, -1, 0.1f), cv::KeyPoint(5, 5, 2, -1, 0.9f),
                                   cv::KeyPoint(8, 1, 2, -1, 0.5f),
                                   cv::KeyPoint(75, 75, 2, -1, 0.01f),
                                   cv::KeyPoint(45, 35, 2, -1, 5.0f)};
  const std::vector<bool> usable = {true, true, true, true, false};
  const cv::Size size(80, 80);
  // Round 1: the strongest of each cell (cell order), round 2: the next of each, ...
  CHECK(SelectSpread(kps, usable, size, 10) == std::vector<int>{1, 3, 2, 0});
  CHECK(SelectSpread(kps, usable, size, 2) == std::vector<int>{1, 3});
  CHECK(SelectSpread(kps, usable, size, 3) == std::vector<int>{1, 3, 2});
  CHECK(SelectSpread(kps, std::vector<bool>(kps.size(), false), size, 10).empty());
}
