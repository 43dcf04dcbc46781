// End-to-end tests of `rgbdvo calibrate --auto`: a synthetic recording fitted, one warned of, one
// refused.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <string>

#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

TEST_CASE("rgbdvo calibrate --auto fits a registered synthetic recording from a perturbed start") {
  // Registered depth (same camera): the truth is the identity. The start is 3 % off in A and C
  // and 10 px in B and D. Measured: A = 0.99994, B = 0.10 px, C = 1.00016, D = -0.07 px (0.9 s).
  const std::string dir = MakeTempDir("autocal");
  const std::vector<Rigid3d> path = MakeSmoothPath(60);
  std::vector<Rigid3d> spread;
  for (size_t k = 0; k < path.size(); k += 10) spread.push_back(path[k]);
  WriteTumSequence(dir + "/rec", SyntheticScene(), PinholeCamera(), spread);
  Calibration base = CalibFor(PinholeCamera());
  base.A = 1.03, base.B = 10, base.C = 0.97, base.D = -10;
  SaveCalibration(base, dir + "/base.yaml");
  std::string out;
  const int code = RunCommand(RgbdvoExe() + " calibrate --auto " + dir + "/rec --calib " + dir +
                                  "/base.yaml --out " + dir + "/fit.yaml --png " + dir +
                                  "/fit.png --max-frames 6",
                              &out);
  INFO(out);
  REQUIRE(code == 0);
  CHECK_THAT(out, Catch::Contains("from 6 of 6 frames"));
  const Calibration fit = LoadCalibration(dir + "/fit.yaml");
  CHECK(std::abs(fit.A - 1) < 0.005);
  CHECK(std::abs(fit.C - 1) < 0.005);
  CHECK(std::abs(fit.B) < 1.5);
  CHECK(std::abs(fit.D) < 1.5);
  CHECK(fit.fx == base.fx);  // K_ir kept from the base
  CHECK_THAT(fit.description, Catch::Contains("calibrate --auto"));
  CHECK(PngSize(dir + "/fit.png") == std::make_pair(640, 480));
}

TEST_CASE("rgbdvo calibrate --auto warns that synth-kinect's one-block view leaves it uncertain") {
  // One block in view: outlines in two directions pin the mapping down to a few px only
  // (measured: corner 1-sigma 2.4 px, constraint ratio 0.05). The fit is written, with a warning,
  // and keeps the start's disparity term (kinect_v1_default, the start for a raw Kinect).
  const std::string dir = MakeTempDir("autocal");
  std::string out;
  REQUIRE(RunCommand(RgbdvoExe() + " synth-kinect " + dir + "/rec --frames 8", &out) == 0);
  const int code = RunCommand(
      RgbdvoExe() + " calibrate --auto " + dir + "/rec --out " + dir + "/fit.yaml", &out);
  INFO(out);
  CHECK(code == 0);
  CHECK_THAT(out, Catch::Contains("kinect_v1_default"));
  CHECK_THAT(out, Catch::Contains("warning: the fit is uncertain by"));
  REQUIRE(std::ifstream(dir + "/fit.yaml").good());
  CHECK(LoadCalibration(dir + "/fit.yaml").s_u == -14.625);
}

TEST_CASE("rgbdvo calibrate --auto refuses too few frames, naming the recording") {
  const std::string dir = MakeTempDir("autocal_few");
  std::string out;
  REQUIRE(RunCommand(RgbdvoExe() + " synth-kinect " + dir + "/rec --frames 2", &out) == 0);
  const int code = RunCommand(
      RgbdvoExe() + " calibrate --auto " + dir + "/rec --out " + dir + "/fit.yaml", &out);
  INFO(out);
  CHECK(code != 0);
  CHECK_THAT(out, Catch::Contains(dir + "/rec: only 2 of 2 frames"));
  CHECK_FALSE(std::ifstream(dir + "/fit.yaml").good());
}
