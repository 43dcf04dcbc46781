#include "rgbdvo/calibration.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

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
}

TEST_CASE("Shipped calibration files load") {
  for (const char* name : {"tum_fr1", "tum_fr2", "tum_fr3", "fiala_ufkes_2011"}) {
    INFO(name);
    const Calibration c = LoadCalibration(test::SourceDir() + "/calib/" + name + ".yaml");
    CHECK(c.fx > 400);
  }
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
