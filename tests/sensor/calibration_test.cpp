#include "rgbdvo/sensor/calibration.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_support.hpp"

using namespace rgbdvo;

TEST_CASE("Calibration YAML round-trips every field") {
  Calibration c;
  c.A = 0.93;
  c.B = -12.5;
  c.C = 1.02;
  c.D = 3.25;
  c.fx = 580.1;
  c.fy = 581.2;
  c.cx = 314.5;
  c.cy = 245.5;
  c.min_depth_m = 0.6;
  c.max_depth_m = 4.5;
  c.description = "test sensor";
  c.dist_ir = {0.26, -0.95, -0.005, 0.0026, 1.16};
  c.depth_units_per_m = 5000;
  const std::string path = test::MakeTempDir("calib") + "/c.yaml";
  SaveCalibration(c, path);
  const Calibration r = LoadCalibration(path);
  CHECK(r.A == c.A);
  CHECK(r.B == c.B);
  CHECK(r.C == c.C);
  CHECK(r.D == c.D);
  CHECK(r.fx == c.fx);
  CHECK(r.fy == c.fy);
  CHECK(r.cx == c.cx);
  CHECK(r.cy == c.cy);
  CHECK(r.min_depth_m == c.min_depth_m);
  CHECK(r.max_depth_m == c.max_depth_m);
  CHECK(r.description == c.description);
  CHECK(r.dist_ir == c.dist_ir);
  CHECK(r.depth_units_per_m == 5000);
  // Optional: a file without it says 0 (not given); a non-positive one is an error.
  Calibration plain = c;
  plain.depth_units_per_m = 0;
  SaveCalibration(plain, path);
  CHECK(LoadCalibration(path).depth_units_per_m == 0);
  std::ofstream(path, std::ios::app) << "depth_units_per_m: -5.\n";
  CHECK_THROWS_WITH(LoadCalibration(path), Catch::Contains("depth_units_per_m"));
}

TEST_CASE("Shipped calibration files load") {
  for (const char* name : {"tum_fr1", "tum_fr2", "tum_fr3", "fiala_ufkes_2011"}) {
    INFO(name);
    const Calibration c = LoadCalibration(test::SourceDir() + "/calib/" + name + ".yaml");
    CHECK(c.fx > 400);
  }
  for (const char* name : {"tum_fr1", "tum_fr2", "tum_fr3"})
    CHECK(LoadCalibration(test::SourceDir() + "/calib/" + name + ".yaml").depth_units_per_m ==
          5000);
  const Calibration paper = LoadCalibration(test::SourceDir() + "/calib/fiala_ufkes_2011.yaml");
  CHECK(paper.fx == 475);
  CHECK(paper.fy == 475);
  CHECK(paper.cx == 320);
  CHECK(paper.cy == 240);
}

TEST_CASE("Bad calibration files fail naming the file and field") {
  const std::string dir = test::MakeTempDir("badcalib");
  CHECK_THROWS_WITH(LoadCalibration(dir + "/missing.yaml"), Catch::Contains("missing.yaml"));
  const std::string no_a = dir + "/no_a.yaml";
  std::ofstream(no_a) << "%YAML:1.0\n---\nB: 0.\nC: 1.\nD: 0.\n";
  CHECK_THROWS_WITH(LoadCalibration(no_a), Catch::Contains("no_a.yaml") && Catch::Contains("'A'"));
  const std::string garbage = dir + "/garbage.yaml";
  std::ofstream(garbage) << "this is : not : yaml : [\n";
  CHECK_THROWS_WITH(LoadCalibration(garbage), Catch::Contains("garbage.yaml"));
  Calibration c;
  c.fx = -1;
  CHECK_THROWS_WITH(c.Check(), Catch::Contains("fx"));
  c = {};
  c.max_depth_m = c.min_depth_m;
  CHECK_THROWS_WITH(c.Check(), Catch::Contains("max_depth_m"));
}

TEST_CASE("Calibration matrices are checked against their shape before anything is allocated") {
  const std::string dir = test::MakeTempDir("badcalib");
  const std::string head = "%YAML:1.0\n---\nA: 1.\nB: 0.\nC: 1.\nD: 0.\n";
  const std::string tail = "min_depth_m: 0.4\nmax_depth_m: 8.\n";
  const auto matrix = [](const std::string& key, const std::string& rows, const std::string& cols,
                         const std::string& data) {
    return key + ": !!opencv-matrix\n   rows: " + rows + "\n   cols: " + cols +
           "\n   dt: d\n   data: [ " + data + " ]\n";
  };
  const std::string k9 = "517.3, 0., 318.6, 0., 516.5, 255.3, 0., 0., 1.";
  struct Case {
    std::string name, yaml, expected;
  };
  const std::vector<Case> cases = {
      // OpenCV's reader would allocate 8 * 2e9 * 2e9 bytes for these.
      {"huge", head + matrix("K_ir", "2000000000", "2000000000", k9) + tail, "it is 2000000000x"},
      {"wide", head + matrix("K_ir", "3", "1000000000", k9) + tail, "3x1000000000"},
      {"negative", head + matrix("K_ir", "-3", "-3", k9) + tail, "it is -3x-3"},
      {"short", head + matrix("K_ir", "3", "3", "1., 2.") + tail, "9 numbers"},
      {"text", head + "K_ir: [ 1, 2 ]\n" + tail, "not a matrix"},
      {"dist",
       head + matrix("K_ir", "3", "3", k9) + matrix("dist_ir", "100000", "100000", "0.") + tail,
       "'dist_ir' must be a 1x5"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string path = dir + "/" + c.name + ".yaml";
    std::ofstream(path) << c.yaml;
    CHECK_THROWS_WITH(LoadCalibration(path),
                      Catch::Contains(c.name + ".yaml") && Catch::Contains(c.expected));
  }
  // A 5x1 dist_ir is the same as 1x5.
  const std::string column = dir + "/column.yaml";
  std::ofstream(column) << head + matrix("K_ir", "3", "3", k9) +
                               matrix("dist_ir", "5", "1", "0.1, 0.2, 0.3, 0.4, 0.5") + tail;
  CHECK(LoadCalibration(column).dist_ir[4] == 0.5);
  // A file far larger than any calibration is refused before it is parsed.
  const std::string big = dir + "/big.yaml";
  std::ofstream(big) << head << std::string(2 << 20, ' ') << "\n";
  CHECK_THROWS_WITH(LoadCalibration(big), Catch::Contains("big.yaml") && Catch::Contains("1 MiB"));
}

TEST_CASE("A calibration file with control bytes is refused before OpenCV's parser sees it") {
  // The input tests/fuzz found: OpenCV's YAML reader loops forever on it (a NUL at offset 45).
  const std::string finding =
      test::SourceDir() + "/tests/fuzz/corpus/calibration/findings/opencv_yaml_hang_on_nul.yaml";
  CHECK_THROWS_WITH(LoadCalibration(finding),
                    Catch::Contains("not a text file") && Catch::Contains("0x00 at offset 45"));
  // CRLF line ends are text.
  const std::string dir = test::MakeTempDir("calib_text");
  std::string yaml;
  for (const std::string line : {"%YAML:1.0", "---", "A: 1.", "B: 0.", "C: 1.", "D: 0.",
                                 "K_ir: !!opencv-matrix", "   rows: 3", "   cols: 3", "   dt: d",
                                 "   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]",
                                 "min_depth_m: 0.4", "max_depth_m: 8."})
    yaml += line + "\r\n";
  std::ofstream(dir + "/crlf.yaml", std::ios::binary) << yaml;
  CHECK(LoadCalibration(dir + "/crlf.yaml").fx == 500);
}

TEST_CASE("Calibration files are read by their own reader: syntax errors name the line") {
  const std::string dir = test::MakeTempDir("calib_syntax");
  const std::string head = "%YAML:1.0\n---\nA: 1.\nB: 0.\nC: 1.\nD: 0.\n";
  const std::string k =
      "K_ir: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
      "   data: [ 500., 0., 320.,  # a comment\n       0., 500., 240., 0., 0., 1. ]\n";
  const std::string tail = "min_depth_m: 0.4\nmax_depth_m: 8.\n";
  const auto load = [&](const std::string& text) {
    std::ofstream(dir + "/c.yaml") << text;
    return LoadCalibration(dir + "/c.yaml");
  };
  // A list over two lines, a comment inside it, a quoted description with '#' and '"'.
  const Calibration c = load(head + k + tail + "description: \"cam \\\"7\\\" # left\"\n");
  CHECK(c.fx == 500);
  CHECK(c.cy == 240);
  CHECK(c.description == "cam \"7\" # left");
  // An indented line with no matrix above it (OpenCV's reader looped forever on one such file).
  CHECK_THROWS_WITH(load(head + "   rows: 3\n  4, -0.95 ]\n" + tail),
                    Catch::Contains("c.yaml:7") && Catch::Contains("indented line"));
  CHECK_THROWS_WITH(load(head + "K_ir: !!opencv-matrix\n   data: [ 1., 2.\n"),
                    Catch::Contains("unterminated"));
  CHECK_THROWS_WITH(load(head + "A: 2.\n" + k + tail), Catch::Contains("'A' given twice"));
  CHECK_THROWS_WITH(load(head + "just text\n"), Catch::Contains("c.yaml:7"));
}

TEST_CASE("A ROS camera_info YAML file is read as the camera of registered depth") {
  const std::string dir = test::MakeTempDir("camera_info");
  // As ROS's camera_calibration writes it (ost.yaml), with an 8-coefficient model.
  const std::string path = dir + "/rgb.yaml";
  std::ofstream(path) << "image_width: 640\nimage_height: 480\ncamera_name: rgb_A00362\n"
                         "camera_matrix:\n  rows: 3\n  cols: 3\n"
                         "  data: [517.3, 0, 318.6, 0, 516.5, 255.3, 0, 0, 1]\n"
                         "distortion_model: rational_polynomial\n"
                         "distortion_coefficients:\n  rows: 1\n  cols: 8\n"
                         "  data: [0.2624, -0.9531, -0.0054, 0.0026, 1.1633, 0, 0, 0]\n"
                         "rectification_matrix:\n  rows: 3\n  cols: 3\n"
                         "  data: [1, 0, 0,\n         0, 1, 0,\n         0, 0, 1]\n"
                         "projection_matrix:\n  rows: 3\n  cols: 4\n"
                         "  data: [517.3, 0, 318.6, 0, 0, 516.5, 255.3, 0, 0, 0, 1, 0]\n";
  const Calibration c = LoadCalibration(path);
  CHECK(c.fx == 517.3);
  CHECK(c.fy == 516.5);
  CHECK(c.cx == 318.6);
  CHECK(c.cy == 255.3);
  CHECK(c.dist_ir == std::array<double, 5>{0.2624, -0.9531, -0.0054, 0.0026, 1.1633});
  CHECK((c.A == 1 && c.B == 0 && c.C == 1 && c.D == 0));
  CHECK(c.min_depth_m == Calibration().min_depth_m);
  CHECK_THAT(c.description, Catch::Contains("rgb_A00362"));

  std::ofstream(dir + "/fisheye.yaml")
      << "camera_matrix:\n  rows: 3\n  cols: 3\n  data: [500, 0, 320, 0, 500, 240, 0, 0, 1]\n"
         "distortion_model: equidistant\n";
  CHECK_THROWS_WITH(LoadCalibration(dir + "/fisheye.yaml"),
                    Catch::Contains("fisheye.yaml") && Catch::Contains("equidistant"));
  std::ofstream(dir + "/bad_k.yaml") << "camera_matrix:\n  rows: 3\n  cols: 3\n  data: [500, 0]\n";
  CHECK_THROWS_WITH(LoadCalibration(dir + "/bad_k.yaml"),
                    Catch::Contains("bad_k.yaml") && Catch::Contains("camera_matrix"));

  // A shape its data does not fill: cols edited to 14 with 5 coefficients left.
  std::ofstream(dir + "/cols.yaml")
      << "camera_matrix:\n  rows: 3\n  cols: 3\n  data: [500, 0, 320, 0, 500, 240, 0, 0, 1]\n"
         "distortion_model: plumb_bob\n"
         "distortion_coefficients:\n  rows: 1\n  cols: 14\n  data: [0.1, 0, 0, 0, 0]\n";
  CHECK_THROWS_WITH(LoadCalibration(dir + "/cols.yaml"),
                    Catch::Contains("cols.yaml:6: field 'distortion_coefficients' has 5 values") &&
                        Catch::Contains("rows 1, cols 14"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("The disparity term round-trips and is 0 when a file leaves it out") {
  Calibration c;
  c.s_u = -14.625;
  c.s_v = 0.25;
  const std::string path = test::MakeTempDir("calib_s") + "/c.yaml";
  SaveCalibration(c, path);
  const Calibration r = LoadCalibration(path);
  CHECK(r.s_u == c.s_u);
  CHECK(r.s_v == c.s_v);
  CHECK(r.HasDisparityTerm());
  const Calibration plain = LoadCalibration(test::SourceDir() + "/calib/tum_fr1.yaml");
  CHECK(plain.s_u == 0);
  CHECK(plain.s_v == 0);
  CHECK_FALSE(plain.HasDisparityTerm());
  SaveCalibration(Calibration{}, path);
  std::ofstream(path, std::ios::app) << "s_u: west\n";
  CHECK_THROWS_WITH(LoadCalibration(path), Catch::Contains("s_u"));
}
