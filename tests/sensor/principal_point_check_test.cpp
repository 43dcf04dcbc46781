#include "rgbdvo/sensor/principal_point_check.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

TEST_CASE("CheckPrincipalPoint finds a calibration read with images of another size") {
  Calibration fr1;  // TUM fr1, calibrated at 640x480
  fr1.cx = 318.6;
  fr1.cy = 255.3;
  CHECK_FALSE(CheckPrincipalPoint(fr1, 640, 480));
  const std::optional<std::string> half = CheckPrincipalPoint(fr1, 320, 240);
  REQUIRE(half);
  CHECK_THAT(*half, Catch::Contains("320x240"));
  CHECK_THAT(*half, Catch::Contains("another image size"));
  CHECK(CheckPrincipalPoint(fr1, 1280, 960));
  CHECK_FALSE(CheckPrincipalPoint(fr1, 0, 0));  // no image yet: nothing to say
  Calibration centred;  // a principal point at the very edge of the middle half still passes
  centred.cx = 319.5 + 160;
  centred.cy = 239.5;
  CHECK_FALSE(CheckPrincipalPoint(centred, 640, 480));
  centred.cx += 1;
  CHECK(CheckPrincipalPoint(centred, 640, 480));
}
