// End-to-end tests of `rgbdvo eval`, `rgbdvo plot` and `rgbdvo run --plot`.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "rgbdvo/io/trajectory_io.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;
namespace fs = std::filesystem;

namespace {

std::string Rgbdvo(const std::string& args, int* code) {
  std::string out;
  *code = RunCommand(RgbdvoExe() + " " + args, &out);
  return out;
}

}  // namespace

TEST_CASE("rgbdvo eval: ground truth against itself has zero error, --json is one object") {
  const std::string gt = SourceDir() + "/data/tum_fr1_xyz_first30/groundtruth.txt";
  int code = 0;
  std::string out = Rgbdvo("eval " + gt + " " + gt, &code);
  INFO(out);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::Contains("ATE (m)                   0.0000    0.0000"));
  CHECK_THAT(out, Catch::Contains("RPE trans (m/1s)"));
  out = Rgbdvo("eval " + gt + " " + gt + " --json --delta 0.5", &code);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::StartsWith("{\"groundtruth\": ") && Catch::Contains("\"delta_s\": 0.5") &&
                      Catch::Contains("\"rmse\": 0,"));
}

TEST_CASE("rgbdvo eval: several estimates give one row each, --json an array") {
  const std::string dir = MakeTempDir("cli_eval_multi");
  const std::string gt_path = SourceDir() + "/data/tum_fr1_xyz_first30/groundtruth.txt";
  const std::vector<StampedPose> gt = ReadTrajectory(gt_path).poses;
  // The ground truth at 80% scale and stamped 0.25 s early (another clock).
  std::vector<StampedPose> small = gt, early = gt;
  for (StampedPose& p : small) p.world_from_cam.translation() *= 0.8;
  for (StampedPose& p : early) p.timestamp -= 0.25;
  WriteTumTrajectory(dir + "/small.txt", small);
  WriteTumTrajectory(dir + "/early.txt", early);
  int code = 0;
  std::string out = Rgbdvo(
      "eval " + gt_path + " " + dir + "/small.txt " + dir + "/early.txt --align sim3", &code);
  INFO(out);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::Contains("alignment sim3"));
  CHECK_THAT(out, Catch::Contains(dir + "/small.txt ") && Catch::Contains(dir + "/early.txt "));
  CHECK_THAT(out, Catch::Contains("1.2500"));  // the scale that undoes 80%

  // --t-offset undoes the other clock: the early copy is the ground truth again.
  out = Rgbdvo("eval " + gt_path + " " + dir + "/early.txt --t-offset 0.25", &code);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::Contains("time offset:  +0.25 s"));
  CHECK_THAT(out, Catch::Contains("ATE (m)                   0.0000    0.0000"));

  out = Rgbdvo("eval " + gt_path + " " + dir + "/small.txt " + gt_path +
                   " --json --delta 10 --delta-unit frames --align scale",
               &code);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::StartsWith("[{\"groundtruth\": ") && Catch::EndsWith("}]\n"));
  CHECK_THAT(out, Catch::Contains("\"delta_unit\": \"frames\"") &&
                      Catch::Contains("\"delta_s\": null") && Catch::Contains("\"scale\": 1.25"));

  out = Rgbdvo("eval " + gt_path + " " + gt_path + " --align affine", &code);
  CHECK(code != 0);
  CHECK_THAT(out, Catch::Contains("affine"));
}

TEST_CASE("rgbdvo eval: a bad row is one error line naming file and line, exit 1") {
  const std::string dir = MakeTempDir("cli_eval");
  std::ofstream(dir + "/est.txt") << "# header\n1 0 0 0 0 0 0 1\n2 0 0 x 0 0 0 1\n";
  int code = 0;
  const std::string out = Rgbdvo("eval " + dir + "/est.txt " + dir + "/est.txt", &code);
  CHECK(code == 1);
  CHECK_THAT(out, Catch::StartsWith("rgbdvo: error: " + dir + "/est.txt:3:"));
}

TEST_CASE("rgbdvo plot and rgbdvo run --plot write PNG figures") {
  const std::string dir = MakeTempDir("cli_plot");
  WriteTumSequence(dir, SyntheticScene(), PinholeCamera(), MakeSmoothPath(5));
  std::ofstream(dir + "/calib.yaml")
      << "%YAML:1.0\n---\nA: 1.\nB: 0.\nC: 1.\nD: 0.\n"
         "K_ir: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
         "   data: [ 525., 0., 319.5, 0., 525., 239.5, 0., 0., 1. ]\n"
         "min_depth_m: 0.4\nmax_depth_m: 8.\n";
  int code = 0;
  std::string out = Rgbdvo(
      "run " + dir + " --calib " + dir + "/calib.yaml --quiet --plot " + dir + "/run.png", &code);
  INFO(out);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::Contains("estimate 5 poses, 5 poses matched with ground truth"));
  CHECK(fs::file_size(dir + "/run.png") > 20000);

  out = Rgbdvo(
      "plot " + dir + "/groundtruth.txt --gt " + dir + "/groundtruth.txt --png " + dir + "/gt.png",
      &code);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::Contains("ATE rmse 0.0000 m"));
  CHECK(fs::file_size(dir + "/gt.png") > 20000);
}

TEST_CASE("rgbdvo eval --plot, --plot-errors and --plot-xyz write PNG figures") {
  const std::string dir = MakeTempDir("cli_eval_plot");
  const std::string gt = SourceDir() + "/data/tum_fr1_xyz_first30/groundtruth.txt";
  int code = 0;
  std::string out =
      Rgbdvo("eval " + gt + " " + gt + " " + gt + " --plot " + dir + "/t.png --plot-errors " + dir +
                 "/e.png --plot-xyz " + dir + "/p.png --json",
             &code);
  INFO(out);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::Contains("wrote " + dir + "/t.png") &&
                      Catch::Contains("wrote " + dir + "/p.png"));
  for (const char* name : {"/t.png", "/e.png", "/p.png"}) CHECK(fs::file_size(dir + name) > 20000);
  // With --json the figures are reported on stderr: stdout is the JSON array alone.
  out.clear();
  code = RunCommand("(" + RgbdvoExe() + " eval " + gt + " " + gt + " " + gt + " --json --plot " +
                        dir + "/t2.png 2>/dev/null)",
                    &out);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::StartsWith("[{") && Catch::EndsWith("}]\n"));
}
