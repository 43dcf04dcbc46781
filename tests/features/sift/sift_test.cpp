#include "rgbdvo/features/sift/sift.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>
#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rgbdvo/features/sift/sift_descriptor.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

cv::Mat ExcerptImage(const std::string& name) {
  const std::string path = SourceDir() + "/data/tum_fr1_xyz_first30/rgb/" + name;
  cv::Mat gray = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (gray.empty()) throw std::runtime_error("cannot read " + path);
  return gray;
}

struct Detected {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
};

Detected Ours(const cv::Mat& gray, const SiftOptions& options = {}) {
  Detected d;
  Sift(options).DetectAndDescribe(gray, &d.keypoints, &d.descriptors);
  return d;
}

Detected OpenCv(const cv::Mat& gray) {
  Detected d;
  cv::SIFT::create(0, 3, 0.04, 10, 1.6, CV_8U)
      ->detectAndCompute(gray, cv::noArray(), d.keypoints, d.descriptors);
  return d;
}

double AngleDiffDeg(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360 - d);
}

// For each keypoint of `a`, the index of a keypoint of `b` at the same place (within px),
// scale (1%) and orientation (2 degrees), or -1. OpenCV's keypoints lie 1/4 pixel right of and
// below where they are seen (its 2x upsampling maps pixel x to x / 2, not x / 2 - 1/4), so
// `shift` is added to a's positions.
std::vector<int> SameKeypoints(const std::vector<cv::KeyPoint>& a,
                               const std::vector<cv::KeyPoint>& b, double px, float shift) {
  std::vector<int> found(a.size(), -1);
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) {
      const cv::Point2f d = a[i].pt + cv::Point2f(shift, shift) - b[j].pt;
      if (std::hypot(d.x, d.y) <= px && std::abs(a[i].size - b[j].size) <= 0.01 * a[i].size &&
          AngleDiffDeg(a[i].angle, b[j].angle) <= 2) {
        found[i] = static_cast<int>(j);
        break;
      }
    }
  return found;
}

}  // namespace

TEST_CASE(
    "SIFT with OpenCV's kernels finds its keypoints on a real image, with close descriptors") {
  // With OpenCV's kernels (cut at 4 sigma; the default cuts them at 3) the scale space is the
  // same, so are the keypoints.
  const cv::Mat gray = ExcerptImage("1305031102.175304.png");
  SiftOptions as_opencv;
  as_opencv.scale_space.kernel_sigmas = 4;
  const Detected ours = Ours(gray, as_opencv), cv = OpenCv(gray);
  REQUIRE(cv.keypoints.size() > 1000);
  CHECK(std::abs(static_cast<double>(ours.keypoints.size()) - cv.keypoints.size()) <
        0.02 * cv.keypoints.size());
  const std::vector<int> same = SameKeypoints(cv.keypoints, ours.keypoints, 0.05, -0.25f);
  std::vector<double> same_dist, other_dist;
  for (size_t i = 0; i < same.size(); ++i) {
    if (same[i] < 0) continue;
    same_dist.push_back(
        cv::norm(cv.descriptors.row(static_cast<int>(i)), ours.descriptors.row(same[i])));
    // The descriptor of a keypoint 7 further on: an unrelated feature.
    other_dist.push_back(cv::norm(cv.descriptors.row(static_cast<int>(i)),
                                  ours.descriptors.row((same[i] + 7) % ours.descriptors.rows)));
  }
  INFO(same_dist.size() << " of " << cv.keypoints.size() << " found");
  CHECK(same_dist.size() > 0.98 * cv.keypoints.size());
  // Descriptors (norm 512): the same keypoint's differ by the grid sampling only.
  std::nth_element(same_dist.begin(), same_dist.begin() + same_dist.size() / 2, same_dist.end());
  std::nth_element(other_dist.begin(), other_dist.begin() + other_dist.size() / 2,
                   other_dist.end());
  INFO("median distance: same keypoint " << same_dist[same_dist.size() / 2] << ", unrelated "
                                         << other_dist[other_dist.size() / 2]);
  CHECK(same_dist[same_dist.size() / 2] < 30);
  CHECK(other_dist[other_dist.size() / 2] > 300);
}

TEST_CASE("SIFT matches between two real frames as well as OpenCV's SIFT") {
  // Frames 0 and 10 of the excerpt (0.33 s apart): ratio-test matches, then the inliers of a
  // fundamental matrix fitted by RANSAC (fixed seed), for both implementations.
  const cv::Mat a = ExcerptImage("1305031102.175304.png");
  const cv::Mat b = ExcerptImage("1305031102.511219.png");
  const auto inliers = [](const Detected& p, const Detected& q) {
    std::vector<std::vector<cv::DMatch>> knn;
    cv::BFMatcher(cv::NORM_L2).knnMatch(p.descriptors, q.descriptors, knn, 2);
    std::vector<cv::Point2f> x, y;
    for (const auto& m : knn)
      if (m.size() == 2 && m[0].distance < 0.8 * m[1].distance) {
        x.push_back(p.keypoints[m[0].queryIdx].pt);
        y.push_back(q.keypoints[m[0].trainIdx].pt);
      }
    cv::theRNG().state = 42;
    cv::Mat mask;
    cv::findFundamentalMat(x, y, cv::FM_RANSAC, 1.0, 0.999, mask);
    return cv::countNonZero(mask);
  };
  const int ours = inliers(Ours(a), Ours(b)), cv = inliers(OpenCv(a), OpenCv(b));
  INFO("inliers: ours " << ours << ", OpenCV " << cv);
  REQUIRE(cv > 300);
  CHECK(ours > 0.95 * cv);
}

TEST_CASE("SIFT keypoints turn with the image: orientation and descriptor are invariant") {
  // 449 rows: the rotation maps even columns and rows to even ones at every octave (448 = 7 x 64),
  // so the decimated octaves sample the same pixels.
  const cv::Mat gray = ExcerptImage("1305031102.175304.png").rowRange(0, 449);
  cv::Mat turned;
  cv::rotate(gray, turned, cv::ROTATE_90_CLOCKWISE);  // (x, y) -> (rows - 1 - y, x)
  SiftOptions o;
  o.scale_space.upsample = false;  // exact pixel mapping between the two
  const Detected a = Ours(gray, o), b = Ours(turned, o);
  std::vector<cv::KeyPoint> moved = a.keypoints;
  for (cv::KeyPoint& k : moved) {
    k.pt = cv::Point2f(gray.rows - 1 - k.pt.y, k.pt.x);
    k.angle = std::fmod(k.angle + 90.0f, 360.0f);  // clockwise in the image
  }
  const std::vector<int> same = SameKeypoints(moved, b.keypoints, 0.1, 0.0f);
  int found = 0, close = 0;
  for (size_t i = 0; i < same.size(); ++i) {
    if (same[i] < 0) continue;
    ++found;
    close += cv::norm(a.descriptors.row(static_cast<int>(i)), b.descriptors.row(same[i])) < 60;
  }
  INFO(found << " of " << a.keypoints.size() << " found, " << close << " with close descriptors");
  CHECK(found > 0.9 * a.keypoints.size());
  CHECK(close > 0.9 * found);
}

TEST_CASE("SIFT keeps the strongest keypoints, is deterministic, and survives tiny images") {
  const cv::Mat gray = ExcerptImage("1305031102.175304.png");
  const Detected all = Ours(gray);
  SiftOptions o;
  o.max_features = 100;
  const Detected best = Ours(gray, o);
  REQUIRE(best.keypoints.size() == 100);
  CHECK(best.descriptors.rows == 100);
  // Exactly the 100 largest responses of all keypoints (ties in detection order), in detection
  // order, each with its own descriptor, although only the strongest extrema were oriented and
  // described.
  std::vector<int> strongest(all.keypoints.size());
  std::iota(strongest.begin(), strongest.end(), 0);
  std::stable_sort(strongest.begin(), strongest.end(), [&](int a, int b) {
    return all.keypoints[a].response > all.keypoints[b].response;
  });
  strongest.resize(100);
  std::sort(strongest.begin(), strongest.end());
  for (int i = 0; i < 100; ++i) {
    const cv::KeyPoint &got = best.keypoints[i], &want = all.keypoints[strongest[i]];
    CHECK(got.pt == want.pt);
    CHECK(got.angle == want.angle);
    CHECK(got.response == want.response);
    CHECK(got.octave == want.octave);
    CHECK(cv::norm(best.descriptors.row(i), all.descriptors.row(strongest[i]), cv::NORM_INF) == 0);
  }
  const Detected again = Ours(gray);
  REQUIRE(again.keypoints.size() == all.keypoints.size());
  CHECK(cv::norm(again.descriptors, all.descriptors, cv::NORM_INF) == 0);

  for (const cv::Size size : {cv::Size(1, 1), cv::Size(5, 40), cv::Size(24, 24)}) {
    const Detected tiny = Ours(cv::Mat(size, CV_8U, cv::Scalar(50)));
    CHECK(tiny.keypoints.empty());
    CHECK(tiny.descriptors.rows == 0);
  }
}

TEST_CASE("FastAtan2 is atan2 to 2e-5 rad, from 0 up to 2 pi") {
  double worst = 0;
  for (int i = 0; i < 3600; ++i) {
    const double a = i * 2 * M_PI / 3600 + 1e-4;
    for (const double r : {1e-3, 1.0, 300.0}) {
      const float got =
          FastAtan2(static_cast<float>(r * std::sin(a)), static_cast<float>(r * std::cos(a)));
      worst = std::max(worst, std::abs(std::remainder(got - a, 2 * M_PI)));
      CHECK((got >= 0 && got < 2 * M_PI + 1e-6));
    }
  }
  CHECK(worst < 2e-5);
  CHECK(FastAtan2(0, 0) == 0);
}

TEST_CASE("SiftOptions::Check names the field") {
  SiftOptions o;
  o.edge_threshold = 0;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("edge_threshold"));
  o = {};
  o.max_features = -1;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("max_features"));
}
