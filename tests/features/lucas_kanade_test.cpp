#include "rgbdvo/features/lucas_kanade.hpp"

#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <random>
#include <stdexcept>
#include <string>

#include "rgbdvo/features/keypoint_tracking.hpp"
#include "test_support.hpp"

using namespace rgbdvo;

namespace {

cv::Mat Grey(const std::string& name) {
  const std::string path = test::SourceDir() + "/data/tum_fr1_desk_turn24/rgb/" + name;
  const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
  REQUIRE(!bgr.empty());
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

// Points all over the image and past its edges, and starts up to 20 px off, fixed seed.
void RandomPoints(cv::Size size, int n, unsigned seed, std::vector<cv::Point2f>* points,
                  std::vector<cv::Point2f>* starts) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> ux(-12.f, static_cast<float>(size.width) + 12.f);
  std::uniform_real_distribution<float> uy(-12.f, static_cast<float>(size.height) + 12.f);
  std::uniform_real_distribution<float> off(-20.f, 20.f);
  for (int i = 0; i < n; ++i) {
    // One draw per statement, last coordinate first: the same points from every compiler.
    const float y = uy(rng);
    const float x = ux(rng);
    points->emplace_back(x, y);
    const float dy = off(rng);
    const float dx = off(rng);
    starts->push_back(points->back() + cv::Point2f(dx, dy));
  }
}

// The same float to the bit (0.0 and -0.0 apart).
bool SameBits(float a, float b) {
  uint32_t ua = 0, ub = 0;
  std::memcpy(&ua, &a, sizeof a);
  std::memcpy(&ub, &b, sizeof b);
  return ua == ub;
}

}  // namespace

TEST_CASE("Lucas-Kanade from windows made once tracks as OpenCV's, bit for bit") {
  // A fast turn with motion blur: frames 0 -> 3 and 0 -> 6 from the same windows.
  const cv::Mat a = Grey("1305031458.827564.png");
  const cv::Mat b = Grey("1305031458.927621.png");
  const cv::Mat c = Grey("1305031459.027665.png");
  std::vector<cv::Point2f> points, starts;
  RandomPoints(a.size(), 3000, 42, &points, &starts);
  // Corners too, where windows are textured: most tracks then converge.
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(a, corners, 500, 0.01, 5);
  for (const cv::Point2f& p : corners) {
    points.push_back(p);
    starts.push_back(p + cv::Point2f(3.5f, -2.25f));
  }
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
  // 9 and 13 px: one eight-pixel block a row, two rows at a time where the CPU has AVX2.
  for (const int side : {5, 9, 13, 21}) {
    for (const int levels : {0, 3}) {
      INFO("window " << side << ", levels " << levels);
      const cv::Size window(side, side);
      TrackingPyramid from, into_b, into_c;
      cv::buildOpticalFlowPyramid(a, from, window, levels, true);
      cv::buildOpticalFlowPyramid(b, into_b, window, levels, false);
      cv::buildOpticalFlowPyramid(c, into_c, window, levels, false);
      const LkWindows windows = MakeLkWindows(from, window, levels, points);
      for (const TrackingPyramid* to : {&into_b, &into_c}) {
        std::vector<cv::Point2f> expected = starts, got = starts;
        std::vector<uchar> expected_found, found;
        cv::calcOpticalFlowPyrLK(from, *to, points, expected, expected_found, cv::noArray(), window,
                                 levels, stop, cv::OPTFLOW_USE_INITIAL_FLOW);
        TrackLkWindows(windows, *to, 30, 0.01, &got, &found);
        REQUIRE(got.size() == expected.size());
        int differ = 0, tracked = 0;
        for (size_t i = 0; i < got.size(); ++i) {
          if (found[i] != expected_found[i] || !SameBits(got[i].x, expected[i].x) ||
              !SameBits(got[i].y, expected[i].y))
            ++differ;
          tracked += expected_found[i] ? 1 : 0;
        }
        CHECK(differ == 0);
        // Both outcomes are exercised: tracks found and tracks lost.
        CHECK(tracked > 300);
        CHECK(tracked < static_cast<int>(got.size()));
      }
    }
  }
}

TEST_CASE("Lucas-Kanade windows need the pyramid's derivatives and one start per point") {
  const cv::Mat a = Grey("1305031458.827564.png");
  TrackingPyramid plain;
  cv::buildOpticalFlowPyramid(a, plain, cv::Size(9, 9), 2, false);
  CHECK_THROWS_AS(MakeLkWindows(plain, cv::Size(9, 9), 2, {{10, 10}}), std::invalid_argument);
  TrackingPyramid with;
  cv::buildOpticalFlowPyramid(a, with, cv::Size(9, 9), 2, true);
  const LkWindows windows = MakeLkWindows(with, cv::Size(9, 9), 5, {{10, 10}, {50, 60}});
  CHECK(windows.levels == 2);  // no more levels than the pyramid holds
  std::vector<cv::Point2f> next(1);
  std::vector<uchar> found;
  CHECK_THROWS_AS(TrackLkWindows(windows, plain, 30, 0.01, &next, &found), std::invalid_argument);
}
