// Depth-only alignment (the fallback for frames features cannot carry) and its check.
#include "rgbdvo/estimation/depth_alignment.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

Rigid3d Motion(double yaw_deg, double pitch_deg, const Eigen::Vector3d& t) {
  Rigid3d T = Rigid3d::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(pitch_deg * M_PI / 180, Eigen::Vector3d::UnitX()))
                   .matrix();
  T.translation() = t;
  return T;
}

}  // namespace

TEST_CASE("DepthAgreement is one for the true motion and low for a wrong one") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const Rigid3d prev_from_cur = Motion(6, 2, {0.05, 0.01, 0.03});
  const cv::Mat prev = scene.RenderDepth(cam, Rigid3d::Identity());
  const cv::Mat cur = scene.RenderDepth(cam, prev_from_cur);
  const DepthAlignOptions o;
  CHECK(DepthAgreement(o, CalibFor(cam), prev, cur, prev_from_cur) > 0.95);
  CHECK(DepthAgreement(o, CalibFor(cam), prev, cur, Rigid3d::Identity()) < 0.5);
  CHECK(DepthAgreement(o, CalibFor(cam), prev, cur, Motion(-6, 2, {0.05, 0.01, 0.03})) < 0.5);
  // Nothing lands on a reading: 0, not a division by zero.
  CHECK(DepthAgreement(o, CalibFor(cam), cv::Mat::zeros(prev.size(), CV_32FC1), cur,
                       prev_from_cur) == 0);
}

TEST_CASE("AlignDepth finds a fast turn from a prediction pointing the other way") {
  // The turn of a shaking hand: the constant-velocity prediction says 8 degrees to the left, the
  // camera went 8 degrees to the right. ICP from the prediction alone would stay near it; one of
  // the other starts (no motion, and ICP from there) lands on the truth and explains the depth.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const Rigid3d truth = Motion(8, 1, {0.04, 0.0, 0.02});
  const cv::Mat prev = scene.RenderDepth(cam, Rigid3d::Identity());
  const cv::Mat cur = scene.RenderDepth(cam, truth);
  const DepthAligner aligner(DepthAlignOptions{}, CalibFor(cam));
  const DepthAlignResult r = aligner.Align(prev, cur, Motion(-8, -1, {-0.04, 0, 0}));
  INFO(r.reason << " agreement " << r.agreement);
  REQUIRE(r.success);
  CHECK(r.agreement > 0.9);
  CHECK(RigidNear(r.prev_from_cur, truth, 0.5, 0.01));
}

TEST_CASE("AlignDepth refuses what the depth images do not support") {
  const SyntheticScene scene;
  const PinholeCamera cam;
  const cv::Mat prev = scene.RenderDepth(cam, Rigid3d::Identity());
  // The camera turned round: nothing of the previous view is in the current one.
  const cv::Mat behind = scene.RenderDepth(cam, Motion(180, 0, {0, 0, 0}));
  const DepthAligner aligner(DepthAlignOptions{}, CalibFor(cam));
  const DepthAlignResult r = aligner.Align(prev, behind, Rigid3d::Identity());
  INFO(r.reason << " agreement " << r.agreement);
  CHECK_FALSE(r.success);
  // Inputs of the wrong type are an error, not a guess.
  CHECK_THROWS_AS(aligner.Align(prev, cv::Mat(), Rigid3d::Identity()), std::invalid_argument);
  DepthAlignOptions bad;
  bad.min_agreement = 1.5;
  CHECK_THROWS_WITH(DepthAligner(bad, CalibFor(cam)), Catch::Contains("min_agreement"));
}
