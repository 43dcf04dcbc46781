#include "rgbdvo/odometry/planarity_check.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

using namespace rgbdvo;

namespace {

// 30 Hz frames of a robot turning 0.02 rad and driving 2 cm a frame, its 6-DOF poses chained
// from steps that also pitch by the step's tilt_deg (about the camera's x) and rise by its
// climb_m: the 6-DOF chain tilts as a drifting or climbing estimate would.
class Chain {
 public:
  FrameResult Next(double tilt_deg, double climb_m) {
    Rigid3d step = Rigid3d::Identity();
    step.linear() = Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY()).matrix();
    step.translation() = Eigen::Vector3d(0, 0, 0.02);
    Rigid3d off = Rigid3d::Identity();
    off.linear() = Eigen::AngleAxisd(tilt_deg * M_PI / 180, Eigen::Vector3d::UnitX()).matrix();
    off.translation() = Eigen::Vector3d(0, -climb_m, 0);
    FrameResult r;
    r.frame = frame_;
    r.timestamp = 10 + frame_ / 30.0;
    r.status = FrameStatus::kAccepted;
    if (frame_++ > 0) {
      planar_ = planar_ * step;
      six_ = six_ * step * off;
    }
    r.world_from_cam = planar_;
    r.world_from_cam_6dof = six_;
    return r;
  }

 private:
  int frame_ = 0;
  Rigid3d planar_ = Rigid3d::Identity(), six_ = Rigid3d::Identity();
};

}  // namespace

TEST_CASE("A planar chain within its noise raises no warning, whatever its slow drift") {
  PlanarityCheck check(PlanarityCheckOptions{}, Eigen::Vector3d::UnitY());
  // The 6-DOF chain drifts 0.5 degree and 1 cm per second: 15 degrees and 0.3 m over the run.
  Chain chain;
  for (int i = 0; i < 900; ++i) CHECK_FALSE(check.Add(chain.Next(0.5 / 30, 0.01 / 30)));
  CHECK(check.episodes() == 0);
  CHECK(check.off_plane_frames() == 0);
}

TEST_CASE("A tilt beyond the bound within a second is announced when it starts and ends") {
  PlanarityCheck check(PlanarityCheckOptions{}, Eigen::Vector3d::UnitY());
  Chain chain;
  for (int i = 0; i < 30; ++i) REQUIRE_FALSE(check.Add(chain.Next(0, 0)));
  // Onto a ramp: 8 degrees of pitch within 10 frames, 2 s on it, then off it within 10. Each
  // change of slope is an episode; on the ramp itself the motion is planar again.
  std::vector<std::string> warnings;
  for (int i = 30; i < 200; ++i) {
    const double tilt = i < 40 ? 0.8 : (i >= 100 && i < 110) ? -0.8 : 0;
    if (auto w = check.Add(chain.Next(tilt, 0))) warnings.push_back(*w);
  }
  for (const std::string& w : warnings) UNSCOPED_INFO(w);
  REQUIRE(warnings.size() == 4);
  CHECK_THAT(warnings[0], Catch::Contains("motion not planar at t=11.200 (frame 36)") &&
                              Catch::Contains("tilts 5.6 deg"));
  CHECK_THAT(warnings[1], Catch::Contains("motion planar again at t=12.200 (frame 66)") &&
                              Catch::Contains("tilted up to 8.0 deg"));
  CHECK_THAT(warnings[2], Catch::Contains("(frame 106)"));
  CHECK_THAT(warnings[3], Catch::Contains("(frame 136)"));
  CHECK(check.episodes() == 2);
  CHECK(check.off_plane_frames() == 60);  // frames 36-65 and 106-135
}

TEST_CASE("A climb beyond the bound is announced, frames without a 6-DOF pose are skipped") {
  PlanarityCheck check(PlanarityCheckOptions{}, Eigen::Vector3d::UnitY());
  std::optional<std::string> first;
  Chain chain;
  for (int i = 0; i < 60; ++i) {
    FrameResult r = chain.Next(0, i < 20 ? 0 : 0.012);  // a kerb: 1.2 cm a frame
    if (i % 3 == 0) r.world_from_cam_6dof.reset();      // predicted frames (24 is one: 6 cm)
    if (auto w = check.Add(r); w && !first) first = w;
  }
  REQUIRE(first);
  CHECK_THAT(*first, Catch::Contains("(frame 25)") && Catch::Contains("climbs 0.072 m"));
  CHECK_THROWS_WITH(PlanarityCheck(PlanarityCheckOptions{0, 5, 0.05}, Eigen::Vector3d::UnitY()),
                    Catch::Contains("window_s"));
}
