// ATE and RPE on hand-computable trajectories.
#include "rgbdvo/evaluation/evaluation.hpp"

#include <catch2/catch.hpp>
#include <cmath>

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
  out.reserve(n);
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
  half.delta = 0.5;
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

namespace {

// The ground truth seen through a similarity: est = est_from_gt * (c * p_gt), rotations turned
// by est_from_gt. The least-squares similarity back is exact: scale 1 / c.
std::vector<StampedPose> Similar(const std::vector<StampedPose>& gt, const Rigid3d& est_from_gt,
                                 double c) {
  std::vector<StampedPose> est = gt;
  for (StampedPose& p : est) {
    p.world_from_cam.translation() *= c;
    p.world_from_cam = est_from_gt * p.world_from_cam;
  }
  return est;
}

// Root mean square distance of the positions from their centroid.
double RmsSpread(const std::vector<StampedPose>& poses) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const StampedPose& p : poses) mean += p.world_from_cam.translation();
  mean /= poses.size();
  double sum_sq = 0;
  for (const StampedPose& p : poses)
    sum_sq += (p.world_from_cam.translation() - mean).squaredNorm();
  return std::sqrt(sum_sq / poses.size());
}

EvaluationOptions Aligned(Alignment align) {
  EvaluationOptions o;
  o.align = align;
  return o;
}

}  // namespace

TEST_CASE("se3 leaves a scale error, sim3 recovers the scale exactly") {
  const std::vector<StampedPose> gt = CurvyPath();
  std::mt19937 rng(7);
  const double c = 0.8;
  const std::vector<StampedPose> est = Similar(gt, RandomRigid(rng, 1.5, 2.0), c);

  // The rigid fit still finds the rotation (the cross-covariance is c times the exact one) and
  // puts the centroids together: every pose is off by (1 - c) times its distance from the
  // centroid.
  const AteResult se3 = ComputeAte(gt, est, Aligned(Alignment::kSe3));
  REQUIRE(se3.success);
  CHECK(se3.scale == 1);
  CHECK(se3.error_m.rmse == Approx((1 - c) * RmsSpread(gt)).epsilon(1e-9));

  const AteResult sim3 = ComputeAte(gt, est, Aligned(Alignment::kSim3));
  REQUIRE(sim3.success);
  CHECK(sim3.scale == Approx(1 / c).epsilon(1e-12));
  CHECK(sim3.error_m.max < 1e-9);
  CHECK(sim3.aligned_on == 50);
  // Aligned() maps every estimate pose, rotation included, onto its ground truth pose.
  for (size_t k = 0; k < gt.size(); k += 7)
    CHECK(RigidNear(sim3.Aligned(est[k].world_from_cam), gt[k].world_from_cam, 1e-6, 1e-9));
}

TEST_CASE("scale alone corrects the scale about the origin and nothing else") {
  const std::vector<StampedPose> gt = CurvyPath();
  // est = 0.8 * gt about the origin, same orientations: the scale fixes it all.
  const std::vector<StampedPose> est = Similar(gt, Rigid3d::Identity(), 0.8);
  const AteResult scale = ComputeAte(gt, est, Aligned(Alignment::kScale));
  REQUIRE(scale.success);
  CHECK(scale.scale == Approx(1.25).epsilon(1e-12));
  CHECK(scale.error_m.max < 1e-9);
  CHECK(RigidNear(scale.gt_from_est, Rigid3d::Identity(), 1e-12, 1e-12));

  // Moved as well: the scale is still Umeyama's (1.25), but no rotation or translation is
  // applied, so the error is the raw distance of 1.25 * p_est from p_gt.
  std::mt19937 rng(8);
  const Rigid3d moved = RandomRigid(rng, 0.5, 1.0);
  const std::vector<StampedPose> est_moved = Similar(gt, moved, 0.8);
  const AteResult r = ComputeAte(gt, est_moved, Aligned(Alignment::kScale));
  REQUIRE(r.success);
  CHECK(r.scale == Approx(1.25).epsilon(1e-12));
  const double first =
      (1.25 * est_moved[0].world_from_cam.translation() - gt[0].world_from_cam.translation())
          .norm();
  CHECK(r.pose_errors_m[0] == Approx(first).epsilon(1e-12));
  CHECK(r.error_m.rmse > 0.1);
}

TEST_CASE("origin puts the first estimate pose exactly onto the first ground truth pose") {
  const std::vector<StampedPose> gt = CurvyPath();
  std::mt19937 rng(9);
  const Rigid3d est_from_gt = RandomRigid(rng, 2.0, 3.0);
  std::vector<StampedPose> est = gt;
  for (StampedPose& p : est) p.world_from_cam = est_from_gt * p.world_from_cam;
  // A rigidly moved estimate is mapped back whole.
  AteResult r = ComputeAte(gt, est, Aligned(Alignment::kOrigin));
  REQUIRE(r.success);
  CHECK(r.aligned_on == 1);
  CHECK(r.error_m.max < 1e-9);

  // An estimate that drifts: the first pose still lands exactly, its rotation too, and the
  // error grows from 0 with the drift (0.01 m per pose along the ground truth's z).
  for (size_t k = 0; k < est.size(); ++k)
    est[k].world_from_cam =
        est_from_gt * Eigen::Translation3d(0, 0, 0.01 * k) * gt[k].world_from_cam;
  r = ComputeAte(gt, est, Aligned(Alignment::kOrigin));
  REQUIRE(r.success);
  CHECK(RigidNear(r.Aligned(est[0].world_from_cam), gt[0].world_from_cam, 1e-6, 1e-12));
  CHECK(r.pose_errors_m[0] < 1e-12);
  CHECK(r.pose_errors_m[49] == Approx(0.49).epsilon(1e-9));
  CHECK(r.error_m.max == Approx(0.49).epsilon(1e-9));
}

TEST_CASE("none compares the raw positions") {
  const std::vector<StampedPose> gt = CurvyPath();
  std::vector<StampedPose> est = gt;
  for (StampedPose& p : est) p.world_from_cam.translation() += Eigen::Vector3d(0.3, 0, 0.4);
  const AteResult none = ComputeAte(gt, est, Aligned(Alignment::kNone));
  REQUIRE(none.success);
  CHECK(none.aligned_on == 0);
  CHECK(none.error_m.rmse == Approx(0.5).epsilon(1e-12));
  CHECK(none.error_m.max == Approx(0.5).epsilon(1e-12));
  CHECK(ComputeAte(gt, est, Aligned(Alignment::kSe3)).error_m.max < 1e-9);
  // One matched pose is enough without a fit; a fit needs 3.
  const std::vector<StampedPose> one = {est[0]};
  CHECK(ComputeAte(gt, one, Aligned(Alignment::kNone)).success);
  CHECK(ComputeAte(gt, one, Aligned(Alignment::kOrigin)).success);
  const AteResult se3 = ComputeAte(gt, one, Aligned(Alignment::kSe3));
  CHECK_FALSE(se3.success);
  CHECK_THAT(se3.reason, Catch::Contains("need 3"));
}

TEST_CASE("align_first fits the alignment to the first N matched poses only") {
  // The estimate follows the ground truth (moved rigidly) for 20 poses, then jumps 0.5 m: fitted
  // to the first 20, those are exact and the other 30 are 0.5 m off.
  const std::vector<StampedPose> gt = CurvyPath();
  std::mt19937 rng(10);
  const Rigid3d est_from_gt = RandomRigid(rng, 1.0, 1.0);
  std::vector<StampedPose> est = gt;
  for (size_t k = 0; k < est.size(); ++k) {
    if (k >= 20) est[k].world_from_cam.translation() += Eigen::Vector3d(0, 0.5, 0);
    est[k].world_from_cam = est_from_gt * est[k].world_from_cam;
  }
  EvaluationOptions o;
  o.align_first = 20;
  const AteResult r = ComputeAte(gt, est, o);
  REQUIRE(r.success);
  CHECK(r.matched == 50);
  CHECK(r.aligned_on == 20);
  CHECK(r.pose_errors_m[19] < 1e-9);
  CHECK(r.error_m.max == Approx(0.5).epsilon(1e-9));
  CHECK(r.error_m.median == Approx(0.5).epsilon(1e-9));
  CHECK(r.error_m.mean == Approx(0.3).epsilon(1e-9));
  // Fitted to all poses, the jump is spread: a lower maximum.
  CHECK(ComputeAte(gt, est, {}).error_m.max < 0.45);

  o.align_first = 2;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("align_first"));
}

TEST_CASE("t_offset recovers an estimate stamped by a clock 0.3 s behind") {
  const std::vector<StampedPose> gt = CurvyPath();
  std::vector<StampedPose> est = gt;
  for (StampedPose& p : est) p.timestamp -= 0.3;
  // Unshifted, pose k is matched with ground truth pose k - 3: a real error.
  const AteResult wrong = ComputeAte(gt, est, {});
  REQUIRE(wrong.success);
  CHECK(wrong.matched == 47);
  CHECK(wrong.error_m.rmse > 0.05);
  EvaluationOptions o;
  o.t_offset_s = 0.3;
  const AteResult ate = ComputeAte(gt, est, o);
  REQUIRE(ate.success);
  CHECK(ate.matched == 50);
  CHECK(ate.error_m.max < 1e-9);
  CHECK(ate.pose_times_s.front() == Approx(100.0).margin(1e-9));
  const RpeResult rpe = ComputeRpe(gt, est, o);
  REQUIRE(rpe.success);
  CHECK(rpe.trans_m.max < 1e-9);
}

TEST_CASE("RPE in frames and in metres on a constant-velocity line is exact") {
  // Ground truth at 1 m/s along x (0.1 m per pose), the estimate at 1.2 m/s: 5 poses apart,
  // the estimate went 0.6 m where the truth went 0.5 m.
  const auto gt = Sampled(51, 0.0, [](double t) { return Pose(0, {t, 0, 0}); });
  const auto est = Sampled(51, 0.0, [](double t) { return Pose(0, {1.2 * t, 0, 0}); });
  EvaluationOptions frames;
  frames.delta = 5;
  frames.delta_unit = DeltaUnit::kFrames;
  RpeResult rpe = ComputeRpe(gt, est, frames);
  REQUIRE(rpe.success);
  CHECK(rpe.pairs == 46);  // (0, 5) .. (45, 50)
  CHECK(rpe.trans_m.rmse == Approx(0.1).epsilon(1e-9));
  CHECK(rpe.trans_m.max == Approx(0.1).epsilon(1e-9));

  EvaluationOptions metres;
  metres.delta = 0.5;
  metres.delta_unit = DeltaUnit::kMetres;
  rpe = ComputeRpe(gt, est, metres);
  REQUIRE(rpe.success);
  CHECK(rpe.pairs == 46);  // from pose 46 on, less than 0.45 m of path is left
  CHECK(rpe.trans_m.rmse == Approx(0.1).epsilon(1e-9));

  // Twice the speed after pose 25 on the ground truth (x = 2.5, 2.7, 2.9, ...): a pair is only
  // kept within 10% of 0.5 m, and from a fast pose 0.5 m ahead is 0.4 or 0.6 m away.
  // Kept: k = 0..20 (5 poses ahead), 22 (2.2 -> 2.7) and 24 (2.4 -> 2.9).
  auto fast = gt;
  for (size_t k = 26; k < fast.size(); ++k)
    fast[k].world_from_cam.translation().x() = 2.5 + 0.2 * (k - 25.0);
  rpe = ComputeRpe(fast, fast, metres);
  REQUIRE(rpe.success);
  CHECK(rpe.pairs == 23);

  frames.delta = 2.5;
  CHECK_THROWS_WITH(frames.Check(), Catch::Contains("whole number"));
  frames.delta = 60;
  rpe = ComputeRpe(gt, est, frames);
  CHECK_FALSE(rpe.success);
  CHECK_THAT(rpe.reason, Catch::Contains("60 frames apart among 51 poses matched"));
}

TEST_CASE("The sim3 scale applies to the RPE as well") {
  const std::vector<StampedPose> gt = CurvyPath();
  const std::vector<StampedPose> est = Similar(gt, Rigid3d::Identity(), 0.8);
  EvaluationOptions o;
  o.delta = 0.5;
  CHECK(ComputeRpe(gt, est, o).trans_m.rmse > 0.01);
  o.align = Alignment::kSim3;
  const AteResult ate = ComputeAte(gt, est, o);
  const RpeResult rpe = ComputeRpe(gt, est, o, ate.scale);
  REQUIRE(rpe.success);
  CHECK(rpe.trans_m.max < 1e-9);
  CHECK(rpe.rot_deg.max < 1e-4);
}

TEST_CASE("Repeated timestamps count and match as in the file read back") {
  // A run's poses stamped by depth time: two poses share a time. Read from a file only the last
  // is kept; computed from memory it must be the same, not a second match of another ground
  // truth pose 0.01 s away.
  const auto gt = Sampled(30, 0.0, [](double t) { return Pose(0, {t, 0, 0}); });
  std::vector<StampedPose> gt100;  // 100 Hz ground truth
  gt100.reserve(300);
  for (int k = 0; k < 300; ++k) gt100.push_back({0.01 * k, Pose(0, {0.01 * k, 0, 0})});
  std::vector<StampedPose> est = gt;
  est.insert(est.begin() + 5, {est[5].timestamp, Pose(0, {9, 9, 9})});  // dropped: not the last
  const AteResult ate = ComputeAte(gt100, est, {});
  REQUIRE(ate.success);
  CHECK(ate.matched == 30);
  CHECK(ate.error_m.max < 1e-9);
  std::vector<StampedPose> copy = est;
  CHECK(KeepLastOfEachTime(&copy) == 1);
  CHECK(copy.size() == 30);
}
