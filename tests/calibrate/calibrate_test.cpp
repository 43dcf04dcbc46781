// `rgbdvo calibrate` without a window: ApplyMappingFit, the outputs and the --pairs CLI.
#include "rgbdvo/calibrate/calibrate.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "rgbdvo/calibrate/pixel_pairs_file.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

namespace {

// Pairs of u_ir = 0.9 u_vis + 20, v_ir = 0.95 v_vis + 10, exact.
std::vector<PixelPair> ExactPairs() {
  std::vector<PixelPair> pairs;
  for (double u : {50.0, 300.0, 600.0})
    for (double v : {40.0, 420.0}) pairs.push_back({u, v, 0.9 * u + 20, 0.95 * v + 10});
  return pairs;
}

}  // namespace

TEST_CASE("The fitted calibration round-trips through YAML and keeps the base's other fields") {
  Calibration base;
  base.fx = 580.5, base.fy = 579.5, base.cx = 317.25, base.cy = 242.75;
  base.min_depth_m = 0.6, base.max_depth_m = 4.0;
  base.dist_ir = {0.1, -0.2, 0.001, -0.002, 0.05};
  base.description = "my kinect";
  const MappingFit fit = FitMapping({}, ExactPairs());
  REQUIRE(fit.success);
  const std::string dir = MakeTempDir("calibrate");
  const std::string msg =
      WriteCalibrateOutputs(ExactPairs(), fit, base, dir + "/c.yaml", dir + "/c.pairs.csv");
  CHECK(msg == "wrote 6 pairs to " + dir + "/c.pairs.csv; wrote " + dir + "/c.yaml");
  const Calibration c = LoadCalibration(dir + "/c.yaml");
  CHECK(c.A == Approx(0.9).epsilon(1e-12));
  CHECK(c.B == Approx(20).epsilon(1e-12));
  CHECK(c.C == Approx(0.95).epsilon(1e-12));
  CHECK(c.D == Approx(10).epsilon(1e-12));
  CHECK(c.fx == base.fx);
  CHECK(c.fy == base.fy);
  CHECK(c.cx == base.cx);
  CHECK(c.cy == base.cy);
  CHECK(c.dist_ir == base.dist_ir);
  CHECK(c.min_depth_m == base.min_depth_m);
  CHECK(c.max_depth_m == base.max_depth_m);
  CHECK_THAT(c.description,
             Catch::StartsWith("A-D fitted by rgbdvo calibrate from 6 pairs (c.pairs.csv)") &&
                 Catch::EndsWith("Other fields: my kinect"));
  CHECK(LoadPixelPairs(dir + "/c.pairs.csv").size() == 6);
}

TEST_CASE("A failed fit writes the pairs but no calibration, and says why") {
  const std::vector<PixelPair> two = {{0, 0, 1, 1}, {100, 100, 91, 91}};
  const MappingFit fit = FitMapping({}, two);
  const std::string dir = MakeTempDir("calibrate");
  const std::string msg = WriteCalibrateOutputs(two, fit, {}, dir + "/c.yaml", dir + "/p.csv");
  CHECK_THAT(msg, Catch::EndsWith("calibration not written: need at least 3 pairs, have 2"));
  CHECK_FALSE(fs::exists(dir + "/c.yaml"));
  CHECK(fs::exists(dir + "/p.csv"));
  CHECK_THROWS_WITH(ApplyMappingFit({}, fit, ""), Catch::Contains("the fit failed"));
}

TEST_CASE("FitReport lists each pair's residual and marks outliers") {
  auto pairs = ExactPairs();
  pairs[2].v_ir += 30;
  MappingFitOptions o;
  o.robust = true;
  const std::string report = FitReport(FitMapping(o, pairs), pairs);
  CHECK_THAT(report, Catch::Contains("from 5 of 6 pairs (1 outlier(s) set aside)"));
  CHECK_THAT(report,
             Catch::Contains("   3   300.0    40.0   290.0    78.0     30.00  outlier (not used)"));
  CHECK_THAT(report, Catch::Contains("   1    50.0    40.0    65.0    48.0      0.00\n"));
}

TEST_CASE("DefaultPairsPath puts the pairs beside the calibration") {
  CHECK(DefaultPairsPath("out/calib.yaml") == "out/calib.pairs.csv");
  CHECK(DefaultPairsPath("calib") == "calib.pairs.csv");
}

TEST_CASE("rgbdvo calibrate --pairs writes a calibration that rgbdvo run accepts") {
  const std::string dir = MakeTempDir("cli_calibrate");
  // Identity pairs: the TUM excerpt's depth is registered to the colour image.
  std::vector<PixelPair> pairs;
  for (double u : {40.0, 320.0, 600.0})
    for (double v : {30.0, 450.0}) pairs.push_back({u, v, u, v});
  SavePixelPairs(pairs, dir + "/pairs.csv");
  std::string out;
  REQUIRE(RunCommand(RgbdvoExe() + " calibrate --pairs " + dir + "/pairs.csv --out " + dir +
                         "/c.yaml --calib " + SourceDir() + "/calib/tum_fr1.yaml",
                     &out) == 0);
  CHECK_THAT(out, Catch::Contains("A=1 B=0 C=1 D=0 from 6 of 6 pairs, RMS 0 px"));
  CHECK_THAT(out, Catch::Contains("wrote " + dir + "/c.yaml"));
  CHECK_THAT(out, Catch::Contains("K_ir, distortion, depth range: from " + SourceDir() +
                                  "/calib/tum_fr1.yaml"));
  const Calibration c = LoadCalibration(dir + "/c.yaml");
  CHECK(c.fx == 517.3);  // from the base calibration

  // Without --calib the paper's K_ir is kept, and said so; a calibration name works as a path.
  REQUIRE(RunCommand(
              RgbdvoExe() + " calibrate --pairs " + dir + "/pairs.csv --out " + dir + "/paper.yaml",
              &out) == 0);
  CHECK_THAT(out, Catch::Contains("K_ir, depth range: the paper's (fx = fy = 475"));
  CHECK(LoadCalibration(dir + "/paper.yaml").fx == 475);
  REQUIRE(RunCommand(RgbdvoExe() + " calibrate --pairs " + dir + "/pairs.csv --out " + dir +
                         "/named.yaml --calib tum_fr1",
                     &out) == 0);
  CHECK(LoadCalibration(dir + "/named.yaml").fx == 517.3);

  // A 3-frame copy of the excerpt, run with the new calibration.
  const std::string rec = dir + "/rec", data = SourceDir() + "/data/tum_fr1_xyz_first30";
  fs::create_directories(rec);
  fs::create_directory_symlink(data + "/rgb", rec + "/rgb");
  fs::create_directory_symlink(data + "/depth", rec + "/depth");
  for (const std::string list : {"rgb.txt", "depth.txt"}) {
    std::ifstream in(data + "/" + list);
    std::ofstream o(rec + "/" + list);
    int kept = 0;
    for (std::string line; std::getline(in, line) && kept < 3;) {
      if (line.empty() || line[0] == '#') continue;
      o << line << "\n", ++kept;
    }
  }
  REQUIRE(RunCommand(RgbdvoExe() + " run " + rec + " --calib " + dir + "/c.yaml --csv " + dir +
                         "/t.csv --quiet",
                     &out) == 0);
  CHECK_THAT(out, Catch::Contains("3 frames"));
}

TEST_CASE("rgbdvo calibrate --pairs: too few, degenerate and bad files are clear errors") {
  const std::string dir = MakeTempDir("cli_calibrate");
  std::string out;
  SavePixelPairs({{0, 0, 1, 1}, {100, 100, 91, 91}}, dir + "/two.csv");
  CHECK(RunCommand(RgbdvoExe() + " calibrate --pairs " + dir + "/two.csv --out " + dir + "/c.yaml",
                   &out) == 1);
  CHECK_THAT(out,
             Catch::Contains("rgbdvo: error: " + dir + "/two.csv: need at least 3 pairs, have 2"));
  CHECK_FALSE(fs::exists(dir + "/c.yaml"));

  SavePixelPairs({{50, 0, 60, 5}, {50, 100, 60, 95}, {50, 200, 60, 185}}, dir + "/same_u.csv");
  CHECK(
      RunCommand(RgbdvoExe() + " calibrate --pairs " + dir + "/same_u.csv --out " + dir + "/c.yaml",
                 &out) == 1);
  CHECK_THAT(out, Catch::Contains("degenerate pairs: u_vis spans 0 px"));

  std::ofstream(dir + "/bad.csv") << "u_vis,v_vis,u_ir,v_ir\n1,2,3,4\n5,6,seven,8\n";
  CHECK(RunCommand(RgbdvoExe() + " calibrate --pairs " + dir + "/bad.csv --out " + dir + "/c.yaml",
                   &out) == 1);
  CHECK_THAT(out, Catch::Contains("rgbdvo: error: " + dir + "/bad.csv:3: 'seven' is not a number"));

  CHECK(RunCommand(RgbdvoExe() + " calibrate --out " + dir + "/c.yaml", &out) != 0);
  CHECK_THAT(out, Catch::Contains("give a SOURCE folder (window) or --pairs FILE"));
}

TEST_CASE("rgbdvo calibrate SOURCE without a display is a clear error") {
  const std::string dir = MakeTempDir("cli_calibrate");
  std::string out;
  CHECK(RunCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + RgbdvoExe() + " calibrate " +
                       SourceDir() + "/data/tum_fr1_xyz_first30 --out " + dir + "/c.yaml",
                   &out) == 1);
  CHECK_THAT(out, Catch::Contains("rgbdvo: error: no display"));
}
