#include "rgbdvo/synthetic/robot_path.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "rgbdvo/estimation/floor_plane.hpp"
#include "rgbdvo/evaluation/evaluation.hpp"
#include "rgbdvo/io/trajectory_io.hpp"
#include "rgbdvo/odometry/odometry.hpp"
#include "rgbdvo/pipeline/run.hpp"
#include "rgbdvo/sensor/kinect_accelerometer.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"
#include "rgbdvo/sources/fakenect_files.hpp"
#include "rgbdvo/sources/fakenect_source.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

constexpr double kDeg = M_PI / 180;

// Yaw of the robot carrying a camera at world_from_color (MakeRobotPath's mount taken off).
double RobotYaw(const RobotPathOptions& o, const Rigid3d& world_from_color) {
  const Eigen::Matrix3d mount = (Eigen::AngleAxisd(-o.pitch_deg * kDeg, Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(o.roll_deg * kDeg, Eigen::Vector3d::UnitZ()))
                                    .toRotationMatrix();
  const Eigen::Matrix3d robot = world_from_color.linear() * mount.transpose();
  CHECK((robot * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitY()).norm() < 1e-12);
  return std::atan2(robot(0, 2), robot(2, 2));
}

// The robot recording shared by the tests (made once per test process): 75 frames (2.5 s,
// 1 m) from 0.5 m before the first corner, through half of the turn.
constexpr int kFrames = 75;
RobotPathOptions SharedPath() {
  RobotPathOptions o;
  o.start_m = o.size_z_m - 2 * o.turn_radius_m - 0.5;
  return o;
}
const std::string& Recording() {
  static const std::string dir = [] {
    std::string d = MakeTempDir("robot") + "/rec";
    WriteRobotRecording(d, SharedPath(), kFrames);
    return d;
  }();
  return dir;
}

// The odometry's results on a robot recording with its depth-aware calibration, single-threaded.
std::vector<FrameResult> RunOnRecording(const std::string& folder, const OdometryOptions& options) {
  Odometry odometry(options, LoadCalibration(folder + "/calib_depth_aware.yaml"));
  FakenectSource source(folder, {});
  std::vector<FrameResult> results;
  RunOptions run;
  run.threads = 1;
  RunOdometry(
      source, odometry, {}, [&](const FrameResult& r) { results.push_back(r); }, run);
  return results;
}

// robot.txt's `key: value` lines.
std::map<std::string, double> ReadRobotTxt(const std::string& path) {
  std::map<std::string, double> values;
  for (const std::string& line : Lines(path)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t colon = line.find(':');
    REQUIRE(colon != std::string::npos);
    values[line.substr(0, colon)] = std::stod(line.substr(colon + 1));
  }
  return values;
}

}  // namespace

TEST_CASE("The robot path is planar: fixed height, pitch and roll, 360 degrees of yaw per lap") {
  const RobotPathOptions o;
  const int lap = o.LapFrames();
  // 15.97 m at 0.4 m/s, 30 Hz: 39.9 s.
  CHECK(o.LapLength() == Approx(2 * (3.5 + 5.0) - 8 * 0.6 + 2 * M_PI * 0.6));
  CHECK(lap == 1198);
  const std::vector<Rigid3d> path = MakeRobotPath(o, lap + 1);
  double yaw_sum = 0, max_step_deg = 0;
  for (int k = 0; k <= lap; ++k) {
    CHECK(path[k].translation().y() == -o.camera_height_m);
    const double yaw = RobotYaw(o, path[k]);
    if (k > 0) {
      const double step = std::remainder(yaw - RobotYaw(o, path[k - 1]), 2 * M_PI);
      CHECK(step >= 0);  // right turns only
      yaw_sum += step;
      max_step_deg = std::max(max_step_deg, step / kDeg);
      const double moved = (path[k].translation() - path[k - 1].translation()).norm();
      CHECK(moved == Approx(o.speed_mps / o.frame_rate_hz).epsilon(1e-3));
    }
  }
  CHECK(yaw_sum / kDeg == Approx(360.0).margin(1e-6));
  // 0.4 m/s on a 0.6 m radius: 38.2 deg/s, 1.27 degrees per frame.
  CHECK(max_step_deg == Approx(0.4 / 0.6 / kDeg / 30).epsilon(1e-6));
  // One lap closes the loop to within the rounding of the lap to whole frames (< 1 cm).
  CHECK(TranslationError(path[0], path[lap]) < 0.4 / 30 / 2 + 1e-9);
  CHECK(RotationErrorDeg(path[0], path[lap]) < 1e-6);

  RobotPathOptions bad;
  bad.turn_radius_m = 2.0;
  CHECK_THROWS_WITH(MakeRobotPath(bad, 1), Catch::Contains("size_x_m"));
}

TEST_CASE("The robot's IR camera sees the floor where robot.txt says", "[long]") {
  const std::map<std::string, double> truth = ReadRobotTxt(Recording() + "/robot.txt");
  // The colour camera at 0.6 m, 12 degrees down, rolled 1 degree; the IR camera 2.5 cm along
  // its x axis, so 2.5 cm * sin(1 deg) cos(12 deg) lower, and the roll about its optical axis
  // measured in the floor's normal, asin(cos(12 deg) sin(1 deg)).
  CHECK(truth.at("ir_height_m") ==
        Approx(0.6 - 0.025 * std::sin(1 * kDeg) * std::cos(12 * kDeg)).margin(1e-6));
  CHECK(truth.at("ir_pitch_deg") == Approx(12.0).margin(0.01));
  CHECK(truth.at("ir_roll_deg") ==
        Approx(std::asin(std::cos(12 * kDeg) * std::sin(1 * kDeg)) / kDeg).margin(1e-6));
  CHECK(truth.at("lap_frames") == 1198);

  FakenectSource source(Recording(), {});
  const std::optional<Frame> first = source.Next();
  REQUIRE(first);
  Rng rng(3);
  const FloorFit fit =
      FitFloor({}, LoadCalibration(Recording() + "/calib_depth_aware.yaml"), first->depth_m, rng);
  INFO(fit.Brief());
  REQUIRE(fit.success);
  // Measured: 0.5997 m, 12.01 and 0.97 degrees (truth 0.5996, 12.00, 0.98).
  CHECK(fit.height_m == Approx(truth.at("ir_height_m")).margin(0.003));
  CHECK(fit.pitch_deg == Approx(truth.at("ir_pitch_deg")).margin(0.1));
  CHECK(fit.roll_deg == Approx(truth.at("ir_roll_deg")).margin(0.1));
}

TEST_CASE("The robot recording's depth has the Kinect's noise, sigma = 1.425e-3 Z^2", "[long]") {
  // The first depth image against the same view rendered without noise, both quantised to raw
  // disparity: at 1.5-2.1 m (the floor and the wall ahead; sigma 3.2-6.3 mm, raw steps 6-12 mm)
  // their difference spreads about as the noise does; without noise it would be 0. Measured:
  // rms 7.4 mm against an rms sigma of 5.6 mm (the quantisation adds to it).
  const SyntheticKinectOptions o = RobotKinectOptions(7);
  Rigid3d color_from_ir = Rigid3d::Identity();
  color_from_ir.translation() = o.ir_in_color;
  const cv::Mat clean =
      DepthFromKinectRaw(KinectRawFromDepth(SyntheticScene::RobotHall(7).RenderDepth(
          o.ir, MakeRobotPath(SharedPath(), 1)[0] * color_from_ir)));
  FakenectSource source(Recording(), {});
  const std::optional<Frame> first = source.Next();
  REQUIRE(first);
  double sum_sq = 0, sum_sigma_sq = 0;
  int n = 0;
  for (int v = 0; v < clean.rows; ++v)
    for (int u = 0; u < clean.cols; ++u) {
      const double z = clean.at<float>(v, u), noisy = first->depth_m.at<float>(v, u);
      if (z < 1.5 || z > 2.1 || noisy <= 0) continue;
      sum_sq += (noisy - z) * (noisy - z);
      sum_sigma_sq += std::pow(1.425e-3 * z * z, 2);
      ++n;
    }
  REQUIRE(n > 1000);
  const double rms = std::sqrt(sum_sq / n), sigma = std::sqrt(sum_sigma_sq / n);
  INFO(n << " pixels at 1.5-2.1 m: rms difference " << rms << " m, sigma " << sigma << " m");
  CHECK(rms > 0.8 * sigma);
  CHECK(rms < 1.6 * sigma);
}

TEST_CASE("The robot's accelerometer reads gravity and the centripetal acceleration", "[long]") {
  // Apparent gravity g - a in the colour camera's frame as the library reads it back: on the
  // straight the world's down; in the turn also v^2 / r = 0.267 m/s^2 away from the centre
  // (within one count, 0.012 m/s^2).
  const RobotPathOptions o = SharedPath();
  const std::vector<Rigid3d> path = MakeRobotPath(o, kFrames);
  std::vector<Eigen::Vector3d> readings;
  for (const std::string& name : ReadFakenectIndex(Recording() + "/INDEX.txt")) {
    if (name[0] != 'a') continue;
    readings.push_back(ApparentGravityFromKinectAccel(ReadFakenectAccel(Recording() + "/" + name)));
  }
  REQUIRE(readings.size() == static_cast<size_t>(kFrames));
  const double centripetal = o.speed_mps * o.speed_mps / o.turn_radius_m;
  const double count = kStandardGravity / kKinectAccelCountsPerG;
  for (int k : {5, 30, 60, 70}) {
    const bool turning = k * o.speed_mps / o.frame_rate_hz > 0.5 + 0.02;
    const Eigen::Vector3d in_world = path[k].linear() * readings[k];
    // Away from the centre of the right turn: to the robot's left, -(cos yaw, 0, -sin yaw).
    const Eigen::Vector3d right = path[k].linear() * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d right_level = Eigen::Vector3d(right.x(), 0, right.z()).normalized();
    INFO("frame " << k << " reading in world " << in_world.transpose());
    CHECK(in_world.y() == Approx(kStandardGravity).margin(count));
    CHECK(-in_world.dot(right_level) == Approx(turning ? centripetal : 0).margin(count));
  }
}

TEST_CASE("The odometry follows a short robot recording through its first turn") {
  const Trajectory truth = ReadTrajectory(Recording() + "/groundtruth.txt");
  const OdometryOptions defaults;
  std::vector<StampedPose> estimate;
  int estimated = 0;
  for (const FrameResult& r : RunOnRecording(Recording(), defaults)) {
    estimate.push_back({r.timestamp, r.world_from_cam});
    estimated += r.status == FrameStatus::kAccepted || r.status == FrameStatus::kFirst;
  }
  const AteResult ate = ComputeAte(truth.poses, estimate, {});
  REQUIRE(ate.success);
  const Rigid3d end_truth =
      truth.poses.front().world_from_cam.inverse() * truth.poses.back().world_from_cam;
  const Rigid3d end_estimate =
      estimate.front().world_from_cam.inverse() * estimate.back().world_from_cam;
  INFO(ate.Brief() << "; end error " << TranslationError(end_truth, end_estimate) << " m, "
                   << RotationErrorDeg(end_truth, end_estimate) << " deg; " << estimated
                   << " frames estimated from features");
  // Measured: ATE RMSE 1.5 mm, end error 1.6 mm and 0.06 degrees over the 1 m, every frame
  // estimated from features (the textured part of the hall).
  CHECK(ate.matched == kFrames);
  CHECK(estimated >= kFrames - 2);
  CHECK(ate.error_m.rmse < 0.005);
  CHECK(TranslationError(end_truth, end_estimate) < 0.01);
  CHECK(RotationErrorDeg(end_truth, end_estimate) < 0.3);
}

TEST_CASE("On the robot's feature-poor side the depth surfaces join and pin the slide", "[long]") {
  // 60 frames (2 s) along the grey mat, the grey panel ahead: 16-90 inliers, few of them on
  // the panel, where a turn and a sideways slide look alike. The depth term joins the frames
  // whose features leave the translation uncertain. Measured: ATE 31.4 mm with features only,
  // 2.9 mm by default.
  RobotPathOptions path;
  path.start_m = 830 / path.frame_rate_hz * path.speed_mps;
  const std::string folder = MakeTempDir("robot_poor") + "/rec";
  WriteRobotRecording(folder, path, 60);
  const Trajectory truth = ReadTrajectory(folder + "/groundtruth.txt");
  const auto ate_m = [&](int depth_term_step) {
    OdometryOptions options;
    options.depth_term_step = depth_term_step;
    std::vector<StampedPose> estimate;
    for (const FrameResult& r : RunOnRecording(folder, options))
      estimate.push_back({r.timestamp, r.world_from_cam});
    const AteResult ate = ComputeAte(truth.poses, estimate, {});
    REQUIRE(ate.success);
    return ate.error_m.rmse;
  };
  const OdometryOptions defaults;
  const double features_only = ate_m(0), with_depth = ate_m(defaults.depth_term_step);
  INFO("ATE RMSE: features only " << features_only << " m, by default " << with_depth << " m");
  CHECK(with_depth < 0.5 * features_only);
  CHECK(with_depth < 0.006);
}
