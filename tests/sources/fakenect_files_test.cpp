#include "rgbdvo/sources/fakenect_files.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

TEST_CASE("fakenect file names round-trip and parse as fakenect-record writes them") {
  const FakenectName n = MakeFakenectName('d', 1294139591394762, 1405006245u);
  CHECK(n.ToString() == "d-1294139591.394762-1405006245.pgm");
  CHECK(MakeFakenectName('r', 1700000000000005, 7).ToString() == "r-1700000000.000005-7.ppm");
  CHECK(MakeFakenectName('a', 1700000000000000, 7).ToString() == "a-1700000000.000000-7.dump");
  const auto p = ParseFakenectName("r-1294886363.011060-2857876922.ppm");  // NYU Depth V2 raw
  REQUIRE(p);
  CHECK(p->type == 'r');
  CHECK(p->wallclock_us == 1294886363011060);
  CHECK(p->device_ts == 2857876922u);
  CHECK(p->extension == "ppm");
  CHECK(p->seconds() == Approx(1294886363.011060));
  for (const char* bad : {"x-1.0-2.ppm", "r-abc-2.ppm", "r-1.0-.ppm", "r-1.0-2", "r1.0-2.ppm",
                          "r-1.0-99999999999.ppm", "INDEX.txt", ""})
    CHECK_FALSE(ParseFakenectName(bad));
}

TEST_CASE("ReadFakenectIndex tolerates CRLF line ends and blank lines") {
  const std::string dir = MakeTempDir("index");
  std::ofstream(dir + "/INDEX.txt", std::ios::binary)
      << "r-1.000000-1.ppm\r\n\r\n  \nd-1.001000-2.pgm\r\n\n";
  const std::vector<std::string> names = ReadFakenectIndex(dir + "/INDEX.txt");
  REQUIRE(names.size() == 2);
  CHECK(names[0] == "r-1.000000-1.ppm");
  CHECK(names[1] == "d-1.001000-2.pgm");
  CHECK_THROWS_WITH(ReadFakenectIndex(dir + "/none.txt"), Catch::Contains(dir + "/none.txt"));
}

TEST_CASE("fakenect depth is a one-line P5 header and little-endian 16-bit values") {
  const std::string dir = MakeTempDir("pgm");
  const uint16_t raw[6] = {0, 1, 0x0102, 2047, 759, 65535};
  WriteFakenectDepth(dir + "/d.pgm", raw, 3, 2);
  const std::string bytes = Slurp(dir + "/d.pgm");
  const std::string header = "P5 3 2 65535\n";
  REQUIRE(bytes.size() == header.size() + 12);
  CHECK(bytes.substr(0, header.size()) == header);
  CHECK(bytes[header.size() + 4] == '\x02');  // 0x0102, low byte first
  CHECK(bytes[header.size() + 5] == '\x01');
  const cv::Mat back = ReadFakenectDepth(dir + "/d.pgm");
  REQUIRE(back.type() == CV_16UC1);
  REQUIRE(back.size() == cv::Size(3, 2));
  for (int i = 0; i < 6; ++i) CHECK(back.at<uint16_t>(i / 3, i % 3) == raw[i]);
  // Never overwrites.
  CHECK_THROWS_WITH(WriteFakenectDepth(dir + "/d.pgm", raw, 3, 2), Catch::Contains(dir + "/d.pgm"));
}

TEST_CASE("fakenect colour is a one-line P6 header and RGB bytes, read back as BGR") {
  const std::string dir = MakeTempDir("ppm");
  const uint8_t rgb[6] = {10, 20, 30, 40, 50, 60};
  WriteFakenectColor(dir + "/r.ppm", rgb, 2, 1);
  CHECK(Slurp(dir + "/r.ppm") == std::string("P6 2 1 255\n") + "\x0a\x14\x1e\x28\x32\x3c");
  const cv::Mat bgr = ReadFakenectColor(dir + "/r.ppm");
  REQUIRE(bgr.type() == CV_8UC3);
  CHECK(bgr.at<cv::Vec3b>(0, 0) == cv::Vec3b(30, 20, 10));
  CHECK(bgr.at<cv::Vec3b>(0, 1) == cv::Vec3b(60, 50, 40));
  // A multi-line header with a comment (other writers) is read too.
  std::ofstream(dir + "/c.ppm", std::ios::binary) << "P6\n# comment\n1 1\n255\nabc";
  CHECK(ReadFakenectColor(dir + "/c.ppm").at<cv::Vec3b>(0, 0) == cv::Vec3b('c', 'b', 'a'));
}

TEST_CASE("truncated, missing or wrong-kind fakenect images are errors naming the file") {
  const std::string dir = MakeTempDir("bad");
  const uint16_t raw[4] = {1, 2, 3, 4};
  WriteFakenectDepth(dir + "/d.pgm", raw, 2, 2);
  fs::resize_file(dir + "/d.pgm", fs::file_size(dir + "/d.pgm") - 1);
  CHECK_THROWS_WITH(ReadFakenectDepth(dir + "/d.pgm"),
                    Catch::Contains(dir + "/d.pgm") && Catch::Contains("truncated"));
  fs::resize_file(dir + "/d.pgm", 5);
  CHECK_THROWS_WITH(ReadFakenectDepth(dir + "/d.pgm"), Catch::Contains(dir + "/d.pgm"));
  CHECK_THROWS_WITH(ReadFakenectColor(dir + "/missing.ppm"),
                    Catch::Contains(dir + "/missing.ppm") && Catch::Contains("missing"));
  const uint8_t rgb[3] = {1, 2, 3};
  WriteFakenectColor(dir + "/r.ppm", rgb, 1, 1);
  CHECK_THROWS_WITH(ReadFakenectDepth(dir + "/r.ppm"),
                    Catch::Contains(dir + "/r.ppm") && Catch::Contains("P5"));
  CHECK_THROWS_WITH(ReadFakenectColor(dir + "/d.pgm"), Catch::Contains(dir + "/d.pgm"));
}
