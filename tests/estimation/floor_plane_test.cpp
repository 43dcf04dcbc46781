#include "rgbdvo/estimation/floor_plane.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "rgbdvo/sensor/kinect_depth.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// The synthetic room's depth (floor at y = 1.5 m, world y down) from a camera 1 m above the
// floor, looking down by pitch_deg and rolled by roll_deg, quantised as a Kinect's raw depth.
cv::Mat RoomDepth(const PinholeCamera& cam, double pitch_deg, double roll_deg) {
  Rigid3d world_from_cam = Rigid3d::Identity();
  world_from_cam.linear() = (Eigen::AngleAxisd(-pitch_deg * M_PI / 180, Eigen::Vector3d::UnitX()) *
                             Eigen::AngleAxisd(roll_deg * M_PI / 180, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  world_from_cam.translation() = Eigen::Vector3d(-1.0, 0.5, -0.5);
  return DepthFromKinectRaw(KinectRawFromDepth(SyntheticScene().RenderDepth(cam, world_from_cam)));
}

}  // namespace

TEST_CASE("FitFloor finds the camera's height, pitch and roll over the synthetic room's floor") {
  // Measured: heights 0.999-1.000 m, normals 0.004-0.035 degrees off (raw Kinect depth steps of
  // 1-3 cm over the floor seen 1.2-4 m away). With one unweighted fit through RANSAC's
  // inliers: 1.004-1.008 m and 0.17-0.26 degrees.
  const PinholeCamera cam;
  for (const auto& [pitch, roll] : {std::pair{20.0, 0.0}, {30.0, 5.0}, {10.0, -8.0}}) {
    Rng rng(5);
    const FloorFit fit = FitFloor({}, CalibFor(cam), RoomDepth(cam, pitch, roll), rng);
    INFO(fit.Brief());
    REQUIRE(fit.success);
    CHECK(fit.height_m == Approx(1.0).margin(0.002));
    CHECK(fit.pitch_deg == Approx(pitch).margin(0.5));  // the angles differ with roll
    // The floor's normal in the camera frame is the world's down seen from the camera.
    const Eigen::Vector3d truth =
        (Eigen::AngleAxisd(-pitch * M_PI / 180, Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(roll * M_PI / 180, Eigen::Vector3d::UnitZ()))
            .toRotationMatrix()
            .transpose() *
        Eigen::Vector3d::UnitY();
    CHECK(std::acos(std::min(1.0, truth.dot(fit.normal_in_cam))) * 180 / M_PI < 0.1);
    CHECK((fit.level_from_cam * fit.normal_in_cam - Eigen::Vector3d::UnitY()).norm() < 1e-9);
  }
}

TEST_CASE("FitFloor says why when there is no floor") {
  const PinholeCamera cam;
  Rng rng(6);
  SECTION("no depth") {
    const FloorFit fit = FitFloor({}, CalibFor(cam), cv::Mat::zeros(480, 640, CV_32FC1), rng);
    CHECK_FALSE(fit.success);
    CHECK(fit.reason == "no depth readings");
  }
  SECTION("looking up at the ceiling") {
    const FloorFit fit = FitFloor({}, CalibFor(cam), RoomDepth(cam, -60, 0), rng);
    INFO(fit.Brief());
    CHECK_FALSE(fit.success);
    CHECK_THAT(fit.reason, Catch::Contains("no plane within 45 degrees of level"));
  }
  SECTION("options are checked") {
    FloorFitOptions o;
    o.max_tilt_deg = 90;
    CHECK_THROWS_WITH(FitFloor(o, CalibFor(cam), cv::Mat::zeros(4, 4, CV_32FC1), rng),
                      Catch::Contains("max_tilt_deg"));
  }
}
