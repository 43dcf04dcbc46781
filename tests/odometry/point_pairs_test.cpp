#include "rgbdvo/odometry/point_pairs.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "rgbdvo/features/matching.hpp"
#include "rgbdvo/sensor/camera.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"
#include "rgbdvo/synthetic/synthetic_kinect.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// The reference: each match's two keypoints lifted from their depth images (how pairs were made
// before keypoints were lifted once per frame); matches without depth are dropped.
std::vector<PointPair> LiftMatches(const Calibration& calib, const LiftOptions& options,
                                   const cv::Mat& depth_prev, const cv::Mat& depth_cur,
                                   const Features& prev, const Features& cur,
                                   const std::vector<cv::DMatch>& matches) {
  std::vector<PointPair> pairs;
  for (const cv::DMatch& m : matches) {
    const cv::Point2f a = prev.keypoints[m.queryIdx].pt, b = cur.keypoints[m.trainIdx].pt;
    const auto p_prev = LiftColorPixel(calib, depth_prev, {a.x, a.y}, options.max_depth_jump_ratio);
    if (!p_prev) continue;
    const auto p_cur = LiftColorPixel(calib, depth_cur, {b.x, b.y}, options.max_depth_jump_ratio);
    if (!p_cur) continue;
    pairs.push_back({*p_prev, *p_cur});
  }
  return pairs;
}

// A colour -> IR mapping of eq. 1 that is not the identity (A, C differ by 1 %).
Calibration MappedCalib() {
  Calibration c;
  c.A = 0.91;
  c.B = 28.0;
  c.C = 0.92;
  c.D = 19.0;
  return c;
}

}  // namespace

TEST_CASE("Lifting every keypoint once gives the same pairs as lifting each match") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(2, 0.03, 2.0);
  const SiftExtractor sift{FeatureOptions{}};
  const Features prev = sift.Extract(scene.RenderColor(cam, path[0]));
  const Features cur = sift.Extract(scene.RenderColor(cam, path[1]));
  const cv::Mat depth_prev = scene.RenderDepth(cam, path[0]),
                depth_cur = scene.RenderDepth(cam, path[1]);
  const std::vector<cv::DMatch> matches = MatchFeatures(MatchOptions{}, prev, cur);
  Calibration calib;  // a Kinect-like mapping with lens distortion: every step of the lifting
  calib.A = 0.98;
  calib.B = -10.0;  // colour pixels near the left and top edges map outside the depth image
  calib.C = 0.99;
  calib.D = -8.0;
  calib.fx = calib.fy = 525;
  calib.dist_ir = {0.05, -0.1, 0.001, -0.001, 0.02};
  for (const double jump : {0.03, 0.0}) {  // bilinear (default) and the paper's nearest pixel
    LiftOptions o;
    o.max_depth_jump_ratio = jump;
    const std::vector<PointPair> expected =
        LiftMatches(calib, o, depth_prev, depth_cur, prev, cur, matches);
    std::vector<int> match_of_pair;
    const std::vector<PointPair> got =
        PairMatches(LiftKeypoints(calib, o, depth_prev, prev),
                    LiftKeypoints(calib, o, depth_cur, cur), matches, &match_of_pair);
    INFO("jump " << jump << ": " << matches.size() << " matches, " << expected.size() << " pairs");
    REQUIRE(got.size() == expected.size());
    CHECK(got.size() > 200);
    CHECK(got.size() < matches.size());  // some matches have no depth
    REQUIRE(match_of_pair.size() == got.size());
    for (size_t k = 0; k < got.size(); ++k) {
      CHECK(got[k].p_prev == expected[k].p_prev);  // bit for bit
      CHECK(got[k].p_cur == expected[k].p_cur);
      const cv::DMatch& m = matches[match_of_pair[k]];
      const cv::Point2f a = prev.keypoints[m.queryIdx].pt;
      CHECK(*LiftColorPixel(calib, depth_prev, {a.x, a.y}, jump) == got[k].p_prev);
    }
  }
}

TEST_CASE("Lifting across time with the identity is plain lifting") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const Calibration calib = CalibFor(cam);
  const SiftExtractor sift{FeatureOptions{}};
  const Features f = sift.Extract(scene.RenderColor(cam, Rigid3d::Identity()));
  const cv::Mat depth = scene.RenderDepth(cam, Rigid3d::Identity());
  REQUIRE(f.size() > 100);
  CHECK(LiftKeypointsAcrossTime(calib, LiftOptions{}, depth, f, Rigid3d::Identity()) ==
        LiftKeypoints(calib, LiftOptions{}, depth, f));
}

TEST_CASE("Depth taken 15 ms after the colour image in a fast turn is read where the point is") {
  // Colour at the identity, depth 15 ms later in a turn of 90 degrees per second (1.35 degrees,
  // about 12 px) with 0.5 m/s sideways. Lifted at the keypoint's own pixel, the depth belongs to
  // another surface point; moved by the motion, it gives the colour-time point (measured median
  // error on the exactly rendered scene: 3.2 cm plain, below a micrometre moved).
  const SyntheticScene scene;
  const PinholeCamera cam;
  const Calibration calib = CalibFor(cam);
  Rigid3d color_from_depth = Rigid3d::Identity();
  color_from_depth.linear() =
      Eigen::AngleAxisd(1.35 * M_PI / 180, Eigen::Vector3d(0.2, 1, 0).normalized()).matrix();
  color_from_depth.translation() = Eigen::Vector3d(0.0075, 0, 0);
  const SiftExtractor sift{FeatureOptions{}};
  const Features f = sift.Extract(scene.RenderColor(cam, Rigid3d::Identity()));
  const cv::Mat depth_then = scene.RenderDepth(cam, color_from_depth);  // world = colour camera
  const KeypointPoints truth =
      LiftKeypoints(calib, LiftOptions{}, scene.RenderDepth(cam, Rigid3d::Identity()), f);
  const KeypointPoints plain = LiftKeypoints(calib, LiftOptions{}, depth_then, f);
  const KeypointPoints moved =
      LiftKeypointsAcrossTime(calib, LiftOptions{}, depth_then, f, color_from_depth.inverse());
  std::vector<double> e_plain, e_moved;
  for (size_t i = 0; i < f.size(); ++i) {
    if (!truth[i]) continue;
    if (plain[i]) e_plain.push_back((*plain[i] - *truth[i]).norm());
    if (moved[i]) e_moved.push_back((*moved[i] - *truth[i]).norm());
  }
  REQUIRE(e_moved.size() > 0.9 * e_plain.size());
  REQUIRE(e_plain.size() > 100);
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  INFO("median error plain " << median(e_plain) << " m, moved " << median(e_moved) << " m");
  CHECK(median(e_plain) > 0.01);
  CHECK(median(e_moved) < 0.001);
}

TEST_CASE("PredictKeypoints projects with the motion and inverts eq. 1") {
  const Calibration c = MappedCalib();
  const Eigen::Vector2d uv_vis(200, 150);
  const KeypointPoints points = {BackProject(c, ColorToIr(c, uv_vis), 2.0), std::nullopt,
                                 Eigen::Vector3d(0, 0, 1)};
  // Identity: back where it was seen. A point moved behind the camera: no prediction.
  Rigid3d behind = Rigid3d::Identity();
  behind.translation() = Eigen::Vector3d(0, 0, -1.5);
  auto p = PredictKeypoints(c, points, Rigid3d::Identity());
  REQUIRE(p[0]);
  CHECK((*p[0] - uv_vis).norm() < 1e-9);
  CHECK(!p[1]);
  p = PredictKeypoints(c, points, behind);
  CHECK(p[0]);
  CHECK(!p[2]);
  // A sideways motion of 0.1 m at 2 m depth shifts the IR pixel by fx * 0.1 / 2, the colour
  // pixel by that over A.
  Rigid3d side = Rigid3d::Identity();
  side.translation() = Eigen::Vector3d(0.1, 0, 0);
  p = PredictKeypoints(c, points, side);
  CHECK(p[0]->x() - uv_vis.x() == Approx(c.fx * 0.1 / 2.0 / c.A));
  CHECK(p[0]->y() == Approx(uv_vis.y()));
}

TEST_CASE("PredictWarps: moving toward a point magnifies, a roll turns, no point leaves it be") {
  const Calibration c = MappedCalib();
  const Eigen::Vector2d uv_vis(320, 240);
  const KeypointPoints points = {BackProject(c, ColorToIr(c, uv_vis), 2.0), std::nullopt};
  // 0.4 m nearer a surface 2 m away (facing the camera): 2 / 1.6 = 1.25 times larger.
  Rigid3d nearer = Rigid3d::Identity();
  nearer.translation() = Eigen::Vector3d(0, 0, -0.4);
  std::vector<cv::Matx22f> w = PredictWarps(c, points, nearer);
  REQUIRE(w.size() == 2);
  CHECK(w[0](0, 0) == Approx(1.25).epsilon(1e-4));
  CHECK(w[0](1, 1) == Approx(1.25).epsilon(1e-4));
  CHECK(std::abs(w[0](0, 1)) < 1e-4);
  CHECK(std::abs(w[0](1, 0)) < 1e-4);
  CHECK(w[1] == cv::Matx22f::eye());
  // Rolled 10 degrees about the optical axis: the colour pixels turn by 10 degrees (scaled by
  // the two axes' pixel sizes, A and C, which differ by 1 %).
  Rigid3d rolled = Rigid3d::Identity();
  rolled.linear() = Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitZ()).matrix();
  w = PredictWarps(c, points, rolled);
  const double cs = std::cos(10 * M_PI / 180), sn = std::sin(10 * M_PI / 180);
  CHECK(w[0](0, 0) == Approx(cs).epsilon(1e-4));
  CHECK(w[0](1, 1) == Approx(cs).epsilon(1e-4));
  CHECK(w[0](0, 1) == Approx(-sn * c.C / c.A).epsilon(1e-4));
  CHECK(w[0](1, 0) == Approx(sn * c.A / c.C).epsilon(1e-4));
  // No motion: the identity.
  w = PredictWarps(c, points, Rigid3d::Identity());
  for (int i = 0; i < 4; ++i) CHECK(w[0].val[i] == Approx(cv::Matx22f::eye().val[i]).margin(1e-5));
}

TEST_CASE("Lifting across time finds the point with an offset IR camera and the disparity term") {
  // As above, with the Kinect's geometry: the depth from an IR camera 2.5 cm beside the colour
  // camera, mapped with the depth-aware calibration (exact at every depth).
  const SyntheticScene scene;
  const SyntheticKinectOptions o;
  const Calibration calib = SyntheticKinectCalibration(o, true);
  Rigid3d color_from_ir = Rigid3d::Identity();
  color_from_ir.translation() = o.ir_in_color;
  Rigid3d colort_from_depthtime = Rigid3d::Identity();  // colour camera at colour time <- later
  colort_from_depthtime.linear() =
      Eigen::AngleAxisd(1.35 * M_PI / 180, Eigen::Vector3d(0.2, 1, 0).normalized()).matrix();
  colort_from_depthtime.translation() = Eigen::Vector3d(0.0075, 0, 0);
  const Rigid3d world_from_color = MakeKinectRangePath(1)[0];
  const SiftExtractor sift{FeatureOptions{}};
  const Features f = sift.Extract(scene.RenderColor(o.color, world_from_color));
  const cv::Mat depth_color = scene.RenderDepth(o.color, world_from_color);
  const cv::Mat depth_then =
      scene.RenderDepth(o.ir, world_from_color * colort_from_depthtime * color_from_ir);
  // The IR camera at colour time <- the IR camera at depth time.
  const Rigid3d depth_from_color =
      (colort_from_depthtime * color_from_ir).inverse() * color_from_ir;
  const KeypointPoints moved =
      LiftKeypointsAcrossTime(calib, LiftOptions{}, depth_then, f, depth_from_color);
  const KeypointPoints eq1 = LiftKeypointsAcrossTime(SyntheticKinectCalibration(o), LiftOptions{},
                                                     depth_then, f, depth_from_color);
  std::vector<double> e, e_eq1;
  for (size_t i = 0; i < f.size(); ++i) {
    const double u = f.keypoints[i].pt.x, v = f.keypoints[i].pt.y;
    const float z =
        depth_color.at<float>(static_cast<int>(std::lround(v)), static_cast<int>(std::lround(u)));
    if (!moved[i] || !(z > 0)) continue;
    // The true point: the colour ray at the colour camera's own depth, in the IR frame.
    const Eigen::Vector3d truth((u - o.color.cx) / o.color.fx * z,
                                (v - o.color.cy) / o.color.fy * z, z);
    e.push_back((*moved[i] - (truth - o.ir_in_color)).norm());
    if (eq1[i]) e_eq1.push_back((*eq1[i] - (truth - o.ir_in_color)).norm());
  }
  REQUIRE(e.size() > 100);
  REQUIRE(e_eq1.size() > 100);
  std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
  std::nth_element(e_eq1.begin(), e_eq1.begin() + e_eq1.size() / 2, e_eq1.end());
  INFO(e.size() << " points, median error " << e[e.size() / 2] << " m; eq. 1 "
                << e_eq1[e_eq1.size() / 2] << " m");
  // Measured: median 3e-8 m (exact up to the truth's own nearest-pixel depth), eq. 1 5 mm.
  CHECK(e[e.size() / 2] < 0.0005);
  CHECK(e_eq1[e_eq1.size() / 2] > 0.002);
}
