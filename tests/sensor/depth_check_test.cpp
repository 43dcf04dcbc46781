// The depth scale's plausibility check.
#include "rgbdvo/sensor/depth_check.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include "rgbdvo/sensor/depth_encoding.hpp"
#include "rgbdvo/sources/tum_source.hpp"
#include "rgbdvo/synthetic/synthetic.hpp"
#include "test_support.hpp"

using namespace rgbdvo;

namespace {

// The first depth image of the bundled fr1/xyz excerpt (16-bit, 5000 units per metre).
cv::Mat FirstDepthRaw() {
  const std::string dir = test::SourceDir() + "/data/tum_fr1_xyz_first30";
  const std::vector<TumListEntry> list = ReadTumList(dir + "/depth.txt");
  REQUIRE_FALSE(list.empty());
  cv::Mat raw = cv::imread(dir + "/" + list.front().path, cv::IMREAD_UNCHANGED);
  REQUIRE(raw.type() == CV_16UC1);
  return raw;
}

}  // namespace

TEST_CASE("CheckDepthScale finds a Kinect recording read at the wrong depth scale") {
  const cv::Mat raw = FirstDepthRaw();
  const Calibration calib = LoadCalibration(test::SourceDir() + "/calib/tum_fr1.yaml");
  CHECK_FALSE(CheckDepthScale(DepthFromScaled16(raw, 5000), calib));  // right: no message
  CHECK_FALSE(CheckDepthScale(DepthFromScaled16(raw, 4000), calib));  // within a factor 1.5
  // 1000 units per metre: every depth 5 times too large, still mostly within the 8 m range,
  // but the steps between depth values are a fifth of a Kinect's at those depths.
  const std::optional<std::string> large = CheckDepthScale(DepthFromScaled16(raw, 1000), calib);
  REQUIRE(large);
  CHECK_THAT(*large, Catch::Contains("5.00 times too large") && Catch::Contains("by 5.00"));
  const std::optional<std::string> small = CheckDepthScale(DepthFromScaled16(raw, 25000), calib);
  REQUIRE(small);
  CHECK_THAT(*small, Catch::Contains("5.00 times too small") && Catch::Contains("by 0.20"));
}

TEST_CASE("CheckDepthScale: even steps are no Kinect's, depths out of range are reported") {
  // The synthetic world's depth is exact (no z^2 steps): nothing to say at the right range.
  const SyntheticScene scene;
  const PinholeCamera cam;
  const cv::Mat depth = scene.RenderDepth(cam, Rigid3d::Identity());
  const Calibration calib = test::CalibFor(cam);
  CHECK_FALSE(CheckDepthScale(depth, calib));
  // The same depth 10 times too far: most readings beyond the calibration's max_depth_m.
  const std::optional<std::string> far = CheckDepthScale(depth * 10, calib);
  REQUIRE(far);
  CHECK_THAT(*far, Catch::Contains("above the calibration's range"));
  CHECK_FALSE(CheckDepthScale(cv::Mat::zeros(480, 640, CV_32FC1), calib));  // no readings
}
