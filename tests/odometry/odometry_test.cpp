#include "rgbdvo/odometry/odometry.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "rgbdvo/synthetic/synthetic.hpp"
#include "rgbdvo/synthetic/synthetic_kinect.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

Frame Render(const SyntheticScene& scene, const PinholeCamera& cam, const Rigid3d& pose, int i) {
  Frame f;
  f.index = i;
  f.timestamp = f.color_timestamp = i / 30.0;
  f.bgr = scene.RenderColor(cam, pose);
  f.depth_m = scene.RenderDepth(cam, pose);
  return f;
}

// The frames of a path, numbered and timed from 0.
std::vector<Frame> RenderPath(const SyntheticScene& scene, const PinholeCamera& cam,
                              const std::vector<Rigid3d>& path) {
  std::vector<Frame> frames;
  frames.reserve(path.size());
  for (int i = 0; i < static_cast<int>(path.size()); ++i)
    frames.push_back(Render(scene, cam, path[i], i));
  return frames;
}

// n poses turning 1 degree of yaw per frame (and moving 5 mm sideways, 2 mm forward), except
// frames first..last, which turn burst_deg each.
std::vector<Rigid3d> YawBurstPath(int n, int first, int last, double burst_deg) {
  std::vector<Rigid3d> path = {Rigid3d::Identity()};
  for (int i = 1; i < n; ++i) {
    const double deg = (i >= first && i <= last) ? burst_deg : 1.0;
    Rigid3d step = Rigid3d::Identity();
    step.linear() = Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitY()).matrix();
    step.translation() = Eigen::Vector3d(0.005, 0, 0.002);
    path.push_back(path.back() * step);
  }
  return path;
}

}  // namespace

TEST_CASE("A frame against itself gives the identity") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const OdometryOptions defaults;
  Odometry odometry(defaults, CalibFor(cam));
  const Frame f = Render(scene, cam, Rigid3d::Identity(), 0);
  CHECK(odometry.Process(f).status == FrameStatus::kFirst);
  Frame again = f;
  again.index = 1;
  const FrameResult r = odometry.Process(again);
  INFO(r.StatusString() << " inliers " << r.inliers);
  CHECK(r.status == FrameStatus::kAccepted);
  CHECK(r.inliers > 200);
  CHECK(RigidNear(r.world_from_cam, Rigid3d::Identity(), 1e-6, 1e-9));
}

TEST_CASE("Odometry recovers a synthetic camera path") {
  // Exact rendering of a textured room; errors come only from pixel quantisation of keypoints
  // and nearest-pixel depth sampling (a few tenths of a mm per frame, measured: 3 mm and
  // 0.04 deg after 30 gentle frames), so 30 frames with up to 2 cm and 1.5 deg per frame must
  // stay within 2 cm and end within 2 cm and 1 degree of the truth.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(30, 0.02, 1.5);
  const OdometryOptions defaults;
  Odometry odometry(defaults, CalibFor(cam));
  FrameResult last;
  double max_trans = 0, max_rot = 0;
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    last = odometry.Process(Render(scene, cam, path[i], i));
    INFO("frame " << i << " " << last.StatusString() << " inliers " << last.inliers);
    REQUIRE((last.status == FrameStatus::kAccepted || last.status == FrameStatus::kFirst));
    CHECK(TranslationError(last.world_from_cam, path[i]) < 0.02);
    max_trans = std::max(max_trans, TranslationError(path.front(), path[i]));
    max_rot = std::max(max_rot, RotationErrorDeg(path.front(), path[i]));
  }
  INFO("final error " << TranslationError(last.world_from_cam, path.back()) << " m, "
                      << RotationErrorDeg(last.world_from_cam, path.back()) << " deg");
  CHECK(max_trans > 0.3);  // the path really moves
  CHECK(max_rot > 10);
  CHECK(RigidNear(last.world_from_cam, path.back(), 1.0, 0.02));
}

TEST_CASE("With the local map the odometry follows a synthetic path there and back") {
  // The camera goes out 15 frames and comes back along the same poses, so the map's points are
  // seen again from the way out. Every frame must stay within 2 cm, the return end within 1 cm
  // and 1 degree of the start, and the adjustment must have run on the keyframes.
  const SyntheticScene scene;
  const PinholeCamera cam;
  std::vector<Rigid3d> path = MakeSmoothPath(15, 0.02, 1.5);
  for (int i = 13; i >= 0; --i) path.push_back(path[i]);
  OdometryOptions options;
  options.local_map.enabled = true;
  Odometry odometry(options, CalibFor(cam));
  FrameResult last;
  int adjusted = 0;
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    last = odometry.Process(Render(scene, cam, path[i], i));
    INFO("frame " << i << " " << last.StatusString() << " inliers " << last.inliers);
    REQUIRE((last.status == FrameStatus::kAccepted || last.status == FrameStatus::kFirst));
    CHECK(TranslationError(last.world_from_cam, path[i]) < 0.02);
    if (last.times.local_map > 0) ++adjusted;
  }
  CHECK(adjusted >= 2);
  CHECK(RigidNear(last.world_from_cam, path.back(), 1.0, 0.01));
}

TEST_CASE("The depth term keeps a synthetic path as exact as the features alone") {
  // Exact rendering: all end within a millimetre (measured 0.6 and 0.5 mm after 15 frames); a
  // wrong surface, derivative or time offset in the term would pull the estimate off. Its
  // textured views pin the translation to well under the default gate (4 mm), so by default
  // the depth term joins no frame and the path is the features' own.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(15, 0.02, 1.5);
  const std::vector<Frame> frames = RenderPath(scene, cam, path);
  const auto final_pose = [&](int depth_term_step, double translation_std_m) {
    OdometryOptions options;
    options.depth_term_step = depth_term_step;
    options.depth_term_translation_std_m = translation_std_m;
    Odometry odometry(options, CalibFor(cam));
    FrameResult last;
    for (const Frame& f : frames) {
      last = odometry.Process(f);
      REQUIRE(HasFeatureEstimate(last.status));
    }
    return last.world_from_cam;
  };
  const OdometryOptions defaults;
  const Rigid3d features_only = final_pose(0, 0);
  const Rigid3d every_frame = final_pose(16, 0);
  const Rigid3d gated = final_pose(defaults.depth_term_step, defaults.depth_term_translation_std_m);
  const double features_error = TranslationError(features_only, path.back());
  const double depth_error = TranslationError(every_frame, path.back());
  INFO("final error: features only " << features_error << " m, with the depth term " << depth_error
                                     << " m");
  CHECK(features_error < 0.002);
  CHECK(depth_error < 0.002);
  CHECK(features_only.isApprox(gated, 1e-12));
  CHECK(!features_only.isApprox(every_frame, 1e-9));
}

TEST_CASE("A frame without an estimate is reported at the constant-velocity prediction") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(4, 0.02, 1.0);
  const OdometryOptions defaults;
  Odometry odometry(defaults, CalibFor(cam));
  odometry.Process(Render(scene, cam, path[0], 0));
  REQUIRE(odometry.Process(Render(scene, cam, path[1], 1)).status == FrameStatus::kAccepted);
  Frame blank = Render(scene, cam, path[2], 2);
  blank.bgr.setTo(cv::Scalar(128, 128, 128));  // no texture: no features, no matches
  blank.depth_m.setTo(0);                      // and no depth: nothing for ICP either
  const FrameResult predicted = odometry.Process(blank);
  CHECK(predicted.status == FrameStatus::kPredicted);
  CHECK(predicted.StatusString().rfind("predicted:", 0) == 0);
  CHECK_THAT(predicted.reason, Catch::Contains("+icp_"));  // what the depth fallback found
  CHECK_FALSE(HasEstimate(predicted.status));
  // The smooth path's velocity changes little from frame to frame: the prediction is close.
  CHECK(RigidNear(predicted.world_from_cam, path[2], 0.3, 0.005));
  CHECK(TranslationError(predicted.world_from_cam, path[1]) > 0.01);  // not held
  const FrameResult next = odometry.Process(Render(scene, cam, path[3], 3));
  CHECK(next.status == FrameStatus::kAccepted);
  CHECK(RigidNear(next.world_from_cam, path[3], 0.5, 0.01));
}

TEST_CASE("With predict_failed_frames off a rejected frame keeps the last pose (the paper)") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(3, 0.02, 1.0);
  OdometryOptions options;
  options.predict_failed_frames = false;
  options.depth_fallback = false;  // features only, as the paper
  CHECK_FALSE(PresetOptions("paper").predict_failed_frames);
  CHECK_FALSE(PresetOptions("paper").depth_fallback);
  Odometry odometry(options, CalibFor(cam));
  odometry.Process(Render(scene, cam, path[0], 0));
  Frame blank = Render(scene, cam, path[1], 1);
  blank.bgr.setTo(cv::Scalar(128, 128, 128));
  const FrameResult rejected = odometry.Process(blank);
  CHECK(rejected.status == FrameStatus::kRejected);
  CHECK(rejected.StatusString().rfind("rejected:", 0) == 0);
  CHECK(RigidNear(rejected.world_from_cam, path[0], 1e-9, 1e-12));
  const FrameResult next = odometry.Process(Render(scene, cam, path[2], 2));
  CHECK(next.status == FrameStatus::kAccepted);
  CHECK(RigidNear(next.world_from_cam, path[2], 0.5, 0.01));
}

TEST_CASE("A burst of fast, blurred rotation is bridged and measured across") {
  // 1 degree of yaw per frame, then 4 frames at 4 degrees per frame so blurred that SIFT finds
  // no usable matches, then 1 degree per frame again. With features only, the blurred frames are
  // predicted (moving on at the old velocity, flagged); the first sharp frame after them is
  // matched against the last accepted one, 17 degrees back (the guided search, 12 degrees off,
  // falls back to brute force), and lands on the truth, so the burst's motion is in the
  // trajectory.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = YawBurstPath(12, 5, 8, 4.0);
  OdometryOptions options;
  options.depth_fallback = false;
  Odometry odometry(options, CalibFor(cam));
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    Frame f = Render(scene, cam, path[i], i);
    const bool blurred = i >= 5 && i <= 8;
    if (blurred) cv::GaussianBlur(f.bgr, f.bgr, cv::Size(0, 0), 25);
    const FrameResult r = odometry.Process(f);
    INFO("frame " << i << " " << r.StatusString() << " inliers " << r.inliers);
    if (blurred) {
      CHECK(r.status == FrameStatus::kPredicted);
      continue;
    }
    REQUIRE(HasEstimate(r.status));
    // Measured: at most 0.03 degrees and 1.6 mm off, before and after the burst.
    CHECK(RigidNear(r.world_from_cam, path[i], 0.2, 0.005));
    if (i == 9) CHECK(r.fallbacks >= 1);
  }
}

TEST_CASE("A frame without depth never becomes the reference: the first frame with depth does") {
  // The first frames of a Kinect stream often come without depth: matched against such a
  // reference, no later frame could be measured until the odometry restarted.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = YawBurstPath(10, 1, 0, 0);
  std::vector<Frame> frames = RenderPath(scene, cam, path);
  for (int i = 0; i < 3; ++i) frames[i].depth_m.setTo(0.0f);
  for (const bool predict : {true, false}) {
    OdometryOptions o;
    o.predict_failed_frames = predict;
    Odometry odometry(o, CalibFor(cam));
    for (size_t i = 0; i < frames.size(); ++i) {
      const FrameResult r = odometry.Process(frames[i]);
      INFO("frame " << i << " " << r.StatusString());
      if (i < 3) {
        CHECK(r.status == (predict ? FrameStatus::kPredicted : FrameStatus::kRejected));
        CHECK(r.reason == "reference_points<15");
        CHECK(RigidNear(r.world_from_cam, Rigid3d::Identity(), 1e-9, 1e-12));
      } else if (i == 3) {
        CHECK(r.status == FrameStatus::kFirst);
        CHECK(RigidNear(r.world_from_cam, Rigid3d::Identity(), 1e-9, 1e-12));
      } else {
        // Measured from frame 3, the origin now.
        CHECK(r.status == FrameStatus::kAccepted);
        CHECK(RigidNear(r.world_from_cam, path[3].inverse() * path[i], 0.05, 0.002));
      }
    }
  }
}

TEST_CASE("A first frame without keypoints but with depth is the reference the depth aligns with") {
  // A dark first colour image (a Kinect's exposure settling): the depth fallback measures the
  // next frames against its depth, as before the first frame with keypoints.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = YawBurstPath(6, 1, 0, 0);
  std::vector<Frame> frames = RenderPath(scene, cam, path);
  frames[0].bgr.setTo(cv::Scalar::all(0));
  Odometry odometry(OdometryOptions{}, CalibFor(cam));
  std::vector<FrameStatus> statuses;
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameResult r = odometry.Process(frames[i]);
    INFO("frame " << i << " " << r.StatusString());
    statuses.push_back(r.status);
    if (i == 0) CHECK(r.status == FrameStatus::kFirst);
    CHECK(HasEstimate(r.status));
    CHECK(RigidNear(r.world_from_cam, path[i], 0.3, 0.01));
  }
  CHECK(statuses[1] == FrameStatus::kDepth);
}

TEST_CASE("After max_rejected_run rejections the odometry restarts and says lost") {
  // The frames after the first show another world (another texture, the same depth): features,
  // but none that match. With depth_fallback off nothing else can carry them.
  const SyntheticScene scene, other(99);
  const PinholeCamera cam;
  OdometryOptions options;
  options.max_rejected_run = 2;
  options.depth_fallback = false;
  Odometry odometry(options, CalibFor(cam));
  odometry.Process(Render(scene, cam, Rigid3d::Identity(), 0));
  CHECK(odometry.Process(Render(other, cam, Rigid3d::Identity(), 1)).status ==
        FrameStatus::kPredicted);
  const FrameResult lost = odometry.Process(Render(other, cam, Rigid3d::Identity(), 2));
  CHECK(lost.status == FrameStatus::kLost);
  CHECK(lost.StatusString().rfind("lost:", 0) == 0);
  // The restart frame is the reference now: the next view of that world matches it.
  CHECK(odometry.Process(Render(other, cam, Rigid3d::Identity(), 3)).status ==
        FrameStatus::kAccepted);
}

TEST_CASE(
    "A frame without features never becomes the reference: tracking resumes from the old one") {
  // Blank colour (a white wall, a covered lens) for longer than max_rejected_run: restarting
  // from such a frame would make the frames after it unmatchable too, so the odometry keeps
  // predicting until a frame with points comes, and that one is matched against the old
  // keyframe, 6 frames back.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(10, 0.01, 0.5);
  OdometryOptions options;
  options.max_rejected_run = 2;
  options.depth_fallback = false;
  Odometry odometry(options, CalibFor(cam));
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    Frame f = Render(scene, cam, path[i], i);
    const bool blank = i >= 2 && i <= 7;
    if (blank) f.bgr.setTo(cv::Scalar(128, 128, 128));
    const FrameResult r = odometry.Process(f);
    INFO("frame " << i << " " << r.StatusString());
    if (blank) {
      CHECK(r.status == FrameStatus::kPredicted);
    } else {
      REQUIRE(HasEstimate(r.status));
      CHECK(RigidNear(r.world_from_cam, path[i], 0.3, 0.01));
    }
  }
}

TEST_CASE("Guided matching follows a smooth path without falling back") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(12, 0.02, 1.5);
  OdometryOptions options;
  REQUIRE(options.guided_radius_px > 0);  // the default
  Odometry odometry(options, CalibFor(cam));
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    const FrameResult r = odometry.Process(Render(scene, cam, path[i], i));
    INFO("frame " << i << " " << r.StatusString() << " inliers " << r.inliers);
    REQUIRE((r.status == FrameStatus::kAccepted || r.status == FrameStatus::kFirst));
    CHECK(r.fallbacks == 0);
    CHECK(RigidNear(r.world_from_cam, path[i], 0.5, 0.01));
    if (i == 0) continue;
    CHECK(r.inliers > 100);
    REQUIRE(r.prediction_error_px.size() == static_cast<size_t>(r.inliers));
    // Frame 1 is predicted with zero velocity (some 15 px off: 1.5 degrees of yaw), the others
    // by constant velocity, which the path's slowly changing velocity (at most 0.15 degrees per
    // frame) leaves about 1 px off.
    std::vector<float> e = r.prediction_error_px;
    std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
    INFO("median prediction error " << e[e.size() / 2] << " px");
    CHECK(e[e.size() / 2] < (i == 1 ? options.guided_radius_px : 2.0));
    if (i == 1) CHECK(e[e.size() / 2] > 5.0);
  }
}

TEST_CASE("A prediction beyond the radius falls back to brute force and gives the right motion") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(3, 0.02, 1.5);
  // Frame 2's colour image claims to come 3 s later: constant velocity extrapolates 90 frame
  // steps (about 1.8 m and 135 degrees), so its keypoints are predicted far from where they are.
  Frame late = Render(scene, cam, path[2], 2);
  late.color_timestamp = 1 / 30.0 + 3.0;
  // SIFT and guided matching on every frame: one fallback. Tracking (the default): the tracks
  // seeded there fail, and SIFT matching falls back as well.
  for (bool track : {false, true}) {
    INFO("tracking " << track);
    OdometryOptions options;
    options.track_between_keyframes = track;
    Odometry odometry(options, CalibFor(cam));
    odometry.Process(Render(scene, cam, path[0], 0));
    REQUIRE(odometry.Process(Render(scene, cam, path[1], 1)).fallbacks == 0);
    const FrameResult r = odometry.Process(late);
    INFO(r.StatusString() << " inliers " << r.inliers);
    if (!track) CHECK(r.fallbacks == 1);
    CHECK(r.fallbacks >= 1);
    CHECK(!r.from_tracks);
    CHECK(r.status == FrameStatus::kAccepted);
    CHECK(RigidNear(r.world_from_cam, path[2], 0.5, 0.01));
  }
  // With brute force only there is nothing to fall back from.
  OdometryOptions brute;
  brute.track_between_keyframes = false;
  brute.guided_radius_px = 0;
  Odometry brute_odometry(brute, CalibFor(cam));
  brute_odometry.Process(Render(scene, cam, path[0], 0));
  brute_odometry.Process(Render(scene, cam, path[1], 1));
  const FrameResult b = brute_odometry.Process(late);
  CHECK(b.fallbacks == 0);
  CHECK(RigidNear(b.world_from_cam, path[2], 0.5, 0.01));
}

TEST_CASE("A prior off by most of the radius is corrected by matching again around the estimate") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(3, 0.02, 1.5);
  // Frame 2's colour image claims to come late, so constant velocity extrapolates further than
  // the camera moved: its keypoints are predicted about `late` steps of the path off (a step
  // moves them about 15 px), within the radius but beyond its inner half.
  const auto run = [&](bool rematch, double late) {
    OdometryOptions options;
    options.track_between_keyframes = false;  // SIFT matching on every frame
    options.guided_rematch = rematch;
    Odometry odometry(options, CalibFor(cam));
    odometry.Process(Render(scene, cam, path[0], 0));
    odometry.Process(Render(scene, cam, path[1], 1));
    Frame f = Render(scene, cam, path[2], 2);
    f.color_timestamp = f.timestamp = (2 + late) / 30.0;
    return odometry.Process(f);
  };
  const FrameResult exact = run(true, 0.0);
  INFO("with the right prior: " << exact.inliers << " inliers");
  CHECK(exact.rematches == 0);
  // 1.5 steps off: most prediction errors 15-30 px, so the radius cuts some right matches off.
  const FrameResult once = run(false, 1.5), again = run(true, 1.5);
  INFO("1.5 steps off: " << once.inliers << " inliers, matched again " << again.inliers);
  CHECK(once.rematches == 0);
  CHECK(again.rematches == 1);
  REQUIRE(once.status == FrameStatus::kAccepted);
  REQUIRE(again.status == FrameStatus::kAccepted);
  CHECK(once.inliers < 0.8 * exact.inliers);
  CHECK(again.inliers >= 0.95 * exact.inliers);
  CHECK(RigidNear(again.world_from_cam, path[2], 0.2, 0.005));
  // The prediction error is still measured from the prior the frame was predicted with.
  REQUIRE(!again.prediction_error_px.empty());
  const double radius_px = OdometryOptions().guided_radius_px;
  CHECK(*std::max_element(again.prediction_error_px.begin(), again.prediction_error_px.end()) >
        0.5 * radius_px);
}

TEST_CASE("A few-inlier estimate that matching around it does not reproduce goes to brute force") {
  // A wall 2 m away, 85 keypoints on a grid (100 px apart across, 25 px down, so that no window
  // of the guided radius holds two of them); the camera is still for two frames, then slides
  // so that every keypoint moves 60 px, twice the radius, where the still prior looks for it.
  // In the third frame, 16 of the keypoints have two look-alikes besides their own: one 20 px
  // from where they were (in the prior's window: a wrong motion they agree on) and one 45 px
  // (beyond it, but in the window around that wrong motion's prediction, 25 px away).
  const PinholeCamera cam;
  constexpr double kDepth = 2.0;
  cv::RNG rng(7);
  Features ref;
  for (int x = 40; x <= 440; x += 100)
    for (int y = 40; y <= 440; y += 25) ref.keypoints.emplace_back(cv::Point2f(x, y), 4.0f);
  const int n = static_cast<int>(ref.keypoints.size());
  ref.descriptors.create(n, 128, CV_8U);
  rng.fill(ref.descriptors, cv::RNG::UNIFORM, 0, 256);
  Features moved;
  std::vector<int> rows;
  const auto add = [&](int i, float shift) {
    moved.keypoints.emplace_back(ref.keypoints[i].pt + cv::Point2f(shift, 0), 4.0f);
    rows.push_back(i);
  };
  for (int i = 0; i < n; ++i) add(i, 60);
  constexpr int kLookAlikes = 16;
  for (int i = 0; i < kLookAlikes; ++i) add(5 * i, 20), add(5 * i, 45);
  moved.descriptors.create(static_cast<int>(rows.size()), 128, CV_8U);
  for (size_t k = 0; k < rows.size(); ++k)
    ref.descriptors.row(rows[k]).copyTo(moved.descriptors.row(static_cast<int>(k)));

  const auto frame = [&](int index) {
    Frame f;
    f.index = index;
    f.timestamp = f.color_timestamp = index / 30.0;
    f.bgr = cv::Mat(cam.height, cam.width, CV_8UC3, cv::Scalar::all(128));
    f.depth_m = cv::Mat(cam.height, cam.width, CV_32F, cv::Scalar(kDepth));
    return f;
  };
  const auto run = [&](bool rematch) {
    OdometryOptions options;
    options.guided_rematch = rematch;
    Odometry odometry(options, CalibFor(cam));
    odometry.Process(frame(0), ref);
    const FrameResult still = odometry.Process(frame(1), ref);
    REQUIRE(still.status == FrameStatus::kAccepted);
    REQUIRE(still.inliers == n);
    return odometry.Process(frame(2), moved);
  };
  // The camera slid 60 px x 2 m / 525 px = 0.229 m; the keypoints moved +x, so the camera -x.
  const double slide = 60 * kDepth / cam.fx;
  const FrameResult without = run(false), with = run(true);
  INFO("without matching again: " << without.inliers << " inliers, x "
                                  << without.world_from_cam.translation().x());
  INFO("with: " << with.inliers << " inliers, x " << with.world_from_cam.translation().x() << ", "
                << with.fallbacks << " brute-force estimates");
  // Without it the 16 look-alikes within the prior's window make a verified estimate a third
  // of the slide short.
  REQUIRE(HasFeatureEstimate(without.status));
  CHECK(without.inliers == kLookAlikes);
  CHECK(std::abs(without.world_from_cam.translation().x() + 20 * kDepth / cam.fx) < 0.005);
  // With it, matching around that estimate finds none (each look-alike has its twin within
  // the radius there), and brute force finds every keypoint without look-alikes.
  REQUIRE(with.status == FrameStatus::kAccepted);
  CHECK(with.rematches == 1);
  CHECK(with.fallbacks == 1);
  CHECK(with.inliers == n - kLookAlikes);
  CHECK(std::abs(with.world_from_cam.translation().x() + slide) < 0.005);
  CHECK(std::abs(with.world_from_cam.translation().y()) < 0.005);
  CHECK(std::abs(with.world_from_cam.translation().z()) < 0.005);
}

TEST_CASE("A new keyframe's pose is measured against the last frame too") {
  // The fusion acts only where a keyframe changes: until the first change the runs with and
  // without it agree exactly, from it on they differ. On exact rendering both stay as exact as
  // pixel quantisation allows (measured: at most 3.2 mm; summed over 40 frames 60 mm fused
  // against 46 mm: on clean data the second estimate adds the last frame's own error and gains
  // nothing; on real recordings it replaces a keyframe's weakest estimate,
  // docs/decisions/0018-keyframe-fusion.md).
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(40, 0.02, 1.5);
  const std::vector<Frame> frames = RenderPath(scene, cam, path);
  const auto run = [&](bool fuse) {
    OdometryOptions options;
    options.fuse_keyframe_pose = fuse;
    Odometry odometry(options, CalibFor(cam));
    std::vector<Rigid3d> poses;
    poses.reserve(frames.size());
    for (const Frame& f : frames) {
      const FrameResult r = odometry.Process(f);
      REQUIRE(HasFeatureEstimate(r.status));
      poses.push_back(r.world_from_cam);
    }
    return poses;
  };
  const std::vector<Rigid3d> fused = run(true);
  const std::vector<Rigid3d> single = run(false);
  int first_difference = -1;
  for (size_t i = 0; i < path.size(); ++i) {
    INFO("frame " << i);
    if (first_difference < 0 && !fused[i].isApprox(single[i], 1e-12))
      first_difference = static_cast<int>(i);
    CHECK(TranslationError(fused[i], path[i]) < 0.005);
    CHECK(TranslationError(single[i], path[i]) < 0.005);
  }
  INFO("first difference at frame " << first_difference);
  CHECK(first_difference > 1);
  CHECK(!PresetOptions("paper").fuse_keyframe_pose);
  const bool fuse = OdometryOptions().fuse_keyframe_pose;
  CHECK(fuse);
}

TEST_CASE("A frame's depth image is kept as it was when the caller writes the next into it") {
  // The odometry keeps a frame's depth image (the frame before a new keyframe is lifted from it
  // later, for the fusion). Handed over (std::move) it is kept without a copy; a caller that
  // reads every frame into the same cv::Mat keeps writing into the buffer it passed, so there
  // the odometry must keep a copy: both runs give the same poses, bit for bit.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(40, 0.02, 1.5);
  const OdometryOptions defaults;
  std::vector<Rigid3d> handed_over;
  int keyframes = 0;
  {
    Odometry odometry(defaults, CalibFor(cam));
    for (int i = 0; i < static_cast<int>(path.size()); ++i) {
      const FrameResult r = odometry.Process(Render(scene, cam, path[i], i));
      REQUIRE(HasFeatureEstimate(r.status));
      keyframes += r.keyframe ? 1 : 0;
      handed_over.push_back(r.world_from_cam);
    }
  }
  INFO(keyframes << " keyframes");
  REQUIRE(keyframes >= 3);  // the fusion lifts the frame before each from its kept depth
  Odometry odometry(defaults, CalibFor(cam));
  Frame reused;
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    const Frame f = Render(scene, cam, path[i], i);
    const uchar* buffer = reused.depth_m.data;
    reused.index = f.index;
    reused.timestamp = f.timestamp;
    reused.color_timestamp = f.color_timestamp;
    f.bgr.copyTo(reused.bgr);
    f.depth_m.copyTo(reused.depth_m);
    if (i > 0) REQUIRE(reused.depth_m.data == buffer);  // written in place
    const FrameResult r = odometry.Process(reused);
    INFO("frame " << i);
    CHECK(r.world_from_cam.matrix() == handed_over[i].matrix());
  }
}

TEST_CASE("The paper preset matches by brute force") {
  CHECK(PresetOptions("paper").guided_radius_px == 0);
  CHECK(PresetOptions("default").guided_radius_px > 0);
  CHECK(!PresetOptions("paper").guided_rematch);
  CHECK(PresetOptions("default").guided_rematch);
}

TEST_CASE("With the depth fallback the blurred frames of a burst are aligned by depth") {
  // As above, with the default depth fallback: each blurred frame's depth is aligned with the
  // last estimated frame's; the rendered depth is exact, so ICP lands on the truth.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = YawBurstPath(10, 5, 7, 3.0);
  OdometryOptions options;
  REQUIRE(options.depth_fallback);  // the default
  Odometry odometry(options, CalibFor(cam));
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    Frame f = Render(scene, cam, path[i], i);
    const bool blurred = i >= 5 && i <= 7;
    if (blurred) cv::GaussianBlur(f.bgr, f.bgr, cv::Size(0, 0), 25);
    const FrameResult r = odometry.Process(f);
    INFO("frame " << i << " " << r.StatusString());
    CHECK(r.status == (i == 0    ? FrameStatus::kFirst
                       : blurred ? FrameStatus::kDepth
                                 : FrameStatus::kAccepted));
    CHECK(HasEstimate(r.status));
    CHECK(RigidNear(r.world_from_cam, path[i], 0.3, 0.01));
  }
}

TEST_CASE("A frame's velocity is the motion from the estimated frame before it, per second") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(3, 0.02, 1.0);
  const OdometryOptions defaults;
  Odometry odometry(defaults, CalibFor(cam));
  Frame f0 = Render(scene, cam, path[0], 0);
  f0.timestamp = f0.color_timestamp + 0.01;  // the depth image 10 ms later
  const FrameResult r0 = odometry.Process(f0);
  CHECK(r0.depth_timestamp == f0.timestamp);
  CHECK(r0.velocity.rotation_per_s.norm() == 0);  // nothing to measure it by yet
  CHECK(r0.velocity.translation_per_s.norm() == 0);
  const FrameResult r1 = odometry.Process(Render(scene, cam, path[1], 1));
  const FrameResult r2 = odometry.Process(Render(scene, cam, path[2], 2));
  REQUIRE(r2.status == FrameStatus::kAccepted);
  const Velocity v = VelocityOf(r1.world_from_cam.inverse() * r2.world_from_cam, 1 / 30.0);
  CHECK((r2.velocity.rotation_per_s - v.rotation_per_s).norm() < 1e-9);
  CHECK((r2.velocity.translation_per_s - v.translation_per_s).norm() < 1e-9);
  // The true motion: 2 cm and 1 degree a frame, so 0.6 m/s and 30 deg/s.
  const Velocity truth = VelocityOf(path[1].inverse() * path[2], 1 / 30.0);
  CHECK((r2.velocity.translation_per_s - truth.translation_per_s).norm() < 0.1);
}

TEST_CASE("After frames aligned by depth the velocity is the feature estimate's own") {
  // Frames 3 and 4 are blurred, so aligned by depth; frame 4's depth image is taken 2 cm to the
  // side of its colour image, so its pose is 2 cm off. Frame 5's features, matched against the
  // keyframe (frame 2), put it right: that correction is no motion of the camera, and its
  // velocity is the true one (the difference from frame 4's pose would be 0.6 m/s off).
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = YawBurstPath(6, 3, 4, 1.0);
  Rigid3d aside = Rigid3d::Identity();
  aside.translation() = Eigen::Vector3d(0.02, 0, 0);
  const OdometryOptions defaults;
  Odometry odometry(defaults, CalibFor(cam));
  FrameResult r;
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    Frame f = Render(scene, cam, path[i], i);
    if (i == 3 || i == 4) cv::GaussianBlur(f.bgr, f.bgr, cv::Size(0, 0), 25);
    if (i == 4) f.depth_m = scene.RenderDepth(cam, path[i] * aside);
    r = odometry.Process(f);
    INFO("frame " << i << " " << r.StatusString());
    REQUIRE(r.status == (i == 0               ? FrameStatus::kFirst
                         : (i == 3 || i == 4) ? FrameStatus::kDepth
                                              : FrameStatus::kAccepted));
    if (i == 4)
      CHECK((r.world_from_cam.translation() - (path[i] * aside).translation()).norm() < 0.005);
  }
  CHECK(RigidNear(r.world_from_cam, path[5], 0.3, 0.005));
  const Velocity truth = VelocityOf(path[4].inverse() * path[5], 1 / 30.0);
  CHECK((r.velocity.translation_per_s - truth.translation_per_s).norm() < 0.05);
  CHECK((r.velocity.rotation_per_s - truth.rotation_per_s).norm() < 0.05);
}

TEST_CASE("A run of frames aligned by depth is aligned with its depth keyframe") {
  // Frames 1-20 are blurred, so aligned by depth; their depth images carry the Kinect's noise
  // (sigma 1.425e-3 z^2, fixed seeds). Each aligned with the frame before, the alignments' errors
  // add up along the run; aligned with the run's depth keyframe (frame 0: the scene stays in
  // view), they do not.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = YawBurstPath(21, 1, 20, 1.0);
  double end_error[2] = {0, 0};
  for (const bool keyframe : {true, false}) {
    OdometryOptions options;
    REQUIRE(options.depth_keyframe);  // the default
    options.depth_keyframe = keyframe;
    Odometry odometry(options, CalibFor(cam));
    FrameResult r;
    for (int i = 0; i < static_cast<int>(path.size()); ++i) {
      Frame f = Render(scene, cam, path[i], i);
      if (i >= 1) {
        cv::GaussianBlur(f.bgr, f.bgr, cv::Size(0, 0), 25);
        cv::RNG rng(static_cast<uint64_t>(i));
        AddKinectDepthNoise(rng, &f.depth_m);
      }
      r = odometry.Process(f);
      INFO("depth keyframe " << keyframe << ", frame " << i << " " << r.StatusString());
      REQUIRE(r.status == (i == 0 ? FrameStatus::kFirst : FrameStatus::kDepth));
    }
    const Rigid3d error = path.back().inverse() * r.world_from_cam;
    end_error[keyframe ? 0 : 1] = error.translation().norm();
  }
  INFO("end error with the depth keyframe " << end_error[0] << " m, frame to frame " << end_error[1]
                                            << " m");
  CHECK(end_error[0] < 0.5 * end_error[1]);
  CHECK(end_error[0] < 0.004);
}

TEST_CASE("Aligned frames take the free direction's velocity over the keyframe's span") {
  // A camera 1.7 m from the robot hall's far wall, pitched down to the floor, sliding 1 cm a
  // frame along the wall: no surface faces that direction, so the depth alignment takes the
  // prediction's translation there. Frame 2's colour image is rendered 1 cm further along, so
  // its feature estimate (against the keyframe, frame 0) is 1 cm off. The velocity from frames
  // 1 and 2 would be 1 cm a frame off, the one over the keyframe's span half that: the three
  // aligned frames after it end 1 + 3 x 0.5 = 2.5 cm off, not 1 + 3 x 1 = 4 cm.
  const SyntheticScene scene = SyntheticScene::RobotHall();
  const PinholeCamera cam;
  std::vector<Rigid3d> path;
  for (int i = 0; i < 6; ++i) {
    Rigid3d p = Rigid3d::Identity();
    p.linear() = Eigen::AngleAxisd(-20 * M_PI / 180, Eigen::Vector3d::UnitX()).matrix();
    p.translation() = Eigen::Vector3d(-1.5 + 0.01 * i, -0.6, 1.8);
    path.push_back(p);
  }
  Rigid3d aside = Rigid3d::Identity();
  aside.translation() = Eigen::Vector3d(0.01, 0, 0);
  const OdometryOptions options;
  Odometry odometry(options, CalibFor(cam));
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    Frame f = Render(scene, cam, path[i], i);
    if (i == 2) f.bgr = scene.RenderColor(cam, path[i] * aside);
    if (i >= 3) cv::GaussianBlur(f.bgr, f.bgr, cv::Size(0, 0), 25);
    const FrameResult r = odometry.Process(f);
    const Eigen::Vector3d error =
        r.world_from_cam.translation() - (path[0].inverse() * path[i]).translation();
    INFO("frame " << i << " " << r.StatusString() << " error " << error.transpose());
    REQUIRE(r.status == (i == 0  ? FrameStatus::kFirst
                         : i < 3 ? FrameStatus::kAccepted
                                 : FrameStatus::kDepth));
    CHECK(error.tail<2>().norm() < 0.003);  // what the surfaces constrain
    if (i == 2) CHECK(error.x() == Approx(0.01).margin(0.002));
    if (i == 5) CHECK(error.x() == Approx(0.025).margin(0.004));
  }
}

namespace {

// A robot's camera 0.5 m above the default room's floor (y = 1.5), pitched 20 degrees down and
// rolled 2 degrees, driving forward 1 cm and turning 1 degree per frame: world_from_cam poses
// relative to the first.
std::vector<Rigid3d> RobotPath(int n, Rigid3d* world_from_first) {
  Rigid3d mount = Rigid3d::Identity();
  mount.linear() = (Eigen::AngleAxisd(2 * M_PI / 180, Eigen::Vector3d::UnitZ()) *
                    Eigen::AngleAxisd(-20 * M_PI / 180, Eigen::Vector3d::UnitX()))
                       .toRotationMatrix();
  Rigid3d robot = Rigid3d::Identity();
  robot.translation() = Eigen::Vector3d(-0.3, 1.0, -0.5);
  std::vector<Rigid3d> path;
  for (int i = 0; i < n; ++i) {
    path.push_back(robot * mount);
    Rigid3d step = Rigid3d::Identity();
    step.linear() = Eigen::AngleAxisd(M_PI / 180, Eigen::Vector3d::UnitY()).matrix();
    step.translation() = Eigen::Vector3d(0, 0, 0.01);
    robot = robot * step;
  }
  *world_from_first = path.front();
  for (Rigid3d& p : path) p = world_from_first->inverse() * p;
  return path;
}

}  // namespace

TEST_CASE("Planar motion: the floor is found in the first frame and the path kept on it") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  Rigid3d world_from_first;
  const std::vector<Rigid3d> path = RobotPath(25, &world_from_first);
  OdometryOptions options;
  options.motion.model = MotionModelKind::kPlanar;
  Odometry odometry(options, CalibFor(cam));
  const Eigen::Vector3d normal_in_first =
      world_from_first.linear().transpose() * Eigen::Vector3d::UnitY();
  FrameResult last;
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    Frame f = Render(scene, cam, world_from_first * path[i], i);
    last = odometry.Process(f);
    INFO("frame " << i << " " << last.StatusString() << "; " << odometry.MotionModelBrief());
    REQUIRE(HasEstimate(last.status));
    // Every pose keeps the first camera's height above the floor (to the fitted normal's error:
    // 0.3 degrees over at most 0.25 m) and its tilt.
    CHECK(std::abs(normal_in_first.dot(last.world_from_cam.translation())) < 0.002);
    CHECK(RotationErrorDeg(last.world_from_cam, path[i]) < 0.5);
    CHECK(TranslationError(last.world_from_cam, path[i]) < 0.01);
  }
  CHECK_THAT(odometry.MotionModelBrief(), Catch::Contains("floor fitted in frame 0"));
  CHECK(RigidNear(last.world_from_cam, path.back(), 0.3, 0.005));
}

TEST_CASE("Planar motion without a floor in view needs the mount given") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  Rigid3d looking_up = Rigid3d::Identity();  // 25 degrees up: the floor out of view
  looking_up.linear() = Eigen::AngleAxisd(25 * M_PI / 180, Eigen::Vector3d::UnitX()).matrix();
  const Frame f = Render(scene, cam, looking_up, 0);
  OdometryOptions options;
  options.motion.model = MotionModelKind::kPlanar;
  Odometry fitted(options, CalibFor(cam));
  CHECK_THROWS_WITH(fitted.Process(f), Catch::Contains("no floor in the first frame") &&
                                           Catch::Contains("--floor accelerometer"));
  options.motion.floor = FloorSource::kGiven;
  Odometry given(options, CalibFor(cam));
  CHECK(given.Process(f).status == FrameStatus::kFirst);
  CHECK_THAT(given.MotionModelBrief(), Catch::Contains("mount given: pitch 0.0 deg, roll 0.0"));
}

TEST_CASE("Planar motion can take the floor's normal from the first frame's accelerometer") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  Rigid3d world_from_first;
  const std::vector<Rigid3d> path = RobotPath(8, &world_from_first);
  OdometryOptions options;
  options.motion.model = MotionModelKind::kPlanar;
  options.motion.floor = FloorSource::kAccelerometer;
  Odometry odometry(options, CalibFor(cam));
  Frame first = Render(scene, cam, world_from_first * path[0], 0);
  CHECK_THROWS_WITH(odometry.Process(first), Catch::Contains("has no accelerometer reading"));
  const Eigen::Vector3d down(0, 9.80665, 0);  // the room's floor is at +y
  Odometry with_reading(options, CalibFor(cam));
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    Frame f = Render(scene, cam, world_from_first * path[i], i);
    f.gravity_in_cam = (world_from_first * path[i]).linear().transpose() * down;
    const FrameResult r = with_reading.Process(f);
    INFO("frame " << i << " " << r.StatusString() << "; " << with_reading.MotionModelBrief());
    REQUIRE(HasEstimate(r.status));
    CHECK(RotationErrorDeg(r.world_from_cam, path[i]) < 0.1);
    CHECK(TranslationError(r.world_from_cam, path[i]) < 0.005);
  }
  // The mount: pitched 20 degrees down, rolled 2 degrees (RobotPath).
  CHECK_THAT(with_reading.MotionModelBrief(),
             Catch::Contains("accelerometer reading: pitch 20.0 deg, roll") &&
                 Catch::Contains("|a| 9.81 m/s^2"));
  options.gravity_correction = true;
  CHECK_THROWS_WITH(options.Check(), Catch::Contains("gravity_correction"));
}

TEST_CASE("Gravity: readings that say a still camera has rolled pull it and the poses after it") {
  // The features say the camera stands still; after the first time constant (0.5 s, whose
  // readings set the world's down) the accelerometer says it has rolled 3 degrees. Every frame
  // turns the pose by 1/15 of the remaining disagreement, and the frames chained after it keep
  // that turn: after 24 frames 1 - (14/15)^24 = 81 % of the roll is taken. The same when the
  // frames after the first are blurred, so aligned by depth with the run's depth keyframe,
  // whose pose is turned with the others.
  const bool blurred = GENERATE(false, true);
  INFO((blurred ? "frames aligned by depth" : "feature estimates"));
  const SyntheticScene scene;
  const PinholeCamera cam;
  OdometryOptions options;
  options.gravity_correction = true;
  options.gravity.time_constant_s = 0.5;
  Odometry odometry(options, CalibFor(cam));
  const Frame still = Render(scene, cam, Rigid3d::Identity(), 0);
  Frame still_blurred = still;
  still_blurred.bgr = cv::Mat();  // not the pixels `still` shares
  cv::GaussianBlur(still.bgr, still_blurred.bgr, cv::Size(0, 0), 25);
  const Eigen::Vector3d down(0, 9.80665, 0);
  const Eigen::Matrix3d roll = Eigen::AngleAxisd(3 * M_PI / 180, Eigen::Vector3d::UnitZ()).matrix();
  FrameResult r;
  int window = 0, corrected = 0;
  for (int i = 0; i < 40; ++i) {
    Frame f = blurred && i > 0 ? still_blurred : still;
    f.index = i;
    f.timestamp = f.color_timestamp = i / 30.0;
    const bool settled = f.color_timestamp > options.gravity.time_constant_s;
    (settled ? corrected : window)++;
    f.gravity_in_cam = settled ? Eigen::Vector3d(roll.transpose() * down) : down;
    r = odometry.Process(f);
    INFO("frame " << i << " " << r.StatusString());
    if (blurred && i > 0)
      REQUIRE(r.status == FrameStatus::kDepth);
    else
      REQUIRE(HasFeatureEstimate(r.status));
    if (!settled)  // ICP's own residual on the still frames: a few 1e-6 degrees
      CHECK(RotationErrorDeg(r.world_from_cam, Rigid3d::Identity()) < (blurred ? 1e-4 : 1e-6));
  }
  REQUIRE(corrected == 24);
  Rigid3d expected = Rigid3d::Identity();
  expected.linear() =
      Eigen::AngleAxisd((1 - std::pow(14.0 / 15, 24)) * 3 * M_PI / 180, Eigen::Vector3d::UnitZ())
          .matrix();
  INFO(odometry.GravityBrief());
  CHECK(RigidNear(r.world_from_cam, expected, 0.02, 1e-4));
  CHECK_THAT(odometry.GravityBrief(), Catch::Contains("40 frames with an accelerometer reading"));
  CHECK_THAT(odometry.MotionModelBrief(), Catch::Contains("roll and pitch pulled toward"));
}

TEST_CASE("Tracking between keyframes follows a synthetic path, SIFT on a part of the frames") {
  // The same bounds as SIFT on every frame ("Odometry recovers a synthetic camera path"): the
  // tracked pairs carry the frames between keyframes, SIFT runs on the keyframes, the frames
  // before them (keyframe fusion) and where tracking fails.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(30, 0.02, 1.5);
  OdometryOptions options;
  options.track_between_keyframes = true;
  Odometry odometry(options, CalibFor(cam));
  REQUIRE(odometry.ExtractsLazily());
  FrameResult last;
  int sift_frames = 0;
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    last = odometry.Process(Render(scene, cam, path[i], i));
    INFO("frame " << i << " " << last.StatusString() << " inliers " << last.inliers);
    REQUIRE((last.status == FrameStatus::kAccepted || last.status == FrameStatus::kFirst));
    CHECK(TranslationError(last.world_from_cam, path[i]) < 0.02);
    if (last.times.features > 0) ++sift_frames;
    if (last.times.features == 0) CHECK(last.features <= options.tracking.max_points);
    // SIFT's time goes with its runs; a frame measured from tracks ran none.
    CHECK((last.sift_runs > 0) == (last.times.features > 0));
    if (last.from_tracks) CHECK(last.sift_runs == 0);
  }
  INFO("SIFT on " << sift_frames << " of " << path.size() << " frames");
  CHECK(sift_frames >= 2);
  CHECK(sift_frames <= static_cast<int>(path.size()) / 2);
  CHECK(RigidNear(last.world_from_cam, path.back(), 1.0, 0.02));
  const OdometryOptions defaults;
  CHECK(defaults.track_between_keyframes);
  CHECK(defaults.tracking.warp);
  CHECK(!PresetOptions("paper").track_between_keyframes);
}

TEST_CASE("A keyframe reached by tracking takes its pose from SIFT matching") {
  // With few tracked keypoints, a tracked estimate has at most that many inliers; a frame that
  // becomes a keyframe is matched by SIFT against the old keyframe as without tracking, and its
  // estimate (with more inliers than the tracks could give) is the one kept.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(30, 0.02, 1.5);
  OdometryOptions options;
  options.track_between_keyframes = true;
  options.tracking.max_points = 30;
  Odometry odometry(options, CalibFor(cam));
  int tracked = 0, keyframes = 0;
  for (int i = 0; i < static_cast<int>(path.size()); ++i) {
    const FrameResult r = odometry.Process(Render(scene, cam, path[i], i));
    INFO("frame " << i << " " << r.StatusString() << " inliers " << r.inliers);
    REQUIRE((r.status == FrameStatus::kAccepted || r.status == FrameStatus::kFirst));
    if (r.status == FrameStatus::kFirst) continue;
    CHECK(TranslationError(r.world_from_cam, path[i]) < 0.02);
    if (r.times.features > 0) {  // SIFT ran: the frame became a keyframe
      ++keyframes;
      CHECK(r.inliers > options.tracking.max_points);
      CHECK(!r.from_tracks);
    } else {
      ++tracked;
      CHECK(r.inliers <= options.tracking.max_points);
      CHECK(r.from_tracks);
    }
  }
  CHECK(keyframes >= 1);
  CHECK(tracked >= 10);
}

TEST_CASE("Where the tracks fail and SIFT reaches the keyframe, the keyframe stays") {
  // Fewer tracks than verification needs (min_inliers): every tracked estimate fails. Each
  // frame is then matched by SIFT against the keyframe, which is renewed by the inlier rule as
  // without tracking, not at every frame (that would chain the poses frame to frame).
  const SyntheticScene scene;
  const PinholeCamera cam;
  const std::vector<Rigid3d> path = MakeSmoothPath(30, 0.02, 1.5);
  const auto keyframes_of = [&](const OdometryOptions& options) {
    Odometry odometry(options, CalibFor(cam));
    int keyframes = 0;
    for (int i = 0; i < static_cast<int>(path.size()); ++i) {
      const FrameResult r = odometry.Process(Render(scene, cam, path[i], i));
      INFO("frame " << i << " " << r.StatusString() << " inliers " << r.inliers);
      REQUIRE((r.status == FrameStatus::kAccepted || r.status == FrameStatus::kFirst));
      CHECK(!r.from_tracks);
      CHECK(TranslationError(r.world_from_cam, path[i]) < 0.02);
      if (r.keyframe) ++keyframes;
    }
    return keyframes;
  };
  OdometryOptions options;
  options.keyframe_inlier_ratio = 0.9;  // renewals happen within the 30 frames
  options.track_between_keyframes = false;
  const int without_tracking = keyframes_of(options);
  options.track_between_keyframes = true;
  options.tracking.max_points = options.verify.min_inliers - 1;
  const int tracks_failing = keyframes_of(options);
  INFO("keyframes without tracking " << without_tracking << ", tracks failing " << tracks_failing);
  CHECK(without_tracking >= 2);
  CHECK(tracks_failing <= without_tracking + 2);
  CHECK(tracks_failing < static_cast<int>(path.size()) / 2);
}
