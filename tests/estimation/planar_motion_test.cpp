#include "rgbdvo/estimation/planar_motion.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "rgbdvo/estimation/rigid_align.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// A camera pitched 15 degrees down and rolled 4 degrees against the floor.
Eigen::Matrix3d Tilted() {
  return (Eigen::AngleAxisd(0.07, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(-0.26, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

TEST_CASE("PlanarMotion keeps the camera's height and turns about the floor's normal") {
  const Eigen::Matrix3d L = Tilted();
  const Rigid3d m = PlanarMotion(L, 0.4, 0.3, -0.2);
  // The camera centre moves within the level frame's x-z plane; the normal (level y) is kept.
  CHECK(std::abs((L * m.translation()).y()) < 1e-12);
  const Eigen::Vector3d normal_in_cam = L.transpose() * Eigen::Vector3d::UnitY();
  CHECK((m.linear() * normal_in_cam - normal_in_cam).norm() < 1e-12);
  CHECK(RotationAngleRad(m.linear()) == Approx(0.4));
}

TEST_CASE("AlignPlanar recovers a planar motion exactly from two pairs") {
  const Eigen::Matrix3d L = Tilted();
  const Rigid3d truth = PlanarMotion(L, -0.3, 0.25, 0.6);
  std::vector<PointPair> pairs;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.4, -0.2, 2.0), Eigen::Vector3d(-1, 0.5, 3)})
    pairs.push_back({truth * p, p});
  const std::optional<Rigid3d> got = AlignPlanar(L, pairs);
  REQUIRE(got);
  CHECK(RigidNear(*got, truth, 1e-9, 1e-12));
  // Fewer than two pairs, or two at the same x-z position: no motion.
  CHECK_FALSE(AlignPlanar(L, {pairs[0]}));
  const Eigen::Vector3d above = L.transpose() * (L * pairs[0].p_cur + Eigen::Vector3d(0, 0.3, 0));
  CHECK_FALSE(AlignPlanar(L, {pairs[0], {truth * above, above}}));
}

TEST_CASE("Planar RANSAC recovers a planar motion with 50% outliers and 3 mm noise") {
  std::mt19937 rng(21);
  Rng ransac_rng(22);
  std::uniform_real_distribution<double> yaw(-0.2, 0.2), step(-0.1, 0.1);
  const Eigen::Matrix3d L = Tilted();
  for (int i = 0; i < 20; ++i) {
    const double z = step(rng);  // one draw per statement, last first: the same on every compiler
    const double x = step(rng);
    const double y = yaw(rng);
    const Rigid3d truth = PlanarMotion(L, y, x, z);
    const auto pairs = SynthesizePairs(rng, truth, 300, 0.003, 0.5);
    const RansacResult r = EstimatePlanarRansac(RansacOptions{}, L, pairs, ransac_rng);
    INFO(r.Brief());
    REQUIRE(r.success);
    CHECK(RotationErrorDeg(r.prev_from_cur, truth) < 0.1);
    CHECK(TranslationError(r.prev_from_cur, truth) < 0.002);  // as the 6-DOF RANSAC's test
    CHECK(r.inliers.size() >= 135);
    CHECK(r.inliers.front() >= 150);  // SynthesizePairs puts the outliers first
  }
}

TEST_CASE("On planar motion the 3-DOF estimate is more accurate than the 6-DOF one") {
  // 20 pairs with 1 cm noise (Kinect depth noise at 2.5 m): over 200 motions, the RMS error of
  // the 3-DOF least-squares estimate against the 6-DOF one (AlignRigid). Measured: rotation
  // 0.089 against 0.172 degrees, translation 4.8 against 7.4 mm (sums of squares compared).
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> yaw(-0.2, 0.2), step(-0.1, 0.1);
  const Eigen::Matrix3d L = Tilted();
  double rot3 = 0, rot6 = 0, tr3 = 0, tr6 = 0;
  for (int i = 0; i < 200; ++i) {
    const double z = step(rng);  // one draw per statement, last first: the same on every compiler
    const double x = step(rng);
    const double y = yaw(rng);
    const Rigid3d truth = PlanarMotion(L, y, x, z);
    const auto pairs = SynthesizePairs(rng, truth, 20, 0.01, 0.0);
    const std::optional<Rigid3d> planar = AlignPlanar(L, pairs), rigid = AlignRigid(pairs);
    REQUIRE(planar);
    REQUIRE(rigid);
    rot3 += std::pow(RotationErrorDeg(*planar, truth), 2);
    rot6 += std::pow(RotationErrorDeg(*rigid, truth), 2);
    tr3 += std::pow(TranslationError(*planar, truth), 2);
    tr6 += std::pow(TranslationError(*rigid, truth), 2);
  }
  INFO("RMS rotation error 3-DOF "
       << std::sqrt(rot3 / 200) << " deg, 6-DOF " << std::sqrt(rot6 / 200) << "; translation "
       << std::sqrt(tr3 / 200) << " / " << std::sqrt(tr6 / 200) << " m");
  CHECK(rot3 < 0.5 * rot6);
  CHECK(tr3 < 0.7 * tr6);
}

TEST_CASE("ProjectPlanar keeps a planar motion and drops the tilt and climb of another") {
  const Eigen::Matrix3d L = Tilted();
  const Rigid3d planar = PlanarMotion(L, 0.3, -0.2, 0.5);
  CHECK(RigidNear(ProjectPlanar(L, planar), planar, 1e-9, 1e-12));
  // The same motion with a 2 degree tilt about the level x axis and a 3 cm climb: projected
  // back onto it (the yaw's projection is exact for a tilt about a horizontal axis only to
  // second order: within 0.05 degrees and 1 mm).
  Rigid3d tilt = Rigid3d::Identity();
  tilt.linear() = L.transpose() * Eigen::AngleAxisd(0.035, Eigen::Vector3d::UnitX()) * L;
  tilt.translation() = L.transpose() * Eigen::Vector3d(0, 0.03, 0);
  CHECK(RigidNear(ProjectPlanar(L, tilt * planar), planar, 0.05, 0.001));
}

TEST_CASE("FloorNormalFromMount gives the normal whose angles FloorFit reports") {
  for (const auto& [pitch, roll] : {std::pair{12.0, 1.0}, {-5.0, 20.0}, {0.0, 0.0}}) {
    const Eigen::Vector3d n = FloorNormalFromMount(pitch, roll);
    CHECK(n.norm() == Approx(1.0));
    CHECK(std::atan2(n.z(), n.y()) * 180 / M_PI == Approx(pitch).margin(1e-9));
    CHECK(std::asin(n.x()) * 180 / M_PI == Approx(roll).margin(1e-9));
    CHECK((LevelFromFloorNormal(n) * n - Eigen::Vector3d::UnitY()).norm() < 1e-12);
    CHECK((MountFromFloorNormal(n) - Eigen::Vector2d(pitch, roll)).norm() < 1e-9);
  }
}
