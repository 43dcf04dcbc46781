#include "rgbdvo/estimation/ransac.hpp"

#include <catch2/catch.hpp>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

TEST_CASE("RANSAC recovers a known motion with 50% outliers and 3 mm noise") {
  std::mt19937 rng(10);
  Rng ransac_rng(11);
  RansacOptions options;  // paper defaults: 200 trials, 4 points, 1.5 cm
  for (int i = 0; i < 20; ++i) {
    const Rigid3d truth = RandomRigid(rng, 0.2, 0.1);
    const auto pairs = SynthesizePairs(rng, truth, 300, 0.003, 0.5);
    const RansacResult r = EstimateRigidRansac(options, pairs, ransac_rng);
    REQUIRE(r.success);
    INFO(r.Brief());
    CHECK(RotationErrorDeg(r.prev_from_cur, truth) < 0.2);
    CHECK(TranslationError(r.prev_from_cur, truth) < 0.002);
    // Almost every true inlier is found, and no outlier (outliers lie far away).
    CHECK(r.inliers.size() >= 135);
    CHECK(r.inliers.front() >= 150);
  }
}

TEST_CASE("RANSAC reports failure without enough pairs") {
  std::mt19937 rng(12);
  Rng ransac_rng(13);
  const auto pairs = SynthesizePairs(rng, Rigid3d::Identity(), 3, 0, 0);
  const RansacResult r = EstimateRigidRansac(RansacOptions{}, pairs, ransac_rng);
  CHECK_FALSE(r.success);
  CHECK(r.reason == "pairs<4");
}

TEST_CASE("RANSAC is deterministic for a fixed seed") {
  std::mt19937 rng(14);
  const auto pairs = SynthesizePairs(rng, RandomRigid(rng, 0.1, 0.1), 100, 0.003, 0.6);
  Rng a(99), b(99);
  const RansacResult ra = EstimateRigidRansac(RansacOptions{}, pairs, a);
  const RansacResult rb = EstimateRigidRansac(RansacOptions{}, pairs, b);
  CHECK(ra.inliers == rb.inliers);
  CHECK(ra.prev_from_cur.matrix() == rb.prev_from_cur.matrix());
}

TEST_CASE("RansacOptions::Check rejects bad values") {
  RansacOptions o;
  o.inlier_distance_m = 0;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("inlier_distance_m"));
  o = {};
  o.sample_size = 2;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("sample_size"));
}

TEST_CASE("Adaptive RANSAC stops early on clean data and keeps the paper's 200 trials at 0") {
  std::mt19937 rng(15);
  const Rigid3d truth = RandomRigid(rng, 0.1, 0.1);
  const auto pairs = SynthesizePairs(rng, truth, 200, 0.002, 0.1);
  Rng a(1), b(1);
  RansacOptions adaptive;  // confidence 0.999: with 90% inliers about 7 trials
  const RansacResult fast = EstimateRigidRansac(adaptive, pairs, a);
  REQUIRE(fast.success);
  CHECK(fast.trials < 20);
  CHECK(RigidNear(fast.prev_from_cur, truth, 0.2, 0.002));
  RansacOptions paper;
  paper.confidence = 0;
  const RansacResult full = EstimateRigidRansac(paper, pairs, b);
  CHECK(full.trials == 200);
  // 60% outliers: more trials are needed (w^4 = 0.0256 -> ~267, capped at 200).
  const auto hard = SynthesizePairs(rng, truth, 200, 0.002, 0.6);
  Rng c(2);
  CHECK(EstimateRigidRansac(adaptive, hard, c).trials > 100);
}
