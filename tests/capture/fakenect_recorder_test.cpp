#include "rgbdvo/capture/fakenect_recorder.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "rgbdvo/sources/fakenect_files.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

TEST_CASE("FakenectRecorder lists each complete file in INDEX.txt in arrival order") {
  const std::string dir = MakeTempDir("rec") + "/new/recording";  // parents are created
  FakenectRecorder rec(dir);
  const uint8_t rgb[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  const uint16_t raw[4] = {500, 600, 2047, 0};
  const char accel[12] = "accelerate";
  rec.AddColor(1700000000000000, 10, rgb, 2, 2);
  rec.AddDepth(1700000000001000, 20, raw, 2, 2);
  rec.AddAccel(1700000000001200, 20, accel, sizeof(accel));
  CHECK(rec.entries() == 3);
  const std::vector<std::string> names = ReadFakenectIndex(dir + "/INDEX.txt");
  REQUIRE(names.size() == 3);
  CHECK(names[0] == "r-1700000000.000000-10.ppm");
  CHECK(names[1] == "d-1700000000.001000-20.pgm");
  CHECK(names[2] == "a-1700000000.001200-20.dump");
  CHECK(ReadFakenectDepth(dir + "/" + names[1]).at<uint16_t>(1, 0) == 2047);
  CHECK(ReadFakenectColor(dir + "/" + names[0]).at<cv::Vec3b>(1, 1) == cv::Vec3b(12, 11, 10));
  CHECK(fs::file_size(dir + "/" + names[2]) == sizeof(accel));
}

TEST_CASE("FakenectRecorder never overwrites: a non-empty folder or a file is refused") {
  const std::string dir = MakeTempDir("rec_exists");
  std::ofstream(dir + "/INDEX.txt") << "r-1.000000-1.ppm\n";
  CHECK_THROWS_WITH(FakenectRecorder(dir), Catch::Contains(dir) && Catch::Contains("refusing"));
  CHECK_THROWS_WITH(FakenectRecorder(dir + "/INDEX.txt"), Catch::Contains("INDEX.txt"));
  std::ifstream in(dir + "/INDEX.txt");
  std::string line;
  std::getline(in, line);
  CHECK(line == "r-1.000000-1.ppm");  // untouched
  // An existing empty folder is fine.
  const std::string empty = MakeTempDir("rec_empty");
  FakenectRecorder ok(empty);
  CHECK(fs::exists(empty + "/INDEX.txt"));
}
