#include "rgbdvo/features/keypoint_tracking.hpp"

#include <algorithm>
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

TEST_CASE(
    "The warped refinement finds points in a magnified, sheared view where the shift is off") {
  // b is a seen 1.25x larger and sheared (as a camera moving toward a slanted surface sees
  // it), about (160, 120): a point at p in a is at c + M (p - c) in b. Tracked with OpenCV's
  // shifted window the points land 0.35 px off on average; refined with the window warped by
  // M, within the interpolation's own error (0.04 px on average, next test).
  const TrackOptions options;
  const cv::Mat a = Texture(240, 320, 11);
  const cv::Matx22f m(1.25f, 0.10f, 0.0f, 1.25f);
  const cv::Point2f c(160, 120);
  const cv::Mat affine =
      (cv::Mat_<double>(2, 3) << m(0, 0), m(0, 1), c.x - m(0, 0) * c.x - m(0, 1) * c.y, m(1, 0),
       m(1, 1), c.y - m(1, 0) * c.x - m(1, 1) * c.y);
  cv::Mat b;
  cv::warpAffine(a, b, affine, a.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT_101);
  std::vector<cv::Point2f> points, truth;
  for (int y = 80; y <= 160; y += 20)
    for (int x = 100; x <= 220; x += 20) {
      const cv::Point2f p(static_cast<float>(x), static_cast<float>(y));
      points.push_back(p);
      truth.push_back(c + m * (p - c));
    }
  std::vector<std::optional<cv::Point2f>> landed =
      TrackPoints(options, MakeTrackingPyramid(options, a, true),
                  MakeTrackingPyramid(options, b, false), points, truth);
  const auto error = [&](const std::vector<std::optional<cv::Point2f>>& at, size_t i) {
    const cv::Point2f d = *at[i] - truth[i];
    return static_cast<double>(std::hypot(d.x, d.y));
  };
  double shifted_sum = 0, warped_sum = 0, warped_max = 0;
  std::vector<std::optional<cv::Point2f>> refined = landed;
  RefineWarped(options, a, b, points, std::vector<cv::Matx22f>(points.size(), m), &refined);
  for (size_t i = 0; i < points.size(); ++i) {
    INFO("point " << points[i]);
    REQUIRE(landed[i]);
    REQUIRE(refined[i]);
    shifted_sum += error(landed, i);
    warped_sum += error(refined, i);
    warped_max = std::max(warped_max, error(refined, i));
  }
  const double n = static_cast<double>(points.size());
  INFO("mean error shifted " << shifted_sum / n << " px, warped " << warped_sum / n << " px");
  CHECK(warped_max < 0.15);
  CHECK(warped_sum < 0.25 * shifted_sum);
}

TEST_CASE(
    "The warped refinement with the identity agrees with the shift, outside it leaves points") {
  TrackOptions options;
  options.warp_min_px = 0;  // refined even where the warp is a shift
  const cv::Mat a = Texture(240, 320, 7);
  const cv::Mat b = Shifted(a, 2.3, -1.6);
  // Started 0.5 px off, the refinement lands where OpenCV's Lucas-Kanade does (both sample the
  // image bilinearly, which puts both up to 0.05 px off a shift of 0.3 px). A point whose
  // window would leave the image, and a lost one, keep what they had.
  const std::vector<cv::Point2f> points = {{100, 100}, {2, 120}, {200, 150}};
  const std::vector<std::optional<cv::Point2f>> opencv =
      TrackPoints(options, MakeTrackingPyramid(options, a, true),
                  MakeTrackingPyramid(options, b, false), {points[0]}, {{102.3f, 98.4f}});
  REQUIRE(opencv[0]);
  std::vector<std::optional<cv::Point2f>> landed = {cv::Point2f(102.8f, 98.1f),
                                                    cv::Point2f(4.3f, 118.4f), std::nullopt};
  RefineWarped(options, a, b, points, std::vector<cv::Matx22f>(3, cv::Matx22f::eye()), &landed);
  REQUIRE(landed[0]);
  CHECK(std::abs(landed[0]->x - opencv[0]->x) < 0.01);
  CHECK(std::abs(landed[0]->y - opencv[0]->y) < 0.01);
  CHECK(std::abs(landed[0]->x - 102.3f) < 0.1);
  CHECK(std::abs(landed[0]->y - 98.4f) < 0.1);
  REQUIRE(landed[1]);
  CHECK(*landed[1] == cv::Point2f(4.3f, 118.4f));
  CHECK(!landed[2]);
  std::vector<std::optional<cv::Point2f>> one(1);
  CHECK_THROWS_AS(RefineWarped(options, a, b, points, {}, &one), std::invalid_argument);
  TrackOptions bad;
  bad.warp_window_px = 2;
  CHECK_THROWS_AS(bad.Check(), std::invalid_argument);
  bad = TrackOptions{};
  bad.warp_max_shift_px = 0;
  CHECK_THROWS_AS(bad.Check(), std::invalid_argument);
  bad = TrackOptions{};
  bad.warp_settled_px = 0;
  CHECK_THROWS_AS(bad.Check(), std::invalid_argument);
  // With the default threshold, a shift is left to the pyramid: the landing stands.
  std::vector<std::optional<cv::Point2f>> shifted = {cv::Point2f(102.8f, 98.1f)};
  RefineWarped(TrackOptions{}, a, b, {points[0]}, {cv::Matx22f::eye()}, &shifted);
  CHECK(*shifted[0] == cv::Point2f(102.8f, 98.1f));
}

TEST_CASE("Nothing to track gives nothing, an empty image is refused") {
  const TrackOptions options;
  const TrackingPyramid p = MakeTrackingPyramid(options, Texture(64, 64, 1), true);
  CHECK(TrackPoints(options, p, p, {}, {}).empty());
  CHECK_THROWS_WITH(GreyImage(cv::Mat()), Catch::Contains("empty image"));
  CHECK_THROWS_AS(MakeTrackingPyramid(options, cv::Mat(8, 8, CV_8UC3), false),
                  std::invalid_argument);
  TrackOptions bad;
  bad.max_points = 0;
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
