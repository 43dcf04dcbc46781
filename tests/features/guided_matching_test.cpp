#include "rgbdvo/features/guided_matching.hpp"

#include <catch2/catch.hpp>

#include "rgbdvo/features/matching.hpp"
#include "rgbdvo/odometry/point_pairs.hpp"
#include "rgbdvo/sensor/camera.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// Two views of the synthetic room: features of both, 3D points of the reference's keypoints and
// the true cur_from_ref.
struct ViewPair {
  Features ref, cur;
  KeypointPoints ref_points;
  Rigid3d cur_from_ref;
  Calibration calib;
};

ViewPair MakeViewPair(const Rigid3d& world_from_ref, const Rigid3d& world_from_cur) {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const SiftExtractor sift{FeatureOptions{}};
  ViewPair v;
  v.calib = CalibFor(cam);
  v.ref = sift.Extract(scene.RenderColor(cam, world_from_ref));
  v.cur = sift.Extract(scene.RenderColor(cam, world_from_cur));
  v.ref_points =
      LiftKeypoints(v.calib, LiftOptions{}, scene.RenderDepth(cam, world_from_ref), v.ref);
  v.cur_from_ref = world_from_cur.inverse() * world_from_ref;
  return v;
}

Rigid3d Motion(double angle_deg, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  Rigid3d T = Rigid3d::Identity();
  T.linear() = AxisAngle(axis, angle_deg * M_PI / 180);
  T.translation() = t;
  return T;
}

// Features with one keypoint per position, descriptors given as rows.
Features MakeFeatures(const std::vector<cv::Point2f>& pts, const cv::Mat& descriptors) {
  Features f;
  for (const cv::Point2f& p : pts) f.keypoints.emplace_back(p, 4.0f);
  f.descriptors = descriptors;
  return f;
}

}  // namespace

TEST_CASE("Guided matching with the true motion finds the true correspondences") {
  const ViewPair v =
      MakeViewPair(Rigid3d::Identity(), Motion(2.0, {0.2, 1, 0.1}, {0.04, -0.01, 0.02}));
  const auto predicted = PredictKeypoints(v.calib, v.ref_points, v.cur_from_ref);
  const std::vector<cv::DMatch> matches =
      MatchGuided(GuidedMatchOptions{}, v.ref, predicted, v.cur);
  // A match is right when the current keypoint lies where the reference keypoint's 3D point
  // projects (exact rendering: keypoint localisation and depth sampling errors only). Measured:
  // 97 % right, as brute force (881 of 908 against 831 of 856); the wrong ones are 4-30 px off,
  // mostly the finest keypoints (2-3 px) on the synthetic texture's repeats, within the
  // prediction's radius.
  const auto right = [&](const std::vector<cv::DMatch>& ms) {
    int n = 0;
    for (const cv::DMatch& m : ms) {
      if (!predicted[m.queryIdx]) continue;
      const cv::Point2f& pt = v.cur.keypoints[m.trainIdx].pt;
      n += (*predicted[m.queryIdx] - Eigen::Vector2d(pt.x, pt.y)).norm() < 4.0;
    }
    return n;
  };
  const int brute_right = right(MatchFeatures(MatchOptions{}, v.ref, v.cur));
  INFO(matches.size() << " matches, " << right(matches) << " right, of " << v.ref.size()
                      << " keypoints; brute force: " << brute_right << " right");
  CHECK(matches.size() > 300);
  CHECK(right(matches) >= 0.96 * matches.size());
  CHECK(right(matches) >= brute_right);  // the prior finds at least the same true matches
  // Only keypoints with a 3D point are matched.
  for (const cv::DMatch& m : matches) CHECK(v.ref_points[m.queryIdx].has_value());
}

TEST_CASE("With a radius covering the image, guided matching is MatchFeatures") {
  const ViewPair v =
      MakeViewPair(Rigid3d::Identity(), Motion(3.0, {0.5, 1, 0}, {0.05, 0.02, -0.03}));
  // Every seventh keypoint loses its 3D point (as at depth edges), so that MatchGuided has to
  // map indices. A prediction somewhere for each keypoint with a 3D point; the radius makes it
  // irrelevant.
  KeypointPoints points = v.ref_points;
  for (size_t i = 0; i < points.size(); i += 7) points[i].reset();
  const auto predicted = PredictKeypoints(v.calib, points, Rigid3d::Identity());
  Features with_prediction;  // MatchFeatures' input: the reference keypoints with a prediction
  std::vector<int> original;
  for (size_t i = 0; i < v.ref.size(); ++i)
    if (predicted[i]) {
      original.push_back(static_cast<int>(i));
      with_prediction.keypoints.push_back(v.ref.keypoints[i]);
      with_prediction.descriptors.push_back(v.ref.descriptors.row(static_cast<int>(i)));
    }
  REQUIRE(original.size() > 500);
  REQUIRE(original.size() < v.ref.size());
  for (const bool mutual : {true, false})
    for (const double ratio : {0.8, 0.6, 1.0}) {
      MatchOptions brute;
      brute.mutual = mutual;
      brute.ratio = ratio;
      GuidedMatchOptions guided;
      guided.mutual = mutual;
      guided.ratio = ratio;
      guided.radius_px = 1e6;
      std::vector<cv::DMatch> expected = MatchFeatures(brute, with_prediction, v.cur);
      for (cv::DMatch& m : expected) m.queryIdx = original[m.queryIdx];
      std::sort(expected.begin(), expected.end(),
                [](const cv::DMatch& a, const cv::DMatch& b) { return a.queryIdx < b.queryIdx; });
      const std::vector<cv::DMatch> got = MatchGuided(guided, v.ref, predicted, v.cur);
      INFO("mutual " << mutual << " ratio " << ratio << ": " << got.size() << " guided, "
                     << expected.size() << " brute force");
      REQUIRE(got.size() == expected.size());
      CHECK(got.size() > 100);
      int same = 0;
      for (size_t k = 0; k < got.size(); ++k)
        same += got[k].queryIdx == expected[k].queryIdx &&
                got[k].trainIdx == expected[k].trainIdx && got[k].distance == expected[k].distance;
      CHECK(same == static_cast<int>(got.size()));
    }
}

TEST_CASE("Guided matching compares only candidates within the radius") {
  // Reference keypoint 0 is predicted at (100, 100). Current keypoint 0 (at 8 px) has its
  // descriptor; keypoint 1 (at 30 px) has the same descriptor, which would make brute-force
  // matching ambiguous (ratio test fails); keypoint 2 (at 4 px) is a different descriptor.
  cv::Mat d_ref = cv::Mat::zeros(1, 128, CV_8U);
  d_ref.at<uint8_t>(0, 0) = 1;
  cv::Mat d_cur = cv::Mat::zeros(3, 128, CV_8U);
  d_cur.at<uint8_t>(0, 0) = 1;
  d_cur.at<uint8_t>(1, 0) = 1;
  d_cur.at<uint8_t>(2, 1) = 1;
  const Features ref = MakeFeatures({{50, 50}}, d_ref);
  const Features cur = MakeFeatures({{108, 100}, {100, 130}, {100, 104}}, d_cur);
  const std::vector<std::optional<Eigen::Vector2d>> predicted = {Eigen::Vector2d(100, 100)};
  GuidedMatchOptions o;
  o.radius_px = 20;
  std::vector<cv::DMatch> m = MatchGuided(o, ref, predicted, cur);
  REQUIRE(m.size() == 1);
  CHECK(m[0].queryIdx == 0);
  CHECK(m[0].trainIdx == 0);
  CHECK(m[0].distance == 0);
  CHECK(MatchFeatures(MatchOptions{}, ref, cur).empty());  // ambiguous without the prior
  o.radius_px = 40;  // now both identical descriptors are candidates: ambiguous again
  CHECK(MatchGuided(o, ref, predicted, cur).empty());
  o.radius_px = 6;  // only the other descriptor is near: a single candidate is kept
  m = MatchGuided(o, ref, predicted, cur);
  REQUIRE(m.size() == 1);
  CHECK(m[0].trainIdx == 2);
  // Without a prediction nothing is matched.
  CHECK(MatchGuided(o, ref, {std::nullopt}, cur).empty());
}

TEST_CASE("Guided matching's mutual check looks at the reference keypoints near each keypoint") {
  // Two reference keypoints predicted 10 px apart compete for current keypoint 0; reference
  // keypoint 1 is nearer to it in descriptor space, so with the mutual check keypoint 0 does
  // not take it.
  cv::Mat d_ref = cv::Mat::zeros(2, 128, CV_8U);
  d_ref.at<uint8_t>(0, 0) = 10;
  d_ref.at<uint8_t>(1, 0) = 9;
  cv::Mat d_cur = cv::Mat::zeros(2, 128, CV_8U);
  d_cur.at<uint8_t>(0, 0) = 9;
  d_cur.at<uint8_t>(1, 2) = 50;  // far in descriptor space from both
  const Features ref = MakeFeatures({{0, 0}, {0, 0}}, d_ref);
  const Features cur = MakeFeatures({{100, 100}, {102, 100}}, d_cur);
  const std::vector<std::optional<Eigen::Vector2d>> predicted = {Eigen::Vector2d(95, 100),
                                                                 Eigen::Vector2d(105, 100)};
  GuidedMatchOptions o;
  std::vector<cv::DMatch> m = MatchGuided(o, ref, predicted, cur);
  REQUIRE(m.size() == 1);
  CHECK(m[0].queryIdx == 1);
  CHECK(m[0].trainIdx == 0);
  o.mutual = false;
  CHECK(MatchGuided(o, ref, predicted, cur).size() == 2);
  // Reference keypoint 1 predicted far away: keypoint 0's only nearby reference keypoint is 0.
  o.mutual = true;
  m = MatchGuided(o, ref, {Eigen::Vector2d(95, 100), Eigen::Vector2d(300, 100)}, cur);
  REQUIRE(m.size() == 1);
  CHECK(m[0].queryIdx == 0);
}
