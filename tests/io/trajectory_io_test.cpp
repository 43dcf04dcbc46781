// Reading TUM and rgbdvo CSV trajectories, and the errors for bad files.
#include "rgbdvo/io/trajectory_io.hpp"

#include <catch2/catch.hpp>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "rgbdvo/io/text.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

namespace {

std::string WriteFile(const std::string& name, const std::string& text) {
  std::string path = MakeTempDir("traj_io") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string ErrorOf(const std::string& path) {
  try {
    ReadTrajectory(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("TUM and rgbdvo CSV files with the same poses read the same") {
  const std::string tum = WriteFile("t.txt",
                                    "# timestamp tx ty tz qx qy qz qw\n"
                                    "1.5 0.1 0.2 0.3 0 0 0.7071068 0.7071068\n"
                                    "\n"
                                    "1.0 0 0 0 0 0 0 1\n");
  const std::string csv = WriteFile("t.csv",
                                    "frame,timestamp,tx,ty,tz,qx,qy,qz,qw,matches,inliers,status\n"
                                    "0,1.0,0,0,0,0,0,0,1,0,0,first\n"
                                    "1,1.5,0.1,0.2,0.3,0,0,0.7071068,0.7071068,90,80,accepted\n");
  const Trajectory a = ReadTrajectory(tum), b = ReadTrajectory(csv);
  CHECK(a.format == TrajectoryFormat::kTum);
  CHECK(b.format == TrajectoryFormat::kCsv);
  REQUIRE(a.poses.size() == 2);
  REQUIRE(b.poses.size() == 2);
  CHECK(a.poses[0].timestamp == 1.0);  // sorted by time
  for (int k = 0; k < 2; ++k) {
    CHECK(a.poses[k].timestamp == b.poses[k].timestamp);
    CHECK(RigidNear(a.poses[k].world_from_cam, b.poses[k].world_from_cam, 1e-9, 1e-12));
  }
  const Rigid3d& T = a.poses[1].world_from_cam;
  CHECK(T.translation().isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  CHECK(RotationAngleDeg(T.linear()) == Approx(90).epsilon(1e-6));  // 90 deg about z
  CHECK(T.linear()(1, 0) == Approx(1).epsilon(1e-6));
}

TEST_CASE("CSV columns are found by the header, in any order") {
  const std::string csv = WriteFile("t.csv",
                                    "qw,status,tz,ty,tx,timestamp,qz,qy,qx\n"
                                    "1,first,3,2,1,7.25,0,0,0\n");
  const Trajectory t = ReadTrajectory(csv);
  REQUIRE(t.poses.size() == 1);
  CHECK(t.poses[0].timestamp == 7.25);
  CHECK(t.poses[0].world_from_cam.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST_CASE("Of rows with the same timestamp the last one is kept, as in the TUM tools") {
  const std::string path = WriteFile("dup.txt",
                                     "2 5 0 0 0 0 0 1\n"
                                     "1 1 0 0 0 0 0 1\n"
                                     "1 2 0 0 0 0 0 1\n"
                                     "3 6 0 0 0 0 0 1\n"
                                     "1 3 0 0 0 0 0 1\n");
  const Trajectory t = ReadTrajectory(path);
  CHECK(t.repeated_timestamps == 2);
  REQUIRE(t.poses.size() == 3);
  CHECK(t.poses[0].timestamp == 1);
  CHECK(t.poses[0].world_from_cam.translation().x() == 3);  // the last row stamped 1
  CHECK(t.poses[1].world_from_cam.translation().x() == 5);
  CHECK(t.poses[2].world_from_cam.translation().x() == 6);
}

TEST_CASE("A written TUM trajectory reads back") {
  std::mt19937 rng(3);
  std::vector<StampedPose> poses;
  poses.reserve(5);
  for (int k = 0; k < 5; ++k) poses.push_back({10 + 0.1 * k, RandomRigid(rng, 0.5, 1.0)});
  const std::string path = MakeTempDir("traj_io") + "/w.txt";
  WriteTumTrajectory(path, poses);
  const Trajectory t = ReadTrajectory(path);
  REQUIRE(t.poses.size() == 5);
  for (int k = 0; k < 5; ++k) {
    CHECK(t.poses[k].timestamp == Approx(poses[k].timestamp).margin(1e-6));
    CHECK(RigidNear(t.poses[k].world_from_cam, poses[k].world_from_cam, 1e-4, 2e-6));
  }
}

TEST_CASE("Bad trajectory rows are errors naming file and line") {
  std::string path = WriteFile("short.txt", "# c\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
  CHECK_THAT(ErrorOf(path), Catch::Contains(path + ":3:") && Catch::Contains("found 7"));

  path = WriteFile("nan.txt", "1 0 0 abc 0 0 0 1\n");
  CHECK_THAT(ErrorOf(path),
             Catch::Contains(path + ":1:") && Catch::Contains("tz: 'abc' is not a number"));

  path = WriteFile("inf.txt", "1 0 0 0 0 0 0 1\n2 inf 0 0 0 0 0 1\n3 0 nan 0 0 0 0 1\n");
  CHECK_THAT(ErrorOf(path),
             Catch::Contains(path + ":2:") && Catch::Contains("tx: 'inf' is not finite"));

  path = WriteFile("zero_q.txt", "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 0\n");
  CHECK_THAT(ErrorOf(path), Catch::Contains(path + ":2:") && Catch::Contains("zero norm"));

  path = WriteFile("bad.csv", "frame,timestamp,tx,ty,tz,qx,qy,qz,qw\n0,1,0,0,0,0,0,0,1\n1,2,0,0\n");
  CHECK_THAT(ErrorOf(path), Catch::Contains(path + ":3:"));

  path = WriteFile("nocol.csv", "frame,timestamp,tx,ty,tz,qx,qy,qz\n0,1,0,0,0,0,0,0\n");
  CHECK_THAT(ErrorOf(path), Catch::Contains(path + ":1:") && Catch::Contains("'qw'"));
}

TEST_CASE("Empty and missing trajectory files are errors naming the file") {
  std::string path = WriteFile("empty.txt", "");
  CHECK_THAT(ErrorOf(path), Catch::Contains(path) && Catch::Contains("no poses"));
  path = WriteFile("header_only.csv", "frame,timestamp,tx,ty,tz,qx,qy,qz,qw\n");
  CHECK_THAT(ErrorOf(path), Catch::Contains("no poses"));
  CHECK_THAT(ErrorOf("/nonexistent/t.txt"), Catch::Contains("/nonexistent/t.txt"));
}

TEST_CASE("A TUM line has fixed decimals whatever the stream's format") {
  Rigid3d T = Rigid3d::Identity();
  T.translation() = Eigen::Vector3d(1.5, -0.25, 1e-7);
  std::ostringstream out;
  out << std::scientific << std::setprecision(2);
  WriteTumLine(out, 1305031102.175304, T);
  CHECK(out.str() ==
        "1305031102.175304 1.500000 -0.250000 0.000000 0.0000000 0.0000000 "
        "0.0000000 1.0000000\n");
  out << 0.5;  // the caller's format is left as it was
  CHECK(out.str().substr(out.str().size() - 8) == "5.00e-01");
}

TEST_CASE("ParseNumber refuses what is not a whole finite number, naming the place") {
  CHECK(ParseNumber(" 2.5\t", "f:1") == 2.5);
  CHECK_THROWS_WITH(ParseNumber("4px", "f:2"), "f:2: '4px' is not a number");
  CHECK_THROWS_WITH(ParseNumber("", "f:3"), "f:3: '' is not a number");
  CHECK_THROWS_WITH(ParseNumber("1e999", "f:4"), "f:4: '1e999' is not finite");
  CHECK_THROWS_WITH(ParseNumber("nan", "f:5"), "f:5: 'nan' is not finite");
  CHECK(Trim(" \t a b \r\n") == "a b");
}
