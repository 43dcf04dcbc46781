// ATE and RPE on hand-computable trajectories.
#include "rgbdvo/evaluation/evaluation.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

Rigid3d Pose(double yaw_deg, const Eigen::Vector3d& t) {
  Rigid3d T = Rigid3d::Identity();
  T.linear() = AxisAngle(Eigen::Vector3d::UnitZ(), yaw_deg * M_PI / 180);
  T.translation() = t;
  return T;
}

// n poses 0.1 s apart starting at t0, pose k = f(t_k).
template <typename F>
std::vector<StampedPose> Sampled(int n, double t0, F f) {
  std::vector<StampedPose> out;
  for (int k = 0; k < n; ++k) out.push_back({t0 + 0.1 * k, f(0.1 * k)});
  return out;
}

// A curvy path with rotations: not collinear, so the ATE alignment is unique.
std::vector<StampedPose> CurvyPath() {
  std::mt19937 rng(11);
  return Sampled(50, 100.0, [&](double t) {
    return Pose(20 * std::sin(t), Eigen::Vector3d(std::cos(t), std::sin(2 * t), 0.3 * t)) *
           RandomRigid(rng, 0.02, 0.0);
  });
}

}  // namespace

TEST_CASE("An estimate equal to the ground truth moved rigidly has ATE 0 and RPE 0") {
  const std::vector<StampedPose> gt = CurvyPath();
  std::mt19937 rng(5);
  const Rigid3d est_from_gt = RandomRigid(rng, 2.0, 3.0);  // 115 deg, 3 m
  std::vector<StampedPose> est = gt;
  for (StampedPose& p : est) p.world_from_cam = est_from_gt * p.world_from_cam;

  const AteResult ate = ComputeAte(gt, est, {});
  REQUIRE(ate.success);
  CHECK(ate.matched == 50);
  CHECK(ate.error_m.rmse < 1e-9);
  CHECK(ate.error_m.max < 1e-9);
  CHECK(RigidNear(ate.gt_from_est, est_from_gt.inverse(), 1e-6, 1e-9));
  const RpeResult rpe = ComputeRpe(gt, est, {});
  REQUIRE(rpe.success);
  CHECK(rpe.trans_m.max < 1e-9);
  CHECK(rpe.rot_deg.max < 1e-4);
}

TEST_CASE("ATE of a saddle-shaped error no rigid motion can reduce is its height") {
  // Ground truth on the unit square in z = 0; the estimate lifts its corners by +h, -h, +h, -h.
  // The centred cross-covariance is diag(1, 1, 0), so the best fit is the identity and every
  // corner is h off: rmse = mean = max = h.
  const double h = 0.1;
  std::vector<StampedPose> gt, est;
  const double corner[4][3] = {{0, 0, h}, {1, 0, -h}, {1, 1, h}, {0, 1, -h}};
  for (int k = 0; k < 4; ++k) {
    gt.push_back({double(k), Pose(0, {corner[k][0], corner[k][1], 0})});
    est.push_back({double(k), Pose(0, {corner[k][0], corner[k][1], corner[k][2]})});
  }
  const AteResult ate = ComputeAte(gt, est, {});
  REQUIRE(ate.success);
  CHECK(ate.error_m.rmse == Approx(h).epsilon(1e-9));
  CHECK(ate.error_m.mean == Approx(h).epsilon(1e-9));
  CHECK(ate.error_m.max == Approx(h).epsilon(1e-9));
  CHECK(RigidNear(ate.gt_from_est, Rigid3d::Identity(), 1e-6, 1e-9));
}

TEST_CASE("A constant per-second drift gives a known RPE") {
  // Ground truth moves along x at 0.1 m/s; the estimate at 0.12 m/s: every 1 s pair is
  // 0.02 m off, whatever its start.
  const auto gt = Sampled(51, 0.0, [](double t) { return Pose(0, {0.1 * t, 0, 0}); });
  auto est = Sampled(51, 0.0, [](double t) { return Pose(0, {0.12 * t, 0, 0}); });
  RpeResult rpe = ComputeRpe(gt, est, {});
  REQUIRE(rpe.success);
  CHECK(rpe.pairs == 40);  // i = 0..39; from i = 40 on, j is the last pose and is dropped
  CHECK(rpe.trans_m.rmse == Approx(0.02).epsilon(1e-9));
  CHECK(rpe.trans_m.median == Approx(0.02).epsilon(1e-9));
  CHECK(rpe.rot_deg.max < 1e-6);

  EvaluationOptions half;
  half.delta_s = 0.5;
  CHECK(ComputeRpe(gt, est, half).trans_m.rmse == Approx(0.01).epsilon(1e-9));

  // A camera that stays put while the estimate turns at 2 deg/s about its own centre: every
  // 1 s pair is off by a 2 deg rotation and no translation.
  est = Sampled(51, 0.0, [](double t) { return Pose(2 * t, {0, 0, 0}); });
  const auto still = Sampled(51, 0.0, [](double) { return Pose(0, {0, 0, 0}); });
  rpe = ComputeRpe(still, est, {});
  REQUIRE(rpe.success);
  CHECK(rpe.rot_deg.rmse == Approx(2.0).epsilon(1e-9));
  CHECK(rpe.rot_deg.mean == Approx(2.0).epsilon(1e-9));
  CHECK(rpe.trans_m.max < 1e-12);
}

TEST_CASE("Estimate poses without ground truth nearby are excluded") {
  const std::vector<StampedPose> gt = CurvyPath();  // 100.0 .. 104.9 s
  std::vector<StampedPose> est = gt;
  // Far-off poses 2-3 s after the ground truth ends, and one between two ground truth samples
  // (0.05 s from both, more than max_dt).
  for (int k = 0; k < 10; ++k) est.push_back({107.0 + 0.1 * k, Pose(0, {50, 50, 50})});
  const AteResult ate = ComputeAte(gt, est, {});
  REQUIRE(ate.success);
  CHECK(ate.matched == 50);
  CHECK(ate.error_m.max < 1e-9);
  const RpeResult rpe = ComputeRpe(gt, est, {});  // no ground truth within 0.2 s of 107+
  REQUIRE(rpe.success);
  CHECK(rpe.trans_m.max < 1e-9);

  // A pose 0.05 s from two ground truth poses: too far at max_dt 0.02 s; at 0.06 s it is a
  // candidate, but both ground truth poses have an exact match, which is closer and wins.
  std::vector<StampedPose> between = gt;
  between.insert(between.begin() + 1, {100.05, Pose(0, {9, 9, 9})});
  CHECK(ComputeAte(gt, between, {}).matched == 50);
  EvaluationOptions loose;
  loose.max_dt_s = 0.06;
  const AteResult ate_loose = ComputeAte(gt, between, loose);
  CHECK(ate_loose.matched == 50);
  CHECK(ate_loose.error_m.max < 1e-9);
}

TEST_CASE("Association takes the closest pairs first and uses each pose once") {
  const std::vector<StampedPose> gt = {{1.000, Rigid3d::Identity()}, {1.030, Rigid3d::Identity()}};
  const std::vector<StampedPose> est = {
      {1.012, Rigid3d::Identity()}, {1.015, Rigid3d::Identity()}, {1.100, Rigid3d::Identity()}};
  const auto m = AssociateByTime(gt, est, 0.02);
  // 1.015 is closest to 1.030 (0.015), 1.012 to 1.000 (0.012); 1.100 has none.
  REQUIRE(m.size() == 2);
  CHECK(m[0] == std::make_pair(0, 0));
  CHECK(m[1] == std::make_pair(1, 1));
}

TEST_CASE("Error statistics: rmse, mean, median, max") {
  const ErrorStats s = ComputeStats({4, 3, 0, 1});
  CHECK(s.count == 4);
  CHECK(s.rmse == Approx(std::sqrt(26.0 / 4)));
  CHECK(s.mean == Approx(2.0));
  CHECK(s.median == Approx(2.0));
  CHECK(s.max == 4);
  CHECK(ComputeStats({5, 1, 2}).median == 2);
}

TEST_CASE("Evaluation refuses no overlap and bad options, and reports too short runs") {
  const std::string dir = MakeTempDir("eval");
  std::ofstream(dir + "/gt.txt") << "1 0 0 0 0 0 0 1\n1.1 0 0 0 0 0 0 1\n1.2 0 0 0 0 0 0 1\n";
  std::ofstream(dir + "/est.txt") << "5 0 0 0 0 0 0 1\n5.1 0 0 0 0 0 0 1\n";
  CHECK_THROWS_WITH(EvaluateFiles(dir + "/gt.txt", dir + "/est.txt", {}),
                    Catch::Contains("no overlapping timestamps") && Catch::Contains("est.txt"));

  EvaluationOptions bad;
  bad.delta_s = -1;
  CHECK_THROWS_WITH(bad.Check(), Catch::Contains("delta_s"));

  // Same three poses: ATE works, RPE has no pair 1 s apart.
  const EvaluationReport r = EvaluateFiles(dir + "/gt.txt", dir + "/gt.txt", {});
  CHECK(r.ate.success);
  CHECK_FALSE(r.rpe.success);
  CHECK_THAT(r.Table(), Catch::Contains("n/a"));
  CHECK_THAT(r.Json(), Catch::Contains("\"rpe\": {\"success\": false"));
  // What could not be computed is null, never a perfect 0; what was computed is a number.
  CHECK_THAT(r.Json(), Catch::Contains("\"trans_m\": {\"rmse\": null, \"mean\": null, "
                                       "\"median\": null, \"max\": null}"));
  CHECK_THAT(r.Json(), Catch::Contains("\"rot_deg\": {\"rmse\": null"));
  CHECK_THAT(r.Json(), Catch::Contains("\"error_m\": {\"rmse\": 0"));
}
