#include "rgbdvo/sensor/calibration_catalog.hpp"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/util/temp_dir.hpp"

using namespace rgbdvo;

namespace {

// Sets RGBDVO_CALIB_PATH for one test and restores it afterwards.
class CalibPathEnv {
 public:
  explicit CalibPathEnv(const std::string& value) {
    if (const char* old = std::getenv("RGBDVO_CALIB_PATH")) old_ = old;
    // NOLINTNEXTLINE(concurrency-mt-unsafe): no other thread runs here
    setenv("RGBDVO_CALIB_PATH", value.c_str(), 1);
  }
  ~CalibPathEnv() {
    if (old_)
      // NOLINTNEXTLINE(concurrency-mt-unsafe): no other thread runs here
      setenv("RGBDVO_CALIB_PATH", old_->c_str(), 1);
    else
      // NOLINTNEXTLINE(concurrency-mt-unsafe): no other thread runs here
      unsetenv("RGBDVO_CALIB_PATH");
  }

 private:
  std::optional<std::string> old_;
};

std::string SaveNamed(const std::string& folder, const std::string& name, double fx) {
  Calibration c;
  c.fx = fx;
  c.description = "camera " + name;
  std::string path = folder + "/" + name + ".yaml";
  SaveCalibration(c, path);
  return path;
}

}  // namespace

TEST_CASE("A calibration name finds NAME.yaml in the folders of RGBDVO_CALIB_PATH") {
  const ScopedTempDir dir("rgbdvo_catalog_");
  const std::string path = SaveNamed(dir.path(), "my_camera", 512.5);
  const CalibPathEnv env("/nonexistent/folder:" + dir.path());
  CHECK(FindCalibration("my_camera") == path);
  CHECK(FindCalibration("my_camera.yaml") == path);
  CHECK(LoadCalibration(FindCalibration("my_camera")).fx == 512.5);
}

TEST_CASE("The first folder of the search path wins over the built-in calibrations") {
  const ScopedTempDir dir("rgbdvo_catalog_");
  const std::string path = SaveNamed(dir.path(), "tum_fr1", 600);
  const CalibPathEnv env(dir.path());
  CHECK(FindCalibration("tum_fr1") == path);
  // The source tree's calibrations are still listed, after the user's.
  const std::vector<CalibrationEntry> list = ListCalibrations();
  bool own = false, paper = false;
  for (const CalibrationEntry& e : list) {
    if (e.name == "tum_fr1") own = e.path == path && e.description == "camera tum_fr1";
    if (e.name == "fiala_ufkes_2011") paper = true;
  }
  CHECK(own);
  CHECK(paper);
}

TEST_CASE("A path to an existing file is taken as it is") {
  const ScopedTempDir dir("rgbdvo_catalog_");
  const std::string path = SaveNamed(dir.path(), "elsewhere", 500);
  CHECK(FindCalibration(path) == path);
}

TEST_CASE("An unknown calibration name or a missing path is an error naming it") {
  const ScopedTempDir dir("rgbdvo_catalog_");
  const CalibPathEnv env(dir.path());
  CHECK_THROWS_WITH(FindCalibration("no_such_camera"),
                    Catch::Contains("'no_such_camera'") && Catch::Contains(dir.path()));
  CHECK_THROWS_WITH(FindCalibration(dir.path() + "/missing.yaml"), Catch::Contains("missing.yaml"));
  CHECK_THROWS(FindCalibration(""));
}
