#include "rgbdvo/sources/accelerometer_track.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "rgbdvo/sources/tum_source.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
namespace fs = std::filesystem;

TEST_CASE("A frame's gravity is the mean of the readings within half a frame period") {
  const AccelerometerTrack track({{1.010, {0, 10, 0}},
                                  {0.990, {0, 8, 0}},
                                  {1.000, {0, 9, 3}},
                                  {1.030, {0, 100, 0}}});  // beyond 1/60 s of 1.0
  const std::optional<Eigen::Vector3d> g = track.GravityAt(1.0);
  REQUIRE(g);
  CHECK(g->isApprox(Eigen::Vector3d(0, 9, 1)));
}

TEST_CASE("Without a reading within the frame, the nearest within a period, else none") {
  const AccelerometerTrack track({{1.0, {0, 9, 0}}, {1.2, {0, 8, 0}}});
  REQUIRE(track.GravityAt(1.025));  // 25 ms from 1.0: outside the frame, within a period
  CHECK(track.GravityAt(1.025)->y() == 9);
  REQUIRE(track.GravityAt(1.17));
  CHECK(track.GravityAt(1.17)->y() == 8);
  CHECK_FALSE(track.GravityAt(1.1));  // 0.1 s from both
  CHECK_FALSE(AccelerometerTrack().GravityAt(1.0));
}

TEST_CASE("TUM's accelerometer.txt is read in the camera frame, bad lines name the line") {
  const std::string dir = test::MakeTempDir("accel");
  {
    std::ofstream out(dir + "/accelerometer.txt");
    out << "# accelerometer data\r\n# timestamp ax ay az\n\n1.5 0.1 7.2 -6.6\r\n";
  }
  const std::vector<AccelReading> r = ReadTumAccelerometer(dir + "/accelerometer.txt");
  REQUIRE(r.size() == 1);
  CHECK(r[0].timestamp == 1.5);
  CHECK(r[0].gravity_in_cam.isApprox(Eigen::Vector3d(0.1, 7.2, 6.6)));
  {
    std::ofstream out(dir + "/bad.txt");
    out << "1.5 0.1 7.2 -6.6\n1.6 0.1 nan 2\n";
  }
  CHECK_THROWS_WITH(ReadTumAccelerometer(dir + "/bad.txt"), Catch::Contains("bad.txt:2"));
  CHECK_THROWS_WITH(ReadTumAccelerometer(dir + "/none.txt"), Catch::Contains("none.txt"));
}

TEST_CASE("TumSource gives frames their gravity when asked, and needs accelerometer.txt then") {
  const std::string dir = test::MakeTempDir("tumaccel");
  fs::create_directories(dir + "/rgb");
  fs::create_directories(dir + "/depth");
  cv::imwrite(dir + "/rgb/0.png", cv::Mat(48, 64, CV_8UC3, cv::Scalar(10, 20, 30)));
  cv::imwrite(dir + "/depth/0.png", cv::Mat(48, 64, CV_16UC1, cv::Scalar(5000)));
  std::ofstream(dir + "/rgb.txt") << "1.0 rgb/0.png\n";
  std::ofstream(dir + "/depth.txt") << "1.001 depth/0.png\n";
  TumSourceOptions options;
  CHECK_FALSE(TumSource(dir, options).Next()->gravity_in_cam);  // not asked: not read
  options.accelerometer = true;
  CHECK_THROWS_WITH(TumSource(dir, options), Catch::Contains("no accelerometer.txt"));
  std::ofstream(dir + "/accelerometer.txt") << "0.995 0 9.8 0.1\n1.005 0 9.6 0.3\n";
  TumSource source(dir, options);
  CHECK_THAT(source.Describe(), Catch::Contains("2 accelerometer readings"));
  const std::optional<Frame> f = source.Next();
  REQUIRE(f);
  REQUIRE(f->gravity_in_cam);
  CHECK(f->gravity_in_cam->isApprox(Eigen::Vector3d(0, 9.7, -0.2)));
}
