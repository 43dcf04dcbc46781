// Depth-only alignment (the fallback for frames features cannot carry) and its check.
#include "rgbdvo/estimation/depth_alignment.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

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

namespace {

// Z-depth of a camera 0.6 m above a floor, facing a wall 3 m ahead, moved by cam_in_world,
// with the Kinect's depth noise (sigma = 1.425e-3 z^2).
cv::Mat FloorAndWall(const PinholeCamera& cam, const Eigen::Vector3d& cam_in_world, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 1.425e-3);
  cv::Mat depth(cam.height, cam.width, CV_32FC1, cv::Scalar(0));
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const Eigen::Vector3d ray((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
      double z = (3.0 - cam_in_world.z()) / ray.z();                         // the wall
      if (ray.y() > 0) z = std::min(z, (0.6 - cam_in_world.y()) / ray.y());  // the floor
      depth.at<float>(v, u) = static_cast<float>(z + noise(rng) * z * z);
    }
  return depth;
}

}  // namespace

TEST_CASE("MeasureTranslationConstraint finds the direction no surface faces") {
  cv::Mat normals(8, 8, CV_32FC3, cv::Scalar(0, -1, 0));  // a floor
  normals.rowRange(0, 4).setTo(cv::Scalar(0, 0, -1));     // and a wall ahead
  normals.at<cv::Vec3f>(0, 0) = cv::Vec3f(NAN, NAN, NAN);
  TranslationConstraint c = MeasureTranslationConstraint(normals, 0.03);
  REQUIRE(c.free_directions.size() == 1);
  CHECK(std::abs(c.free_directions[0].x()) == Approx(1.0));
  CHECK(c.weakest == Approx(0).margin(1e-9));
  normals.col(0).setTo(cv::Scalar(1, 0, 0));  // a side wall over 1/8 of the image
  c = MeasureTranslationConstraint(normals, 0.03);
  CHECK(c.free_directions.empty());
  CHECK(c.weakest > 0.1);
  CHECK(MeasureTranslationConstraint(cv::Mat(4, 4, CV_32FC3, cv::Scalar(NAN, NAN, NAN)), 0.03)
            .free_directions.size() == 3);
}

TEST_CASE("On a floor and one wall the depth alignment takes the prediction along the wall") {
  // Moving along the wall changes neither depth image: ICP cannot see it, and left alone it
  // slides by whatever its start and noise give. The prediction's component is used there.
  const PinholeCamera cam;
  const DepthAligner aligner(DepthAlignOptions{}, CalibFor(cam));
  const Eigen::Vector3d truth(0.04, 0, 0.03);
  const cv::Mat prev = FloorAndWall(cam, Eigen::Vector3d::Zero(), 1);
  const cv::Mat cur = FloorAndWall(cam, truth, 2);
  for (const double guess_x : {0.04, 0.0, 0.3}) {
    Rigid3d guess = Rigid3d::Identity();
    guess.translation() = Eigen::Vector3d(guess_x, 0, 0);
    const DepthAlignResult r = aligner.Align(prev, cur, guess);
    INFO("guess x " << guess_x << ": " << r.reason << " t "
                    << r.prev_from_cur.translation().transpose());
    REQUIRE(r.success);
    REQUIRE(r.constraint.free_directions.size() == 1);
    CHECK(std::abs(r.constraint.free_directions[0].x()) > 0.99);
    CHECK(r.prev_from_cur.translation().x() == Approx(guess_x).margin(0.003));
    CHECK(r.prev_from_cur.translation().z() == Approx(truth.z()).margin(0.005));
    CHECK(RotationAngleRad(r.prev_from_cur.linear()) < 0.005);
  }
}
