#include "rgbdvo/pipeline/trajectory_writer.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

// A frame at colour time t_color paired with depth time t_depth, at x = x_m, moving 1 m/s
// along its x.
FrameResult At(int frame, double t_color, double t_depth, double x_m) {
  FrameResult r;
  r.frame = frame;
  r.timestamp = t_color;
  r.depth_timestamp = t_depth;
  r.world_from_cam.translation() = Eigen::Vector3d(x_m, 0, 0);
  r.velocity.translation_per_s = Eigen::Vector3d(1, 0, 0);
  r.status = FrameStatus::kAccepted;
  return r;
}

// Frames 1 and 2 share the depth image at 1.050 (nearest pairing); frame 0's depth image is
// 10 ms after its colour image, frame 3's 5 ms before.
std::vector<FrameResult> Frames() {
  return {At(0, 1.000, 1.010, 0.0), At(1, 1.033, 1.050, 0.033), At(2, 1.066, 1.050, 0.066),
          At(3, 1.100, 1.095, 0.100)};
}

std::vector<std::vector<double>> Rows(const std::string& path, char sep) {
  std::vector<std::vector<double>> rows;
  for (std::string line : Lines(path)) {
    if (line.empty() || line[0] == '#' || line[0] == 'f') continue;  // comment or CSV header
    for (char& c : line) c = c == sep ? ' ' : c;
    std::istringstream fields(line);
    std::vector<double> v;
    for (std::string f; fields >> f;) v.push_back(std::strtod(f.c_str(), nullptr));  // status: 0
    rows.push_back(v);
  }
  return rows;
}

}  // namespace

TEST_CASE("StampRow: color keeps the estimate, depth moves it by velocity * (t_depth - t_color)") {
  const FrameResult r = At(0, 1.000, 1.010, 0.5);
  const StampedPose color = StampRow(r, StampTime::kColor);
  CHECK(color.timestamp == 1.000);
  CHECK(color.world_from_cam.translation().x() == 0.5);
  const StampedPose depth = StampRow(r, StampTime::kDepth);
  CHECK(depth.timestamp == 1.010);
  CHECK(std::abs(depth.world_from_cam.translation().x() - 0.510) < 1e-12);  // 1 m/s * 10 ms
  CHECK(ParseStampTime(StampTimeName(StampTime::kDepth)) == StampTime::kDepth);
  CHECK_THROWS_WITH(ParseStampTime("rgb"), Catch::Contains("rgb"));
}

TEST_CASE("Stamped by depth, TUM and KITTI rows carry the depth stamps, a repeated one left out") {
  const std::string dir = MakeTempDir("stamp_depth");
  {
    TumTrajectoryWriter tum(dir + "/t.txt", StampTime::kDepth);
    KittiTrajectoryWriter kitti(dir + "/k.txt", StampTime::kDepth);
    CsvTrajectoryWriter csv(dir + "/c.csv", StampTime::kDepth);
    for (const FrameResult& r : Frames())
      for (TrajectoryWriter* w : std::vector<TrajectoryWriter*>{&tum, &kitti, &csv}) w->Write(r);
    CHECK(tum.rows_left_out() == 1);
    CHECK(kitti.rows_left_out() == 1);
    CHECK(csv.rows_left_out() == 0);
  }
  const auto tum = Rows(dir + "/t.txt", ' ');
  REQUIRE(tum.size() == 3);  // frame 2 shares 1.050 with frame 1: the first is kept
  const double stamps[] = {1.010, 1.050, 1.095}, xs[] = {0.010, 0.050, 0.095};
  for (int i = 0; i < 3; ++i) {
    CHECK(tum[i][0] == Approx(stamps[i]).margin(1e-9));
    CHECK(tum[i][1] == Approx(xs[i]).margin(1e-9));  // moved to the depth time at 1 m/s
  }
  const auto kitti = Rows(dir + "/k.txt", ' ');
  REQUIRE(kitti.size() == 3);
  for (int i = 0; i < 3; ++i) CHECK(kitti[i][3] == Approx(xs[i]).margin(1e-9));
  CHECK_THAT(Slurp(dir + "/c.csv"),
             Catch::StartsWith("frame,timestamp,color_timestamp,tx,ty,tz,qx,qy,qz,qw,"));
  const auto csv = Rows(dir + "/c.csv", ',');
  REQUIRE(csv.size() == 4);  // every frame, both stamps
  CHECK(csv[2][1] == Approx(1.050).margin(1e-9));
  CHECK(csv[2][2] == Approx(1.066).margin(1e-9));
  CHECK(csv[2][3] == Approx(0.050).margin(1e-9));  // 0.066 moved back 16 ms
}

TEST_CASE("Stamped by colour, every frame is written at its colour time, as estimated") {
  const std::string dir = MakeTempDir("stamp_color");
  {
    TumTrajectoryWriter tum(dir + "/t.txt", StampTime::kColor);
    for (const FrameResult& r : Frames()) tum.Write(r);
    CHECK(tum.rows_left_out() == 0);
  }
  const auto tum = Rows(dir + "/t.txt", ' ');
  REQUIRE(tum.size() == 4);
  CHECK(tum[2][0] == Approx(1.066).margin(1e-9));
  CHECK(tum[2][1] == Approx(0.066).margin(1e-9));
  CHECK(Lines(dir + "/t.txt").front() ==
        "# timestamp tx ty tz qx qy qz qw (camera-to-world, rgbdvo)");
}
